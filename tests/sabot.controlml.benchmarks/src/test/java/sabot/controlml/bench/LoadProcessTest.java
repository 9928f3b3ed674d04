package sabot.controlml.bench;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Resources;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.tools.load.FleetLoad;
import sabot.tools.load.Following;

/** The load robots in a process of their own at a nice value, driven over its standard input and output. */
class LoadProcessTest {

    @Test
    void theRobotsRunInTheirOwnProcessAtTheNiceValueAndReportTheirPublications(@TempDir Path dir) throws Exception {
        FleetLoad.setUpSmack();
        try (PrivateXmppServer server = PrivateXmppServer.prosody().start()) {
            EntityBareJid operator = server.register("operator", PrivateXmppServer.DOMAIN, "operator-pw");
            server.registerAll(FleetLoad.accounts(2, "load-", "robot-pw")); // in-band registration is closed
            long loadPid;
            try (LoadProcess load = LoadProcess.start(server.port(), server.caFile(), 19, dir.resolve("load.log"), List.of("--robots",
                    "2", "--password", "robot-pw", "--operator", operator.toString(), "--rate", "10", "--seed", "1"))) {
                loadPid = load.pid();
                assertEquals(List.of("load-01@sabot.local", "load-02@sabot.local"), load.jids().stream().map(
                        Object::toString).toList());
                // a scheduling group of its own at nice 19 (where the kernel has autogroups), and every thread of the
                // process, the JVM's own included, at nice 19
                if (Files.exists(Paths.get("/proc/self/autogroup"))) {
                    String own = Files.readString(Paths.get("/proc/self/autogroup")).split(" ")[0];
                    assertTrue(load.autogroup().endsWith(" nice 19") && !load.autogroup().startsWith(own + " "), () ->
                            "load " + load.autogroup() + ", this JVM " + own);
                }
                // every thread of the process, the JVM's own included, at nice 19 (a thread that ended between the
                // listing and the read of its stat is skipped: the JVM starts and ends threads all along)
                int checked = 0;
                try (var tasks = Files.list(Paths.get("/proc", Long.toString(loadPid), "task"))) {
                    for (Path t : tasks.toList()) {
                        int nice;
                        try {
                            nice = niceOf(t);
                        } catch (IOException e) {
                            if (Files.exists(t)) {
                                throw e;
                            }
                            continue; // the thread ended (no such file, or no such process while it was read)
                        }
                        assertEquals(19, nice, () -> "thread " + t + " of the load process");
                        checked++;
                    }
                }
                assertTrue(checked > 1, "threads checked: " + checked);
                // the operator receives both robots' telemetry, which the robots count as acknowledged
                XMPPTCPConnection wb = new XMPPTCPConnection(server.configuration("operator", PrivateXmppServer.DOMAIN,
                        "operator-pw").setResource("wb").build());
                Map<EntityBareJid, Boolean> seen = new ConcurrentHashMap<>();
                CountDownLatch both = new CountDownLatch(2);
                ControlMlManager.getInstanceFor(wb).telemetry().addListener(Resources.POSITION, (device, p) -> {
                    if (seen.put(device, true) == null) {
                        both.countDown();
                    }
                });
                sabot.fleet.SubscriptionGate.onWorkbench(wb);
                try {
                    wb.connect().login();
                    Following.follow(wb, load.jids());
                    assertTrue(both.await(30, TimeUnit.SECONDS), "telemetry from both robots: " + seen.keySet());
                } finally {
                    wb.disconnect();
                }
                long published = load.telemetryPublished();
                assertTrue(published > 0, "publications acknowledged: " + published);
                assertEquals(0, load.telemetryFailed());
                assertTrue(load.telemetryPublished() >= published, "the count only grows");
            }
            assertFalse(ProcessHandle.of(loadPid).map(ProcessHandle::isAlive).orElse(false),
                    "the load process ended with close()");
        }
    }

    @Test
    void aLoadThatCannotComeOnlineIsAnErrorWithItsLog(@TempDir Path dir) {
        // no such CA file, nothing listens on the port: the process fails before it is ready
        IOException e = assertThrows(IOException.class, () -> LoadProcess.start(1, dir.resolve("no-ca.pem"), 0, dir
                .resolve("load.log"), List.of("--robots", "1", "--operator", "operator@sabot.local")));
        assertTrue(e.getMessage().contains("before its robots were online") && e.getMessage().contains("load.log"), e
                .getMessage());
    }

    private static int niceOf(Path task) throws IOException {
        return ProcStat.nice(task.resolve("stat"));
    }
}
