package sabot.products;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** The ./sabot launcher as a user runs it: its private XMPP server and its answers when something is missing. */
class LauncherTest {

    @TempDir
    Path dir;

    private record Result(int status, String output) {
    }

    private Result sabot(Map<String, String> env, String... args) throws IOException, InterruptedException {
        List<String> cmd = new java.util.ArrayList<>();
        cmd.add(ProductProcess.root().resolve("sabot").toString());
        cmd.addAll(List.of(args));
        ProcessBuilder pb = new ProcessBuilder(cmd).directory(dir.toFile()).redirectErrorStream(true);
        pb.environment().putAll(env);
        Process p = pb.start();
        byte[] out = p.getInputStream().readAllBytes();
        assertTrue(p.waitFor(60, TimeUnit.SECONDS), "./sabot did not finish");
        return new Result(p.exitValue(), new String(out, StandardCharsets.UTF_8));
    }

    @Test
    void missingJdkNamesTheInstallCommand() throws Exception {
        Path noJvms = Files.createDirectories(dir.resolve("jvm"));
        Result r = sabot(Map.of("SABOT_JVM_DIR", noJvms.toString(), "SABOT_JAVA_HOME", "", "JAVA_HOME", "",
                "TEMURIN25_HOME", ""), "onboard");
        assertEquals(1, r.status(), r.output());
        assertTrue(r.output().contains("no JDK >= 21 found"), r.output());
        assertTrue(r.output().contains("apt-get install -y temurin-25-jdk"), r.output());
    }

    @Test
    void missingProsodyNamesTheInstallCommand() throws Exception {
        Result r = sabot(Map.of("SABOT_PROSODY", dir.resolve("no-prosody").toString(), "SABOT_XMPP_RUN", dir
                .resolve("xmpp").toString()), "xmpp", "start");
        assertEquals(1, r.status(), r.output());
        assertTrue(r.output().contains("apt-get install -y prosody"), r.output());
    }

    @Test
    void privateXmppServerStartsReportsAndStops() throws Exception {
        int port;
        try (ServerSocket s = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            port = s.getLocalPort();
        }
        Map<String, String> env = Map.of("SABOT_XMPP_RUN", dir.resolve("xmpp").toString(), "SABOT_XMPP_PORT",
                Integer.toString(port));
        try {
            Result start = sabot(env, "xmpp", "start");
            assertEquals(0, start.status(), start.output());
            assertTrue(start.output().contains("ready"), start.output());
            Result status = sabot(env, "xmpp", "status");
            assertEquals(0, status.status(), status.output());
            assertTrue(status.output().contains("running: prosody, pid") && status.output().contains("127.0.0.1:" + port),
                    status.output());
            try (java.net.Socket s = new java.net.Socket(InetAddress.getLoopbackAddress(), port)) {
                assertTrue(s.isConnected());
            }
            // the private instance's own log, listening where it was told to
            String log = Files.readString(dir.resolve("xmpp/prosody.log"));
            assertTrue(log.contains("Activated service 'c2s' on [127.0.0.1]:" + port), log);
            Result register = sabot(env, "xmpp", "register", "robot7", "pw7");
            assertEquals(0, register.status(), register.output());
        } finally {
            Result stop = sabot(env, "xmpp", "stop");
            assertEquals(0, stop.status(), stop.output());
        }
        Result after = sabot(env, "xmpp", "status");
        assertEquals(3, after.status(), after.output());
        assertTrue(after.output().contains("stopped"), after.output());
    }
}
