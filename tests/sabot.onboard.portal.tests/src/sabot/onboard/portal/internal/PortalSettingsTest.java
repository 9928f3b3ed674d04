package sabot.onboard.portal.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.osgi.framework.FrameworkUtil;

import sabot.onboard.task.InvalidSettings;
import sabot.onboard.task.TaskSettingsCheck.Problem;
import sabot.testsupport.osgi.TaskMetatype;

/** The portal's settings: Metatype defaults are the code's, and what Metatype cannot say is checked. */
class PortalSettingsTest {

    @Test
    void metatypeDefaultsAreTheCodesDefaults() throws Exception {
        Map<String, String> d = TaskMetatype.defaults(FrameworkUtil.getBundle(PortalTask.class), "sabot.task.portal");
        PortalSettings s = PortalSettings.of(Map.of());
        assertEquals(PortalSettings.DEFAULT_BIND, d.get("bind"));
        assertEquals(s.port(), Integer.parseInt(d.get("port")));
        assertEquals(s.sessionTimeout().toSeconds(), Long.parseLong(d.get("sessionTimeout")));
        assertEquals(s.throttle().failures(), Integer.parseInt(d.get("loginFailures")));
        assertEquals(s.throttle().window().toSeconds(), Long.parseLong(d.get("loginWindow")));
        assertEquals(s.poll().toMillis(), Long.parseLong(d.get("pollInterval")));
        assertEquals(s.requestTimeout().toSeconds(), Long.parseLong(d.get("requestTimeout")));
        assertEquals("false", d.get("tls"));
        assertNull(s.tls());
    }

    @Test
    void thePagesAddressIsTheBindAddressOrTheConfiguredOne() {
        assertEquals("http://127.0.0.1:8081/", PortalSettings.of(Map.of("bind", "127.0.0.1", "port", 8081)).url());
        assertEquals("http://robot-1.lab:8080/", PortalSettings.of(Map.of("bind", "0.0.0.0", "address",
                "robot-1.lab")).url());
    }

    @Test
    void httpsNeedsReadableCertificateAndKeyAndAHostNameIsNoBindAddress(@TempDir Path dir) throws Exception {
        assertEquals(List.of(new Problem("certificateFile", "HTTPS is on (tls = true): this file must be given"),
                new Problem("keyFile", "HTTPS is on (tls = true): this file must be given")), PortalSettings.problems(
                        Map.of("tls", true)));
        assertEquals(List.of(new Problem("bind", "'robot.lab' is not an IP address")), PortalSettings.problems(Map.of(
                "bind", "robot.lab")));
        Path junk = Files.writeString(dir.resolve("junk.pem"), "not a certificate");
        List<Problem> p = PortalSettings.problems(Map.of("tls", true, "certificateFile", junk.toString(), "keyFile",
                junk.toString()));
        assertEquals(1, p.size(), p.toString());
        assertTrue(p.get(0).message().startsWith("cannot use " + junk), p.get(0).message());
        assertThrows(InvalidSettings.class, () -> PortalSettings.of(Map.of("port", 0)));
        assertEquals(List.of(new Problem("requestTimeout", "'0' is outside 1..300")), PortalSettings.problems(Map.of(
                "requestTimeout", 0)));
    }

    @Test
    void aLabCaCertificateAndKeyMakeATlsContext(@TempDir Path dir) throws Exception {
        Path key = dir.resolve("robot.key");
        Path crt = dir.resolve("robot.crt");
        Process openssl = new ProcessBuilder("openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt",
                "ec_paramgen_curve:prime256v1", "-nodes", "-days", "2", "-subj", "/CN=robot.sabot.local", "-keyout",
                key.toString(), "-out", crt.toString()).redirectErrorStream(true).start();
        assertTrue(openssl.waitFor(30, TimeUnit.SECONDS) && openssl.exitValue() == 0, new String(openssl
                .getInputStream().readAllBytes()));
        PortalSettings s = PortalSettings.of(Map.of("tls", true, "certificateFile", crt.toString(), "keyFile", key
                .toString(), "port", 8443, "bind", "127.0.0.1"));
        assertEquals("https://127.0.0.1:8443/", s.url());
        assertEquals("TLS", PemIdentity.load(s.tls()).getProtocol());
        char[] password = "p".toCharArray(); // the store written for Jetty: the key under its alias, with the chain
        java.security.KeyStore store = PemIdentity.keyStore(s.tls(), password);
        assertTrue(store.isKeyEntry(PemIdentity.ALIAS));
        assertEquals("CN=robot.sabot.local", ((java.security.cert.X509Certificate) store.getCertificate(
                PemIdentity.ALIAS)).getSubjectX500Principal().getName());
        assertTrue(store.getKey(PemIdentity.ALIAS, password) instanceof java.security.PrivateKey);
    }

    @Test
    void theThrottleRefusesAfterTheFailuresAllowedUntilTheOldestLeavesTheWindow() {
        long[] now = { 0 };
        LoginThrottle t = new LoginThrottle(new LoginThrottle.Limits(3, Duration.ofSeconds(60)), () -> now[0]);
        for (int i = 0; i < 3; i++) {
            assertEquals(Duration.ZERO, t.wait("10.0.0.1", "alice@lab"));
            t.failed("10.0.0.1", "alice@lab");
            now[0] += TimeUnit.SECONDS.toNanos(1);
        }
        assertEquals(Duration.ofSeconds(57), t.wait("10.0.0.1", "alice@lab"), "the same client and account");
        assertEquals(Duration.ofSeconds(57), t.wait("10.0.0.2", "alice@lab"), "the account from elsewhere");
        assertEquals(Duration.ofSeconds(57), t.wait("10.0.0.1", "bob@lab"), "another account from the client");
        assertEquals(Duration.ZERO, t.wait("10.0.0.2", "bob@lab"), "somebody else");
        now[0] += TimeUnit.SECONDS.toNanos(57);
        assertEquals(Duration.ZERO, t.wait("10.0.0.1", "alice@lab"), "the oldest failure left the window");
    }

    @Test
    void sessionsEndAfterTheirIdleTimeoutAndAtLogOutAndCheckTheirCsrfToken() {
        long[] now = { 0 };
        PortalSessions sessions = new PortalSessions(Duration.ofSeconds(60), () -> now[0]);
        PortalSessions.Session s = sessions.open("alice@lab");
        assertEquals(43, s.id().length(), "256 random bits, base64url");
        assertTrue(s.csrfMatches(s.csrf()));
        assertTrue(!s.csrfMatches(null) && !s.csrfMatches("") && !s.csrfMatches(s.id()));
        now[0] += TimeUnit.SECONDS.toNanos(59);
        assertTrue(sessions.find(s.id()).isPresent(), "used within the timeout: its idle time restarts");
        now[0] += TimeUnit.SECONDS.toNanos(59);
        assertTrue(sessions.find(s.id()).isPresent());
        now[0] += TimeUnit.SECONDS.toNanos(60);
        assertTrue(sessions.find(s.id()).isEmpty(), "idle for the timeout");
        PortalSessions.Session t = sessions.open("bob@lab");
        sessions.close(t.id());
        assertTrue(sessions.find(t.id()).isEmpty());
        for (int i = 0; i < PortalSessions.MAX_SESSIONS + 5; i++) {
            sessions.open("user" + i + "@lab");
        }
        assertEquals(PortalSessions.MAX_SESSIONS, sessions.size());
    }

    @Test
    void formsAreParsedStrictly() throws Exception {
        assertEquals(Map.of("a", "1 2", "b", "é&"), PortalRoutes.parseForm("a=1+2&b=%C3%A9%26"));
        assertEquals(Map.of("a", ""), PortalRoutes.parseForm("a="));
        for (String bad : List.of("a=%zz", "a", "=1", "a=1&a=2", "a=1&&b=2")) {
            PortalRoutes.HttpError e = assertThrows(PortalRoutes.HttpError.class, () -> PortalRoutes.parseForm(bad),
                    bad);
            assertEquals(400, e.status, bad);
        }
        assertEquals(400, assertThrows(PortalRoutes.HttpError.class, () -> PortalRoutes.parseForm("a=1&".repeat(
                PortalRoutes.MAX_FIELDS + 1))).status);
    }

    @Test
    void textIsEscapedForHtmlAndJson() {
        assertEquals("&lt;script&gt;&amp;&quot;&#39;", Html.esc("<script>&\"'"));
        assertEquals("\"\\u003c/script>\\n\"", Json.write("</script>\n"));
        assertEquals("[1,0.5000,true,null]", Json.write(java.util.Arrays.asList(1, 0.5, true, null)));
    }
}
