package sabot.xmpp.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Test;

import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The private server itself (product/bin/sabot-xmpp through the fixture): a server that cannot start fails fast with
 * why and leaves nothing running; a stopped server comes back with its accounts.
 */
class PrivateXmppServerTest {

    /** Far below the 60 s ready timeout: the failure is seen in the server's exit or log, not by waiting it out. */
    private static final Duration FAILS_WITHIN = Duration.ofSeconds(20);

    @Test
    void prosodyOnATakenPortFailsBeforeItStarts() throws Exception {
        assertStartFailsOnATakenPort(PrivateXmppServer.Kind.PROSODY, "is already in use");
    }

    @Test
    void ejabberdOnATakenPortFailsBeforeItStarts() throws Exception {
        assertStartFailsOnATakenPort(PrivateXmppServer.Kind.EJABBERD, "is already in use");
    }

    /**
     * Another program listens on the port and never answers. The script refuses before it launches the server (its
     * readiness probe would otherwise take another server's answer on the port for its own; a server that loses the
     * port in a race is caught by its log line or exit): the start fails quickly, says why, and leaves nothing.
     */
    private static void assertStartFailsOnATakenPort(PrivateXmppServer.Kind kind, String reason) throws Exception {
        try (ServerSocket taken = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            PrivateXmppServer server = PrivateXmppServer.of(kind);
            long t0 = System.nanoTime();
            IOException e = assertThrows(IOException.class, () -> server.start(taken.getLocalPort()));
            Duration took = Duration.ofNanos(System.nanoTime() - t0);
            assertTrue(took.compareTo(FAILS_WITHIN) < 0, "failed after " + took.toMillis() + " ms");
            String message = e.getMessage();
            assertTrue(message.startsWith("private " + kind.name().toLowerCase() + " did not start: "), message);
            assertTrue(message.contains("127.0.0.1:" + taken.getLocalPort()), message);
            assertTrue(message.contains(reason), message);
            assertEquals(List.of(), processesOf(server.runDir()), "server processes left running");
            server.close(); // nothing to stop: must not fail
        }
    }

    @Test
    void prosodyRestartsOnItsPortWithItsAccounts() throws Exception {
        try (PrivateXmppServer server = PrivateXmppServer.prosody().start()) {
            int port = server.port();
            long firstPid = server.pid();
            server.login("alice").disconnect();
            server.stopServer();
            assertFalse(running(firstPid), "server still running after stopServer()");
            server.restart();
            assertEquals(port, server.port());
            assertTrue(firstPid != server.pid(), "same pid after a restart");
            // alice is still there: a login with her password works
            XMPPTCPConnection alice = server.connect(server.configuration("alice", PrivateXmppServer.DOMAIN,
                    PrivateXmppServer.DEFAULT_PASSWORD).build());
            assertTrue(alice.isAuthenticated());
        }
    }

    /**
     * {@code sabot-xmpp group}, the lab's grants: a bad group name or JID (spaces, a quote that would reach ejabberd's
     * JSON or Prosody's groups file) is refused with why, the groups unchanged; a good one is listed.
     */
    @Test
    void badGroupChangesAreRefusedWithWhyAndChangeNothing() throws Exception {
        try (PrivateXmppServer server = PrivateXmppServer.prosody().start()) {
            assertEquals("", group(server, 0, "list"));
            String badGroup = group(server, 1, "add", "sabot operators", "alice@sabot.local");
            assertTrue(badGroup.contains("[sabot] error: xmpp: group 'sabot operators': letters, digits, '.', '_' and "
                    + "'-' only"), badGroup);
            String badJid = group(server, 1, "add", "sabot-operators", "al\"ice@sabot.local");
            assertTrue(badJid.contains("is not a bare JID (local@domain, no quote or backslash)"), badJid);
            String noAt = group(server, 1, "remove", "sabot-operators", "alice");
            assertTrue(noAt.contains("'alice' is not a bare JID"), noAt);
            assertEquals("", group(server, 0, "list"), "changed by a refused change");
            group(server, 0, "add", "sabot-operators", "alice@sabot.local");
            assertEquals("sabot-operators alice@sabot.local", group(server, 0, "list").strip());
        }
    }

    @Test
    void badAccountsAndEnrolmentsAreRefusedWithWhyAndChangeNothing() throws Exception {
        try (PrivateXmppServer server = PrivateXmppServer.prosody().start()) {
            String quote = script(server, 1, "register", "al'ice@sabot.local", "pw");
            assertTrue(quote.contains("'al'ice@sabot.local' is not an account (local@domain, no quote, backslash or "
                    + "space)"), quote);
            String spaced = script(server, 1, "register", "bob@sabot.local", "two words");
            assertTrue(spaced.contains("the password of bob@sabot.local has a space, quote, backslash or control "
                    + "character"), spaced);
            String domain = script(server, 1, "register", "bob@elsewhere.example", "pw");
            assertTrue(domain.contains("Prosody did not make every account"), domain);
            String notAsking = script(server, 1, "enrol", "approve", "carol@sabot.local");
            assertTrue(notAsking.contains("carol@sabot.local is not asking for access (enrol list: nobody)"),
                    notAsking);
            String badToken = script(server, 1, "enrol", "token", "sabot 07@sabot.local");
            assertTrue(badToken.contains("is not an account"), badToken);
            assertEquals("", script(server, 0, "enrol", "list"), "changed by a refused enrolment");
            assertEquals("", group(server, 0, "list"), "a group changed by a refused enrolment");
            assertThrows(org.jivesoftware.smack.sasl.SASLErrorException.class, () -> server.connect(server
                    .configuration("bob", PrivateXmppServer.DOMAIN, "pw").build()), "bob was made");
        }
    }

    /**
     * {@code sabot-xmpp start --federate} (docs/FEDERATION.md): options that do not fit it are refused before anything
     * starts; the pair is Prosody, ejabberd and ejabberd's private name server, each server with its one domain, and
     * one stop ends them all.
     */
    @Test
    void aFederationIsTwoServersStoppedTogetherAndBadOptionsAreRefused() throws Exception {
        Path unused = PrivateXmppServer.repositoryRoot().resolve("target/xmpp-run/federation-refused");
        String pair = "--federate starts its own pair (Prosody for sabot.local, ejabberd for sabot2.local): no --server "
                + "or --nodes with it";
        for (var bad : List.of(java.util.Map.entry(List.of("--federate", "--server", "ejabberd"), pair), java.util.Map
                .entry(List.of("--federate", "--nodes", "2"), pair), java.util.Map.entry(List.of("--federate", "--tls",
                        "off"), "--federate needs TLS (s2s is authenticated by certificates): no --tls off with it"),
                java.util.Map.entry(List.of("--federate", "--s2s-via", "1"), "--s2s-ports/--s2s-via '1': expected two "
                        + "ports, PROSODY,EJABBERD"), java.util.Map.entry(List.of("--s2s-ports", "25269,25270"),
                                "--s2s-ports and --s2s-via are options of --federate"))) {
            List<String> command = new java.util.ArrayList<>(List.of("start", "--run", unused.toString()));
            command.addAll(bad.getKey());
            String out = sabotXmpp(1, command.toArray(String[]::new));
            assertTrue(out.contains("[sabot] error: xmpp: " + bad.getValue()), bad.getKey() + ": " + out);
        }
        assertFalse(Files.exists(unused), "a refused start made its state directory");

        PrivateXmppServer server = PrivateXmppServer.federation().start();
        try {
            List<String> processes = processesOf(server.runDir());
            assertTrue(processes.stream().anyMatch(p -> p.contains("prosody")), processes.toString());
            assertTrue(processes.stream().anyMatch(p -> p.contains("beam")), processes.toString());
            assertTrue(processes.stream().anyMatch(p -> p.contains("dnsmasq")), processes.toString());
            String local = sabotXmpp(1, "register", "--run", server.runDir().resolve("peer").toString(),
                    "x@sabot.local", "pw");
            assertTrue(local.contains("x@sabot.local: the server of " + server.runDir().resolve("peer")
                    + " serves sabot2.local only"), local);
            String status = sabotXmpp(0, "status", "--run", server.runDir().toString());
            assertTrue(status.startsWith("running: prosody for sabot.local, pid " + server.pid()), status);
            assertTrue(status.contains("federated with ejabberd for sabot2.local"), status);
        } finally {
            server.close();
        }
        assertEquals(List.of(), processesOf(server.runDir()), "processes left running after the stop");
    }

    /**
     * {@code sabot-xmpp cert} (docs/PORTAL.md): a lab computer's certificate, signed by the lab CA (made when missing),
     * with every name and address given, its key for the owner only, and the portal's settings printed; a name that
     * is no host name or address is refused and writes nothing.
     */
    @Test
    void certMakesALabComputersCertificateSignedByTheLabCa(@org.junit.jupiter.api.io.TempDir Path run)
            throws Exception {
        Path out = run.resolve("robot-1");
        String printed = sabotXmpp(0, "cert", "--run", run.toString(), "robot-1.lab", "10.0.0.7", "--out", out
                .toString());
        Path crt = out.resolve("robot-1.lab.crt");
        Path key = out.resolve("robot-1.lab.key");
        assertTrue(printed.contains("portal.certificateFile = " + crt + "\n"), printed);
        assertTrue(printed.contains("portal.keyFile = " + key + "\n"), printed);
        assertTrue(printed.contains("portal.address = robot-1.lab\n"), printed);
        var x509 = java.security.cert.CertificateFactory.getInstance("X.509");
        java.security.cert.X509Certificate ca, cert;
        try (var in = Files.newInputStream(run.resolve("ca/ca.pem"))) {
            ca = (java.security.cert.X509Certificate) x509.generateCertificate(in);
        }
        try (var in = Files.newInputStream(crt)) {
            cert = (java.security.cert.X509Certificate) x509.generateCertificate(in);
        }
        cert.verify(ca.getPublicKey()); // signed by the lab CA, or this throws
        cert.checkValidity();
        assertEquals(List.of(List.of(2, "robot-1.lab"), List.of(7, "10.0.0.7")), cert.getSubjectAlternativeNames()
                .stream().map(List::copyOf).toList());
        assertEquals(-1, cert.getBasicConstraints(), "a CA certificate");
        assertEquals("rw-------", java.nio.file.attribute.PosixFilePermissions.toString(Files.getPosixFilePermissions(
                key)));
        for (String bad : List.of("a b", "../x", "robot_1.lab", "x-.lab", "a..b")) {
            String refused = sabotXmpp(1, "cert", "--run", run.toString(), bad, "--out", out.toString());
            assertTrue(refused.contains("'" + bad + "' is neither a host name nor an IP address"), refused);
        }
        try (var files = Files.list(out)) {
            assertEquals(2, files.count(), "a refused name wrote a file");
        }
    }

    /** Runs {@code sabot-xmpp ARGS...}; @return its output (both streams) */
    private static String sabotXmpp(int expectedStatus, String... args) throws Exception {
        List<String> command = new java.util.ArrayList<>(List.of(PrivateXmppServer.repositoryRoot().resolve(
                "product/bin/sabot-xmpp").toString()));
        command.addAll(List.of(args));
        Process p = new ProcessBuilder(command).redirectErrorStream(true).start();
        p.getOutputStream().close();
        String out = new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        assertEquals(expectedStatus, p.waitFor(), () -> String.join(" ", command) + ": " + out);
        return out;
    }

    /** Runs {@code sabot-xmpp group OP --run DIR ARGS...}; @return its output (both streams) */
    private static String group(PrivateXmppServer server, int expectedStatus, String op, String... args)
            throws Exception {
        List<String> all = new java.util.ArrayList<>(List.of(op, "--run", server.runDir().toString()));
        all.addAll(List.of(args));
        return script(server, expectedStatus, "group", all.toArray(String[]::new));
    }

    /**
     * Runs {@code sabot-xmpp ACTION ARGS...} (for register and enrol, {@code --run DIR} goes after the action's
     * first word when it has a sub-command, else first); @return its output (both streams)
     */
    private static String script(PrivateXmppServer server, int expectedStatus, String action, String... args)
            throws Exception {
        List<String> command = new java.util.ArrayList<>(List.of(PrivateXmppServer.repositoryRoot().resolve(
                "product/bin/sabot-xmpp").toString(), action));
        List<String> rest = new java.util.ArrayList<>(List.of(args));
        if (action.equals("enrol")) {
            command.add(rest.remove(0));
        }
        if (!action.equals("group")) {
            command.addAll(List.of("--run", server.runDir().toString()));
        }
        command.addAll(rest);
        Process p = new ProcessBuilder(command).redirectErrorStream(true).start();
        String out = new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        assertEquals(expectedStatus, p.waitFor(), () -> String.join(" ", command) + ": " + out);
        return out;
    }

    /**
     * The live processes of a state directory: ejabberd's name it on their command line, Prosody's in their
     * environment (SABOT_XMPP_RUN).
     */
    private static List<String> processesOf(Path runDir) {
        String dir = runDir.toString();
        byte[] env = ("SABOT_XMPP_RUN=" + dir + "\0").getBytes(StandardCharsets.UTF_8);
        return ProcessHandle.allProcesses().filter(p -> running(p.pid())).filter(p -> p.info().commandLine().map(
                c -> c.contains(dir)).orElse(false) || contains(read(Path.of("/proc/" + p.pid() + "/environ")), env))
                .map(p -> p.pid() + " " + p.info().commandLine().orElse("")).toList();
    }

    /** Whether process {@code pid} runs (a zombie does not: whatever runs as pid 1 may be slow to reap it). */
    private static boolean running(long pid) {
        String stat = new String(read(Path.of("/proc/" + pid + "/stat")), StandardCharsets.UTF_8);
        int end = stat.lastIndexOf(") ");
        return end > 0 && end + 2 < stat.length() && stat.charAt(end + 2) != 'Z';
    }

    private static byte[] read(Path file) {
        try {
            return Files.readAllBytes(file);
        } catch (IOException | SecurityException gone) {
            return new byte[0];
        }
    }

    private static boolean contains(byte[] haystack, byte[] needle) {
        outer: for (int i = 0; i + needle.length <= haystack.length; i++) {
            for (int j = 0; j < needle.length; j++) {
                if (haystack[i + j] != needle[j]) {
                    continue outer;
                }
            }
            return true;
        }
        return false;
    }
}
