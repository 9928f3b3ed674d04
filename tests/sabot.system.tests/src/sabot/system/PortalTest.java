package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.io.InputStream;
import java.net.ServerSocket;
import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.HttpRequest;
import java.net.http.HttpResponse;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.KeyStore;
import java.security.cert.CertificateFactory;
import java.time.Duration;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import javax.net.ssl.SSLContext;
import javax.net.ssl.SSLSocket;
import javax.net.ssl.TrustManagerFactory;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.Goal;
import sabot.identity.DeviceCard;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.IdentityResult;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.OnboardProcess;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The robot's web page (docs/PORTAL.md) over HTTPS with the lab CA's certificate, on the product driving the
 * simulated robot, with a plain HTTP client: log-in with the robot's XMPP accounts and roles, the pose changing while
 * the robot drives, a setting changed and applied, refusals (a bad value with the configuration's error text, a forged
 * form, an observer), bad input (413, path traversal, malformed forms, wrong methods, unknown settings), the log-in
 * throttle, log-out; the robot still drives after all of it, and its vCard's URL is the page.
 */
class PortalTest extends RigTest {

    /** The page's poll interval in the tests (the default's). */
    static final int POLL_MS = 250;
    /** How long a request's body may take in the tests: short, so that the test of slow clients does not wait long. */
    static final int REQUEST_TIMEOUT_S = 2;
    static final Pattern CSRF = Pattern.compile("name=\"csrf\" value=\"([A-Za-z0-9_-]+)\"");
    static final Pattern POSE_X = Pattern.compile("\"pose\":\\{\"x\":(-?[0-9.]+)");
    static final Pattern BATTERY_SOC = Pattern.compile("\"battery\":\\{\"stateOfCharge\":([0-9.E-]+)");

    /**
     * @return the portal's extra configuration lines: HTTPS on 127.0.0.1 with the lab CA's certificate of this computer
     *         (localhost, 127.0.0.1), on a free port
     */
    static String portalConfig(PrivateXmppServer xmpp, int port) {
        Path certs = xmpp.runDir().resolve("certs");
        return "tasks = " + OnboardProcess.TASKS + ", portal\n"
                + "portal.bind = 127.0.0.1\n"
                + "portal.port = " + port + "\n"
                + "portal.tls = true\n"
                + "portal.certificateFile = " + certs.resolve("localhost.crt") + "\n"
                + "portal.keyFile = " + certs.resolve("localhost.key") + "\n"
                + "portal.pollInterval = " + POLL_MS + "\n"
                + "portal.requestTimeout = " + REQUEST_TIMEOUT_S + "\n";
    }

    static int freePort() throws IOException {
        try (ServerSocket s = new ServerSocket(0)) {
            return s.getLocalPort();
        }
    }

    /**
     * An HTTP client that trusts the lab CA only (and checks the name: 127.0.0.1) and follows no redirect (the test
     * reads each 303).
     */
    static HttpClient client(PrivateXmppServer xmpp) throws Exception {
        return HttpClient.newBuilder().sslContext(labTls(xmpp)).followRedirects(HttpClient.Redirect.NEVER)
                .connectTimeout(Duration.ofSeconds(5)).build();
    }

    /** @return a TLS context that trusts the lab CA only */
    static SSLContext labTls(PrivateXmppServer xmpp) throws Exception {
        KeyStore trust = KeyStore.getInstance("PKCS12");
        trust.load(null, null);
        try (InputStream in = Files.newInputStream(xmpp.caFile())) {
            trust.setCertificateEntry("lab-ca", CertificateFactory.getInstance("X.509").generateCertificate(in));
        }
        TrustManagerFactory tmf = TrustManagerFactory.getInstance(TrustManagerFactory.getDefaultAlgorithm());
        tmf.init(trust);
        SSLContext tls = SSLContext.getInstance("TLS");
        tls.init(null, tmf.getTrustManagers(), null);
        return tls;
    }

    /**
     * A client that sends a request's start and then nothing more: its headers complete and part of a body
     * ({@code body} true), or half a header.
     */
    static final class SlowClient implements AutoCloseable {
        final SSLSocket socket;

        SlowClient(SSLContext tls, int port, boolean body) throws IOException {
            socket = (SSLSocket) tls.getSocketFactory().createSocket("127.0.0.1", port);
            socket.startHandshake();
            String start = body ? "POST /logout HTTP/1.1\r\nHost: 127.0.0.1:" + port + "\r\nContent-Type: "
                    + "application/x-www-form-urlencoded\r\nContent-Length: 100\r\n\r\ncsrf=slow"
                    : "GET /api/status HTTP/1.1\r\nHost: 127.0.0.1";
            socket.getOutputStream().write(start.getBytes(StandardCharsets.US_ASCII));
            socket.getOutputStream().flush();
        }

        /** @return the status line the server has sent, null when it has sent nothing within {@code waitMs} */
        String statusLine(int waitMs) throws IOException {
            socket.setSoTimeout(waitMs);
            try {
                StringBuilder line = new StringBuilder();
                int c;
                while ((c = socket.getInputStream().read()) >= 0 && c != '\r') {
                    line.append((char) c);
                }
                return line.toString();
            } catch (java.net.SocketTimeoutException nothingYet) {
                return null;
            }
        }

        /** Sends the rest of the announced body. */
        void finish() throws IOException {
            String rest = "&x=";
            socket.getOutputStream().write((rest + "x".repeat(100 - "csrf=slow".length() - rest.length())).getBytes(
                    StandardCharsets.US_ASCII));
            socket.getOutputStream().flush();
        }

        @Override
        public void close() throws IOException {
            socket.close();
        }
    }

    /** One person's browser: the base address, the session cookie once logged in. */
    record Browser(HttpClient http, String base, String cookie) {

        HttpResponse<String> get(String path) throws Exception {
            return send(HttpRequest.newBuilder(URI.create(base + path)).GET());
        }

        HttpResponse<String> post(String path, String form) throws Exception {
            return send(HttpRequest.newBuilder(URI.create(base + path)).header("Content-Type",
                    "application/x-www-form-urlencoded").POST(HttpRequest.BodyPublishers.ofString(form)));
        }

        HttpResponse<String> send(HttpRequest.Builder request) throws Exception {
            if (cookie != null) {
                request.header("Cookie", cookie);
            }
            return http.send(request.timeout(Duration.ofSeconds(20)).build(), HttpResponse.BodyHandlers.ofString());
        }

        Browser logIn(String account, String password) throws Exception {
            HttpResponse<String> r = post("/login", "account=" + enc(account) + "&password=" + enc(password));
            assertEquals(303, r.statusCode(), r.body());
            String setCookie = r.headers().firstValue("Set-Cookie").orElseThrow();
            return new Browser(http, base, setCookie.substring(0, setCookie.indexOf(';')));
        }

        String csrf() throws Exception {
            Matcher m = CSRF.matcher(get("/").body());
            assertTrue(m.find(), "no CSRF token on the status page");
            return m.group(1);
        }
    }

    static String enc(String s) {
        return java.net.URLEncoder.encode(s, StandardCharsets.UTF_8);
    }

    static double poseX(Browser b) throws Exception {
        HttpResponse<String> r = b.get("/api/status");
        assertEquals(200, r.statusCode(), r.body());
        Matcher m = POSE_X.matcher(r.body());
        assertTrue(m.find(), r.body());
        return Double.parseDouble(m.group(1));
    }

    @Test
    void theRobotsPageLogsInByRoleShowsItDrivingChangesASettingAndRefusesBadInputWhileTheRobotDrives(
            @TempDir Path dir) throws Exception {
        int port = freePort();
        try (RobotRig rig = RobotRig.start(xmpp, dir, CORRIDOR_WEST, new String[0], portalConfig(xmpp, port))) {
            String url = "https://127.0.0.1:" + port + "/";
            rig.onboard.await(l -> l.contains("portal task started: the robot's page at " + url), "serving its page");
            xmpp.login("observer");
            xmpp.grant(JidCreate.bareFrom("observer@" + PrivateXmppServer.DOMAIN), Role.OBSERVER);
            Browser anonymous = new Browser(client(xmpp), "https://127.0.0.1:" + port, null);
            String maintainer = RobotRig.OPERATOR + "@" + PrivateXmppServer.DOMAIN; // a maintainer (RobotRig)

            // the vCard's URL is the page
            DeviceIdentityManager identity = DeviceIdentityManager.getInstanceFor(rig.operatorConnection);
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(20);
            String published = null;
            while (System.nanoTime() < deadline) {
                IdentityResult<DeviceCard> card = identity.fetch(JidCreate.entityBareFrom(rig.robot.asBareJid()));
                if (card instanceof IdentityResult.Ok<DeviceCard> ok && ok.value().profile().portal() != null) {
                    published = ok.value().profile().portal().toString();
                    break;
                }
                TimeUnit.MILLISECONDS.sleep(100); // polling the server's stored vCard: no event to wait on
            }
            assertEquals(url, published, "the vCard's URL");

            // not logged in: the log-in page; a wrong password: refused
            HttpResponse<String> first = anonymous.get("/");
            assertEquals(303, first.statusCode());
            assertEquals("/login", first.headers().firstValue("Location").orElseThrow());
            assertEquals(401, anonymous.get("/api/status").statusCode());
            HttpResponse<String> wrong = anonymous.post("/login", "account=" + enc(maintainer) + "&password=nope");
            assertEquals(401, wrong.statusCode());
            assertTrue(wrong.body().contains("wrong account or password"), wrong.body());

            // the maintainer logs in: a Secure, HttpOnly, SameSite=Strict cookie
            HttpResponse<String> in = anonymous.post("/login", "account=" + enc(maintainer) + "&password=" + enc(
                    PrivateXmppServer.DEFAULT_PASSWORD));
            assertEquals(303, in.statusCode(), in.body());
            String setCookie = in.headers().firstValue("Set-Cookie").orElseThrow();
            for (String attribute : List.of("HttpOnly", "SameSite=Strict", "Secure", "Path=/")) {
                assertTrue(setCookie.contains(attribute), setCookie);
            }
            Browser m = anonymous.logIn(maintainer, PrivateXmppServer.DEFAULT_PASSWORD);
            HttpResponse<String> page = m.get("/");
            assertEquals(200, page.statusCode());
            assertEquals("max-age=31536000", page.headers().firstValue("Strict-Transport-Security").orElseThrow());
            assertTrue(page.headers().firstValue("Content-Security-Policy").orElseThrow().contains("script-src 'self'"));
            assertTrue(page.body().contains(RobotRig.ROBOT) && page.body().contains("(maintainer)"), page.body());
            String status = m.get("/api/status").body();
            for (String part : List.of("\"jid\":\"sabot-01@sabot.local\"", "\"uuid\":\"urn:uuid:", "\"page\":\"" + url,
                    "\"online\":true", "\"name\":\"motion\"", "\"name\":\"portal\"", "\"role\":\"maintainer\"")) {
                assertTrue(status.contains(part), part + " in " + status);
            }
            assertTrue(m.get("/map.svg").body().startsWith("<svg"));

            // the battery as the power board measures it (about once a second), as the simulator has it
            Matcher soc = BATTERY_SOC.matcher("");
            long batteryBy = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
            while (!(soc = BATTERY_SOC.matcher(m.get("/api/status").body())).find() && System.nanoTime() < batteryBy) {
                TimeUnit.MILLISECONDS.sleep(POLL_MS); // as the page's script polls
            }
            assertTrue(soc.find(0), "no battery in " + m.get("/api/status").body());
            Matcher truth = Pattern.compile("soc=([0-9.]+)").matcher(rig.sim.command("battery 1"));
            assertTrue(truth.find(), "the simulator's battery truth");
            assertEquals(Double.parseDouble(truth.group(1)), Double.parseDouble(soc.group(1)), 0.01,
                    "the page's state of charge against the simulator's");

            // clients that send slowly hold no thread: more of them than Jetty's threads, bodies and headers
            // unfinished, and the page still answers at once; each slow body is answered (408) after its time
            SSLContext tls = labTls(xmpp);
            List<SlowClient> slow = new java.util.ArrayList<>();
            for (int i = 0; i < 12; i++) {
                slow.add(new SlowClient(tls, port, i % 2 == 0));
            }
            assertEquals(200, m.get("/api/status").statusCode());
            assertTrue(m.get("/").body().contains(RobotRig.ROBOT));
            for (SlowClient c : slow) {
                assertEquals(null, c.statusLine(1), "a slow client was answered before its request was complete");
            }
            SlowClient finished = slow.get(0);
            finished.finish();
            assertEquals("HTTP/1.1 401 Unauthorized", finished.statusLine(20_000), "a slow body, complete");

            // the robot drives: the page's pose follows it
            double x0 = poseX(m);
            var goal = rig.operator.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(8.0, 1.0, 0), 0.15, 0.3));
            assertTrue(goal.isSuccess(), "goal refused: " + goal.errorOrNull());
            awaitSpeed(rig.sim, 0.1, 15);
            deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(20);
            double x = x0;
            while (x < x0 + 0.3 && System.nanoTime() < deadline) {
                TimeUnit.MILLISECONDS.sleep(POLL_MS); // as the page's script polls: a busy loop would starve the robot
                x = poseX(m);
            }
            assertTrue(x >= x0 + 0.3, "the page's pose stayed at " + x + " from " + x0);

            // a setting changed: written to the file and applied (the task restarts with it)
            Path conf = rig.onboard.config();
            String csrf = m.csrf();
            HttpResponse<String> changed = m.post("/config", "csrf=" + csrf + "&task=remotefs&s.readOnly=true");
            assertEquals(200, changed.statusCode(), changed.body());
            assertTrue(changed.body().contains("task &#39;remotefs&#39; restarts with its new settings"), changed
                    .body());
            assertTrue(Files.readString(conf).contains("\nremotefs.readOnly = true\n"), Files.readString(conf));
            rig.onboard.await(l -> l.contains("remote FS task started") && l.contains("read-only"),
                    "restarting remotefs read-only");

            // refused, nothing written: a bad value (the configuration's own text), an unknown setting, no CSRF token
            byte[] before = Files.readAllBytes(conf);
            HttpResponse<String> bad = m.post("/config", "csrf=" + csrf + "&task=remotefs&s.maxChunk=0");
            assertEquals(400, bad.statusCode());
            assertTrue(bad.body().contains("key &#39;remotefs.maxChunk&#39;: &#39;0&#39; is below the minimum 1"), bad
                    .body());
            HttpResponse<String> unknown = m.post("/config", "csrf=" + csrf + "&task=remotefs&s.bogus=1");
            assertEquals(400, unknown.statusCode());
            assertTrue(unknown.body().contains("task &#39;remotefs&#39; has no setting &#39;bogus&#39;"), unknown
                    .body());
            HttpResponse<String> forged = m.post("/config", "task=remotefs&s.readOnly=false");
            assertEquals(403, forged.statusCode());
            assertTrue(forged.body().contains("CSRF token is missing or wrong"), forged.body());
            assertEquals(403, m.post("/config", "csrf=" + csrf.substring(1) + "x&task=remotefs&s.readOnly=false")
                    .statusCode());

            // an observer reads, changes nothing
            Browser o = anonymous.logIn("observer@" + PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
            assertEquals(200, o.get("/api/status").statusCode());
            assertFalse(o.get("/").body().contains("href=\"/config\""));
            assertEquals(403, o.get("/config").statusCode());
            assertEquals(403, o.post("/config", "csrf=" + o.csrf() + "&task=remotefs&s.readOnly=false").statusCode());

            // bad input: a clear error each
            SimProcess.Truth driving = rig.sim.truth();
            assertEquals(413, m.post("/config", "csrf=" + csrf + "&task=remotefs&s.root=" + "a".repeat(20_000))
                    .statusCode());
            assertEquals(400, m.send(HttpRequest.newBuilder(URI.create(m.base() + "/static/../../etc/passwd")).GET())
                    .statusCode());
            assertEquals(400, m.get("/static/%2e%2e/%2e%2e/etc/passwd").statusCode());
            assertEquals(404, m.get("/etc/passwd").statusCode());
            assertEquals(400, m.post("/config", "csrf=" + csrf + "&task=remotefs&s.readOnly=%zz").statusCode());
            assertEquals(400, m.post("/config", "csrf=" + csrf + "&task=remotefs&noequals").statusCode());
            assertEquals(400, m.post("/config", "csrf=" + csrf + "&csrf=" + csrf + "&task=remotefs").statusCode());
            HttpResponse<String> delete = m.send(HttpRequest.newBuilder(URI.create(m.base() + "/config")).DELETE());
            assertEquals(405, delete.statusCode());
            assertEquals("GET, POST", delete.headers().firstValue("Allow").orElseThrow());
            assertEquals(405, m.send(HttpRequest.newBuilder(URI.create(m.base() + "/")).PUT(HttpRequest.BodyPublishers
                    .ofString("x"))).statusCode());
            assertEquals(415, m.send(HttpRequest.newBuilder(URI.create(m.base() + "/config")).header("Content-Type",
                    "text/plain").POST(HttpRequest.BodyPublishers.ofString("csrf=" + csrf))).statusCode());
            assertEquals(400, m.post("/config", "csrf=" + csrf + "&task=nosuchtask&s.a=1").statusCode());
            assertTrue(java.util.Arrays.equals(before, Files.readAllBytes(conf)), "the file changed");

            // the product is alive and still drives: it takes the next goal and moves (a new goal replaces the
            // mission under way; on a machine so loaded that the loop braked for lack of odometry, it ends that fault)
            assertEquals(200, m.get("/api/status").statusCode());
            // (a mission of two targets: the page lists them with their states)
            var next = rig.operator.set(rig.robot, Resources.MISSION, MissionTest.start(List.of(MissionTest.target(
                    8.5, 1.0, 0, sabot.controlml.payload.MissionTarget.Action.PASS, 0), MissionTest.target(7.0, 1.0,
                            Math.PI, sabot.controlml.payload.MissionTarget.Action.STOP, 0))));
            assertTrue(next.isSuccess(), "mission refused after the bad input: " + next.errorOrNull());
            String listed = "\"targets\":[{\"x\":8.5000,\"y\":1.0000,\"action\":\"pass\",\"state\":\"active\"},"
                    + "{\"x\":7.0000,\"y\":1.0000,\"action\":\"stop\",\"state\":\"pending\"}]";
            String targets = m.get("/api/status").body();
            for (long by = System.nanoTime() + TimeUnit.SECONDS.toNanos(5); !targets.contains(listed) && System
                    .nanoTime() < by;) {
                TimeUnit.MILLISECONDS.sleep(POLL_MS); // as the page's script polls
                targets = m.get("/api/status").body();
            }
            assertTrue(targets.contains(listed), targets);
            try {
                awaitTruth(rig.sim, t -> t.distanceTo(driving.x(), driving.y()) > 0.2, 20, "still driving");
            } catch (AssertionError stopped) {
                throw new AssertionError(stopped.getMessage() + "\n" + rig.onboard.output(), stopped);
            }
            assertTrue(rig.onboard.output().lines().noneMatch(l -> l.matches(".*portal: [A-Z]+ /\\S* failed.*")), rig
                    .onboard.output()); // no request ended in an exception (PortalRoutes' 500)

            // the slow bodies not finished: 408 once their time is over (REQUEST_TIMEOUT_S after their headers)
            for (int i = 2; i < slow.size(); i += 2) {
                assertEquals("HTTP/1.1 408 Request Timeout", slow.get(i).statusLine(20_000), "slow body " + i);
            }
            for (SlowClient c : slow) {
                c.close();
            }

            // log-out ends the session
            assertEquals(303, m.post("/logout", "csrf=" + m.csrf()).statusCode());
            assertEquals(401, m.get("/api/status").statusCode());

            // the throttle: after the failures allowed (one above), refused without asking the server, even the right
            // password
            int attempts = 0;
            HttpResponse<String> r;
            do {
                r = anonymous.post("/login", "account=" + enc(maintainer) + "&password=wrong-" + attempts);
                attempts++;
            } while (r.statusCode() == 401 && attempts < 10);
            assertEquals(429, r.statusCode(), r.body());
            assertEquals(5, attempts, "failed log-ins before the throttle (the default 5, one of them above)");
            assertTrue(r.headers().firstValue("Retry-After").isPresent());
            assertEquals(429, anonymous.post("/login", "account=" + enc(maintainer) + "&password=" + enc(
                    PrivateXmppServer.DEFAULT_PASSWORD)).statusCode());
            System.out.printf(Locale.ROOT, "[figure] portal: page at %s, pose followed the robot%n", url);
        }
    }
}
