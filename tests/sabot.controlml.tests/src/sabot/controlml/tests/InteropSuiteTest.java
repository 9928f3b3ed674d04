package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;

import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.SubscribeListener.SubscribeAnswer;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Test;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.TelemetryLeases;
import sabot.controlml.payload.PoseEstimate;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceProfile;
import sabot.identity.DeviceUrn;
import sabot.identity.HardwareDescription;
import sabot.identity.IdentityResult;
import sabot.identity.Inventories;
import sabot.identity.Inventory;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The ControlML 1.0 interop suite (docs/CONTROLML.md section 12): {@code tools/controlml-py/interop.py}, a client on
 * slixmpp written from the specification, against a device assembled here from the public API (ControlMlManager,
 * an access policy, telemetry, sabot.identity) on a private server. The suite's own checks are its output; this test
 * fails when one of them fails. The venv is made by {@code tools/controlml-py/venv.sh} on first use (pinned
 * packages from PyPI); the QR code is read by zbar's {@code zbarimg} ({@code ./sabot deps} installs zbar-tools).
 * <p>
 * The device: every resource of the catalogue served as {@link RecordingDevice} does, except {@code cm.map} (not
 * served, for unsupported-operation); a {@code cm.mission} set refused with the reason its {@code detail} names
 * ({@code busy-once}: busy the first time only; {@code throw}: the handler throws), its get the sample of
 * {@link Samples} (two targets, a wait reached and a dock active, one mission queued); {@code cm.position} published at
 * 20 Hz with x = 1, 2, 3, ..., leased up to 40 Hz for at most 10 s ({@code cm.telemetry}); operator may set, viewer may get, everyone else nothing; the vCard and QR inventory of
 * {@link #SERIAL}, with a non-ASCII part.
 */
abstract class InteropSuiteTest {

    static final String SERIAL = "SB-2026-0042";
    static final String PART = "Räder ø150 mm";
    private static final long SUITE_TIMEOUT_S = 150;

    protected abstract PrivateXmppServer server();

    @Test
    void theSlixmppSuitePasses() throws Exception {
        String zbarimg = "/usr/bin/zbarimg";
        assertTrue(Files.isExecutable(Paths.get(zbarimg)), "zbarimg missing: apt-get install -y zbar-tools "
                + "(./sabot deps installs it)");
        String suffix = server().kind().name().toLowerCase();
        for (String who : List.of("operator", "viewer", "stranger")) {
            server().register(who + "-" + suffix, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
        }
        Jid operator = JidCreate.bareFrom("operator-" + suffix + "@" + PrivateXmppServer.DOMAIN);
        Jid viewer = JidCreate.bareFrom("viewer-" + suffix + "@" + PrivateXmppServer.DOMAIN);
        Map<Jid, Role> rights = Map.of(operator, Role.MAINTAINER, viewer, Role.OBSERVER);

        XMPPTCPConnection robot = server().login("robot-" + suffix);
        Roster roster = Roster.getInstanceFor(robot);
        // section 9: approve whoever may get, and subscribe back (mutual, the recipe of section 6)
        roster.addSubscribeListener((from, request) -> rights.getOrDefault(from.asBareJid(), Role.NONE)
                == Role.NONE ? SubscribeAnswer.Deny : SubscribeAnswer.ApproveAndAlsoRequestIfRequired);
        ControlMlManager device = ControlMlManager.getInstanceFor(robot);
        RecordingDevice recording = new RecordingDevice();
        recording.registerOn(device);
        device.removeHandlers(Resources.MAP);
        AtomicInteger busyOnce = new AtomicInteger();
        device.onSet(Resources.MISSION, (request, mission) -> switch (mission.detail()) {
            case "maintenance-lock" -> Outcome.failure(ControlMlCondition.MAINTENANCE_LOCK, "in maintenance");
            case "invalid-state" -> Outcome.failure(ControlMlCondition.INVALID_STATE, "no mission to pause");
            case "busy" -> Outcome.failure(ControlMlCondition.BUSY, "queue full");
            case "busy-once" -> busyOnce.getAndIncrement() == 0 ? Outcome.failure(ControlMlCondition.BUSY,
                    "queue full") : Outcome.done();
            case "device-fault" -> Outcome.failure(ControlMlCondition.DEVICE_FAULT, "motor board silent");
            case "throw" -> throw new IllegalStateException("a handler bug");
            default -> Outcome.done();
        });
        device.setAccessPolicy(j -> rights.getOrDefault(j.asBareJid(), Role.NONE));

        Inventory inventory = Inventories.of(new HardwareDescription(SERIAL, new Inventory.Mechanic("S1", List.of(
                new Inventory.Part("wheels", PART))), "main board", List.of()), null, List.of(new Inventory.Item(
                        "sabot.controlml", "0.1.0"), new Inventory.Item("org.igniterealtime.smack.core", "4.4.8")));
        DeviceProfile profile = new DeviceProfile("mobile robot (differential drive)", "Sabot", "S1", "interop", null,
                null, null, DeviceUrn.urnOf(SERIAL), robot.getUser().asBareJid().toString(), "robot", null, null,
                null);
        IdentityResult<?> published = DeviceIdentityManager.getInstanceFor(robot).publish(profile, inventory);
        assertTrue(published instanceof IdentityResult.Ok, published::toString);

        AtomicLong tick = new AtomicLong();
        List<String> output = new java.util.concurrent.CopyOnWriteArrayList<>();
        int exit;
        try (TelemetryLeases telemetry = device.telemetry().serveLeases(10)) {
            telemetry.offer(Resources.POSITION, () -> new PoseEstimate(Samples.T, new Pose2D(tick.incrementAndGet(), 0,
                    0), Samples.POSE.covariance()), 20, 40);
            exit = runSuite(List.of("--port", Integer.toString(server().port()), "--ca-file", server().caFile()
                    .toString(), "--domain", PrivateXmppServer.DOMAIN,
                    "--robot", robot.getUser().toString(), "--operator", "operator-" + suffix, "--viewer", "viewer-"
                            + suffix, "--stranger", "stranger-" + suffix, "--password",
                    PrivateXmppServer.DEFAULT_PASSWORD, "--serial", SERIAL, "--part", PART), output);
        }
        String report = String.join("\n", output);
        System.out.println("[interop " + suffix + "]\n" + report);
        assertEquals(0, exit, report);
        assertTrue(output.get(output.size() - 1).matches("interop: \\d+ passed, 0 failed"), report);
    }

    /** Runs interop.py in controlml.py's venv (made on first use); its stdout and stderr go to {@code output}. */
    private static int runSuite(List<String> args, List<String> output) throws IOException, InterruptedException {
        Path tool = PrivateXmppServer.repositoryRoot().resolve("tools/controlml-py");
        Process venv = new ProcessBuilder(tool.resolve("venv.sh").toString()).redirectError(ProcessBuilder.Redirect
                .INHERIT).start();
        String python = new String(venv.getInputStream().readAllBytes(), StandardCharsets.UTF_8).strip();
        assertTrue(venv.waitFor(SUITE_TIMEOUT_S, TimeUnit.SECONDS) && venv.exitValue() == 0, "venv.sh failed");
        List<String> command = new java.util.ArrayList<>(List.of(python, tool.resolve("interop.py").toString()));
        command.addAll(args);
        Process suite = new ProcessBuilder(command).redirectErrorStream(true).start();
        Thread reader = new Thread(() -> {
            try (BufferedReader r = new BufferedReader(new InputStreamReader(suite.getInputStream(),
                    StandardCharsets.UTF_8))) {
                r.lines().forEach(output::add);
            } catch (IOException e) {
                output.add("(output lost: " + e + ")");
            }
        }, "interop-output");
        reader.start();
        if (!suite.waitFor(SUITE_TIMEOUT_S, TimeUnit.SECONDS)) {
            suite.descendants().forEach(ProcessHandle::destroyForcibly);
            suite.destroyForcibly();
            reader.join(TimeUnit.SECONDS.toMillis(5));
            throw new AssertionError("interop.py did not end within " + SUITE_TIMEOUT_S + " s:\n" + String.join("\n",
                    output));
        }
        reader.join(TimeUnit.SECONDS.toMillis(10));
        return suite.exitValue();
    }
}
