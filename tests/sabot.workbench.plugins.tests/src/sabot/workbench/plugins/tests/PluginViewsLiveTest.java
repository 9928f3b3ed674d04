package sabot.workbench.plugins.tests;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.nio.file.StandardCopyOption;
import java.time.Instant;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Random;
import java.util.concurrent.TimeUnit;
import java.util.function.BooleanSupplier;
import java.util.function.Supplier;

import org.eclipse.core.runtime.jobs.Job;
import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.ImageLoader;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Control;
import org.eclipse.swtchart.ISeries;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Event;
import org.eclipse.ui.IViewPart;
import org.eclipse.ui.IWorkbenchPage;
import org.eclipse.ui.PlatformUI;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.vcardtemp.VCardManager;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.impl.JidCreate;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.MethodOrderer;
import org.junit.jupiter.api.Order;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestMethodOrder;

import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.FileEntry;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.PidGains;
import sabot.identity.DeviceCard;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceProfile;
import sabot.identity.DeviceUrn;
import sabot.identity.IdentityResult;
import sabot.identity.QrInventory;
import sabot.testsupport.robot.OnboardProcess;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.workbench.account.XmppAccount;
import sabot.workbench.account.XmppAccountStore;
import sabot.pidstep.StepFigures;
import sabot.pidstep.controlml.StepTest;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotIdentity;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.fleet.TrafficStatistics;
import sabot.controlml.ControlMlCondition;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.identity.internal.IdentityView;
import sabot.workbench.joystick.internal.JoystickView;
import sabot.workbench.pid.internal.PidView;
import sabot.workbench.remotefs.internal.RemoteFilesView;
import sabot.workbench.statistics.internal.TrafficView;
import sabot.workbench.robotview.RobotView;

/**
 * The plug-ins' views in the real workbench against the real stack: a private Prosody, {@code sabot-sim} on the lab
 * map and the onboard product as processes; the workbench's ControlML plug-in logs in with the account stored in its
 * preferences, and each view observes its FleetState. Judged on the simulator's ground truth, the robot's remote-FS
 * directory on disk and the robot's own answers. One stack for all tests (each robot start costs ~10 s).
 */
@TestMethodOrder(MethodOrderer.OrderAnnotation.class)
class PluginViewsLiveTest {

    static final String ROBOT = "sabot-01";
    static final String ROBOT_JID = ROBOT + "@" + PrivateXmppServer.DOMAIN;
    static final String OPERATOR = "operator";
    /** The lab's east room, facing +x: free space ahead for a short joystick drive. */
    static final double[] START = { 6.0, 2.8, 0.0 };
    /** The simulated robot's linear acceleration limit, m/s² (docs/sabot-robot.properties). */
    static final double A_MAX = 0.5;
    /** Pad deflection forward: a quarter of the robot's top speed, so that braking alone takes ~0.25 s. */
    static final double DEFLECTION = 0.25;

    static PrivateXmppServer xmpp;
    static SimProcess sim;
    static OnboardProcess onboard;
    static Path dir;

    @BeforeAll
    static void startStack() throws Exception {
        xmpp = PrivateXmppServer.prosody().start();
        xmpp.register(ROBOT, PrivateXmppServer.DOMAIN, "robot-pw");
        xmpp.register(OPERATOR, PrivateXmppServer.DOMAIN, "operator-pw");
        // the plug-ins change gains, files and run step tests: the maintainer's role (the robot in the robots' group)
        xmpp.enrolRobot(JidCreate.bareFrom(ROBOT_JID));
        xmpp.grant(JidCreate.bareFrom(OPERATOR + "@" + PrivateXmppServer.DOMAIN), Role.MAINTAINER);
        dir = Files.createDirectories(Paths.get("target", "live-plugins").toAbsolutePath());
        sim = SimProcess.start(dir, START);
        onboard = OnboardProcess.start(dir, new OnboardProcess.Robot(ROBOT, sim.link(1), START, xmpp.port(), xmpp
                .caFile()), "robot-pw", "");
        onboard.await(l -> l.contains("XMPP session online"), "saying the XMPP session is online");
        onboard.await(l -> l.contains("ready to move"), "saying the inertial biases have settled");
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        store.saveRobots(List.of(ROBOT_JID));
        store.save(operatorAccount(xmpp.port()),
                "operator-pw".toCharArray());
    }

    @AfterAll
    static void stopStack() throws Exception {
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        store.forgetPassword();
        store.saveRobots(List.of());
        if (onboard != null) {
            onboard.close();
        }
        if (sim != null) {
            sim.close();
        }
        if (xmpp != null) {
            xmpp.close();
        }
    }

    @Test
    @Order(1)
    void joystickHeldDrivesTheRobotAndReleasedStopsItWithinHalfASecond() throws Exception {
        JoystickView joystick = open(JoystickView.ID, JoystickView.class);
        awaitLive(joystick);
        waitFor(() -> joystick.limits() != null, 20, () -> "limits not read: " + joystick.message());
        SimProcess.Truth before = sim.truth();

        Control pad = joystick.pad();
        Point size = pad.getSize();
        double radius = Math.max(10, Math.min(size.x, size.y) / 2.0 - 12); // as the pad computes it
        int x = size.x / 2;
        int y = (int) Math.round(size.y / 2.0 - DEFLECTION * radius);
        mouse(pad, SWT.MouseDown, x, y);
        assertTrue(joystick.held(), joystick.message());
        // the pad quantises to its pixels: within one pixel of the deflection aimed at
        double max = joystick.limits().maxLinearSpeed();
        double expected = joystick.twist().linear();
        assertEquals(DEFLECTION * max, expected, max / radius, "pad of " + size);
        assertEquals(0, joystick.twist().angular(), 1e-9);
        // held: the robot accelerates to the pad's speed and keeps it while twists arrive at 10 Hz
        SimProcess.Truth[] driving = new SimProcess.Truth[1];
        waitFor(() -> {
            driving[0] = truth();
            return driving[0].v() > 0.9 * expected && driving[0].distanceTo(before.x(), before.y()) > 0.1;
        }, 15, () -> "robot not driving at " + expected + " m/s: " + driving[0] + "; " + joystick.message());
        int sentBefore = joystick.sentCount();
        long t0 = System.nanoTime();
        waitFor(() -> System.nanoTime() - t0 > 1_000_000_000L, 5, () -> "one second held");
        int rate = joystick.sentCount() - sentBefore;
        assertTrue(rate >= 8 && rate <= 12, "twists sent in one second held: " + rate);
        SimProcess.Truth stillDriving = truth();
        assertTrue(stillDriving.v() > 0.9 * expected, "stopped while held (deadman not fed?): " + stillDriving);
        shot(joystick, "joystick.png");

        mouse(pad, SWT.MouseUp, x, y);
        SimProcess.Truth atRelease = truth();
        assertFalse(joystick.held());
        SimProcess.Truth[] stopped = new SimProcess.Truth[1];
        waitFor(() -> {
            stopped[0] = truth();
            return Math.abs(stopped[0].v()) < 0.005 && Math.abs(stopped[0].omega()) < 0.01;
        }, 5, () -> "robot still moving after release: " + stopped[0]);
        double stopTime = stopped[0].t() - atRelease.t();
        System.out.printf(Locale.ROOT, "[figure] joystick release to standstill (simulator clock): %.3f s from %.3f m/s%n",
                stopTime, atRelease.v());
        assertTrue(stopTime <= 0.5, "stopped " + stopTime + " s after the release (" + atRelease + " -> "
                + stopped[0] + ")");
        assertFalse(joystick.messageIsError(), joystick.message());
        // under the pad, the robot's own words on its motion (its mission's state and detail, from its telemetry)
        waitFor(() -> {
            MissionStatus m = joystick.robotState().mission();
            return m != null && joystick.robotSays().equals("robot: " + m.state().code() + (m.detail().isBlank() ? ""
                    : " — " + m.detail()));
        }, 5, () -> "under the pad: '" + joystick.robotSays() + "', the robot's mission: "
                + joystick.robotState().mission());
    }

    @Test
    @Order(2)
    void remoteFilesUploadListDownloadDeleteAndRefusalsShowTheirReason() throws Exception {
        RemoteFilesView files = open(RemoteFilesView.ID, RemoteFilesView.class);
        awaitLive(files);
        byte[] content = new byte[100_000]; // four chunks of 32 KiB
        new Random(15).nextBytes(content);
        Path local = Files.write(dir.resolve("payload.bin"), content);
        Path onRobot = dir.resolve("fs/plugin-test/payload.bin");
        Files.deleteIfExists(onRobot);

        finish(files, files.upload(List.of(local), "plugin-test"), "upload");
        assertArrayEquals(content, Files.readAllBytes(onRobot), "the robot's file differs from the uploaded one");

        files.refresh();
        waitFor(() -> files.listed("") != null, 20, files::message);
        assertTrue(files.listed("").stream().anyMatch(e -> e.name().equals("plugin-test") && e.directory()), files
                .listed("").toString());
        files.viewer().expandToLevel(2);
        waitFor(() -> files.listed("plugin-test") != null, 20, files::message);
        files.viewer().expandToLevel(2);
        assertEquals(List.of(new FileEntry("payload.bin", content.length, false)), files.listed("plugin-test"));
        shot(files, "remote-files.png");

        Path back = dir.resolve("downloaded.bin");
        Files.deleteIfExists(back);
        finish(files, files.download("plugin-test/payload.bin", back), "download");
        assertArrayEquals(content, Files.readAllBytes(back), "downloaded bytes differ");

        // refused by the robot: a directory that is not empty; by the path rule: '..'
        finish(files, files.delete("plugin-test"), "delete");
        assertTrue(files.messageIsError() && files.message().contains("invalid-state"), files.message());
        assertTrue(Files.exists(onRobot), "a refused delete changed the disk");
        finish(files, files.upload(List.of(local), "../outside"), "upload");
        assertTrue(files.messageIsError() && files.message().contains("invalid-value"), files.message());
        assertFalse(Files.exists(dir.resolve("outside")), "a refused upload wrote outside the root");

        finish(files, files.delete("plugin-test/payload.bin"), "delete");
        assertFalse(files.messageIsError(), files.message());
        assertFalse(Files.exists(onRobot), "not deleted on the robot");
        waitFor(() -> files.listed("plugin-test") != null && files.listed("plugin-test").isEmpty(), 20, () -> "listing "
                + "after delete: " + files.listed("plugin-test"));
    }

    @Test
    @Order(3)
    void pidGainsWrittenAreReadBackFromTheBoard() throws Exception {
        PidView pid = open(PidView.ID, PidView.class);
        awaitLive(pid);
        waitFor(() -> pid.gains() != null, 20, pid::message);
        PidGains original = pid.gains();
        assertFalse(original.motors().isEmpty());
        // the SACT board holds whole numbers (its own units, 0..32767): new whole gains
        PidGains changed = new PidGains(original.motors().stream().map(m -> new MotorGains(m.motor(), Math.round(m
                .kp()) + 17, Math.round(m.ki()) + 3, Math.round(m.kd()) + 1)).toList());
        try {
            pid.type(changed);
            pid.writeTyped();
            waitFor(() -> pid.message().contains("write gains: done"), 20, pid::message);
            // a fresh read from the robot: what its motor board holds now
            pid.readGains();
            waitFor(() -> pid.message().contains("read gains: done"), 20, pid::message);
            assertGains(changed, pid.gains());
            waitFor(() -> pid.plotted() > 3, 20, () -> "no telemetry plotted: " + pid.plotted());
            shot(pid, "pid.png");
        } finally {
            pid.writeGains(original);
            waitFor(() -> pid.message().contains("write gains"), 20, pid::message);
        }
        assertFalse(pid.messageIsError(), pid.message());
    }

    /**
     * The account's role on the robot, as the robot says it (cm.role): a maintainer's Write button is enabled; a role
     * changed on the server shows when the robot refuses (its text on the message line), and the button is then
     * disabled with the reason as its tooltip.
     */
    @Test
    @Order(10)
    void aRoleTakenAwayOnTheServerDisablesWhatTheAccountMayNoLongerDo() throws Exception {
        PidView pid = open(PidView.ID, PidView.class);
        awaitLive(pid);
        waitFor(() -> pid.role() == Role.MAINTAINER, 20, () -> "role on the robot: " + pid.role());
        assertTrue(pid.writeButton().isEnabled());
        waitFor(() -> pid.gains() != null, 20, pid::message);
        BareJid operator = JidCreate.bareFrom(OPERATOR + "@" + PrivateXmppServer.DOMAIN);
        xmpp.grant(operator, Role.OPERATOR);
        xmpp.revoke(operator, Role.MAINTAINER);
        try {
            pid.writeTyped();
            waitFor(() -> pid.message().contains("write gains:") && pid.role() == Role.OPERATOR, 20, () -> pid
                    .message() + "; role " + pid.role());
            assertTrue(pid.messageIsError() && pid.message().contains("is an operator on this device; a set of "
                    + "cm.pid needs the maintainer role (set-not-permitted)"), pid.message());
            waitFor(() -> !pid.writeButton().isEnabled(), 5, () -> "Write gains enabled for an operator");
            assertEquals("Writing gains needs the maintainer role on " + ROBOT_JID + "; the robot says this account is"
                    + " an operator there (roles are granted on the lab's XMPP server)", pid.writeButton()
                            .getToolTipText());
        } finally {
            xmpp.grant(operator, Role.MAINTAINER);
            xmpp.revoke(operator, Role.OPERATOR);
        }
    }

    @Test
    @Order(5)
    void pidStepTestPlotsTheBoardsResponseComparesTwoGainSetsAndRefusesBadInput() throws Exception {
        PidView pid = open(PidView.ID, PidView.class);
        awaitLive(pid);
        waitFor(() -> pid.gains() != null, 20, pid::message);
        PidGains original = pid.gains();
        FleetState fleet = fleet();
        // out of maintenance: refused with the robot's reason, nothing plotted
        pid.stepTest(1, 0.002);
        waitFor(() -> pid.message().contains("switch the robot to maintenance first"), 30, pid::message);
        assertTrue(pid.messageIsError());
        assertNull(pid.lastStep());
        fleet.set(pid.robot(), Resources.MISSION, new MissionStatus(MissionState.IDLE, true, 0, "PID tuning")).get(
                20, TimeUnit.SECONDS);
        try {
            SimProcess.Truth before = truth();
            pid.stepTest(2, 0.002);
            waitFor(() -> pid.message().contains("motor 2: this robot has motors 0 (left) and 1 (right)"), 30,
                    pid::message);
            pid.stepTest(0, 0.008);
            waitFor(() -> pid.message().contains("following-error limit"), 30, pid::message);
            assertNull(pid.lastStep(), "a refused step test plots nothing");
            assertTrue(truth().distanceTo(before.x(), before.y()) < 1e-4, "refusals moved the robot");

            pid.stepTest(1, 0.002);
            waitFor(() -> pid.lastStep() != null, 30, pid::message);
            StepTest stiff = pid.lastStep();
            assertEquals(256, stiff.samples().size());
            ISeries<?> measured = pid.stepChart().getSeriesSet().getSeries("measured");
            assertEquals(256, measured.getYSeries().length, "the plot holds every sample");
            StepFigures f = StepFigures.of(stiff.samples());
            assertTrue(f.riseTime() > 5e-3 && f.riseTime() < 40e-3 && f.overshoot() < 20 && f.settlingTime() < 0.1,
                    f.toString());
            // a softer right wheel, then the same test: both on the plot, both sets of figures shown
            PidGains soft = new PidGains(List.of(new MotorGains(1, 60, 2, 600)));
            pid.type(soft);
            pid.writeTyped();
            waitFor(() -> pid.message().contains("write gains: done"), 20, pid::message);
            pid.stepTest(1, -0.002);
            waitFor(() -> pid.lastStep() != stiff && pid.lastStep() != null, 30, pid::message);
            assertEquals(stiff, pid.previousStep());
            assertTrue(pid.stepChart().getSeriesSet().getSeries("previous: measured") != null);
            assertTrue(pid.figuresText().contains("now wheel 1, -2.00 mm") && pid.figuresText().contains(
                    "before wheel 1, 2.00 mm"), pid.figuresText());
            StepFigures g = StepFigures.of(pid.lastStep().samples());
            assertTrue(g.settlingTime() > f.settlingTime(), "softer gains settle later: " + g + " vs " + f);
            System.out.printf("[pid step view] %s%n", pid.figuresText());
            shot(pid, "pid-step.png");
        } finally {
            pid.writeGains(original);
            waitFor(() -> pid.message().contains("write gains"), 20, pid::message);
            fleet.set(pid.robot(), Resources.MISSION, new MissionStatus(MissionState.IDLE, false, 0, "")).get(20,
                    TimeUnit.SECONDS);
        }
    }

    private static FleetState fleet() {
        org.osgi.framework.BundleContext c = org.osgi.framework.FrameworkUtil.getBundle(PluginViewsLiveTest.class)
                .getBundleContext();
        return c.getService(c.getServiceReference(FleetState.class));
    }

    @Test
    @Order(4)
    void identityShowsTheRobotsVCardAndSavesItsQrCodeAsPng() throws Exception {
        IdentityView identity = open(IdentityView.ID, IdentityView.class);
        awaitLive(identity);
        // fetched by the view through FleetState.identity (the ControlML plug-in's connection, off the UI thread)
        identity.load();
        waitFor(() -> identity.message().contains("identity: done") && identity.shown() != null, 20,
                identity::message);
        assertFalse(identity.messageIsError(), identity.message());
        RobotIdentity card = identity.shown();

        // the oracle: the robot's vCard as any other XMPP client reads it from the server
        XMPPTCPConnection auditor = xmpp.login("auditor");
        try {
            IdentityResult<DeviceCard> fetched = DeviceIdentityManager.getInstanceFor(auditor).fetch(JidCreate
                    .entityBareFrom(ROBOT_JID));
            DeviceCard d = fetched.orElseThrow();
            assertNotNull(d.inventory(), "the robot's vCard has no readable QR code: " + d.inventoryProblem());
            DeviceProfile p = d.profile();
            byte[] png = VCardManager.getInstanceFor(auditor).loadVCard(JidCreate.entityBareFrom(ROBOT_JID))
                    .getAvatar();
            assertEquals(new RobotIdentity(p.jid(), p.nickname(), p.portal() == null ? null : p.portal().toString(),
                    p.latitude(), p.longitude(), p.uid(), p.category(), p.manufacturer(), p.model(), png), card);
        } finally {
            auditor.instantShutdown();
        }
        // the robot's serial is its bare JID (docs/IDENTITY.md): its UUID follows from it
        assertEquals(DeviceUrn.urnOf(ROBOT_JID), card.uid());
        Map<String, String> shown = identity.shownTexts();
        assertEquals(ROBOT_JID, shown.get("JID"));
        assertEquals(card.uid(), shown.get("UUID"));
        assertTrue(shown.get("UUID").startsWith("urn:uuid:"), shown.toString());
        assertTrue(shown.get("Inventory").contains("board"), "QR code not decoded: " + shown);
        shot(identity, "identity.png");

        Path saved = dir.resolve("qr.png");
        identity.saveQr(saved);
        assertArrayEquals(card.qrPng(), Files.readAllBytes(saved));
        assertEquals(card.uid(), QrInventory.decode(Files.readAllBytes(saved)).orElseThrow().uid());
    }

    /**
     * The Traffic view (statistics plug-in) counts the workbench's own traffic with the live robot: requests the test
     * sends, the one the robot refuses by its condition, round trips, telemetry; it plots the robot's rates and p99
     * and refreshes at 1 Hz without holding the UI thread.
     */
    @Test
    @Order(6)
    void trafficViewCountsRequestsErrorsRoundTripsAndTelemetryOfTheLiveRobot() throws Exception {
        TrafficView traffic = open(TrafficView.ID, TrafficView.class);
        FleetState fleet = fleet();
        waitFor(() -> traffic.rows().stream().anyMatch(r -> r.robot().equals(ROBOT_JID) && r.telemetryHz() > 0),
                30, () -> "no telemetry counted: " + traffic.rows());
        TrafficStatistics before = fleet.traffic(ROBOT_JID).orElseThrow();
        int gets = 10;
        for (int i = 0; i < gets; i++) {
            fleet.get(ROBOT_JID, Resources.LIMITS).get(20, TimeUnit.SECONDS);
        }
        // a refusal by the robot: gains it cannot hold (kp is a whole number on the board)
        java.util.concurrent.ExecutionException refused = org.junit.jupiter.api.Assertions.assertThrows(
                java.util.concurrent.ExecutionException.class, () -> fleet.set(ROBOT_JID, Resources.PID, new PidGains(
                        List.of(new MotorGains(0, 225.01, 0, 0)))).get(20, TimeUnit.SECONDS));
        ControlMlCondition condition = ((FleetCommandException) refused.getCause()).condition();
        assertEquals(ControlMlCondition.INVALID_VALUE, condition, refused.getCause().getMessage());

        TrafficStatistics after = fleet.traffic(ROBOT_JID).orElseThrow();
        assertTrue(after.requests() - before.requests() >= gets + 1, before + " -> " + after);
        assertEquals(before.errors().getOrDefault(condition, 0L) + 1, after.errors().get(condition), String.valueOf(
                after.errors()));
        assertTrue(after.roundTrips() >= gets + 1, after.toString());
        assertTrue(after.roundTripP50Ms() > 0 && after.roundTripP50Ms() <= after.roundTripP99Ms()
                && after.roundTripP99Ms() < 20_000, after.toString());
        assertTrue(after.stanzasOut() - before.stanzasOut() >= gets + 1, "each request is a stanza out: " + after);
        assertTrue(after.bytesOut() > after.stanzasOut() * 50, "bytes of the serialised stanzas: " + after);
        // the robot publishes at most 10 + 10 + 1 + 2 Hz (position, velocity, mission, obstacles: onboard defaults);
        // each item is a stanza in
        assertTrue(after.telemetryHz() > 1 && after.telemetryHz() <= 23 * 1.2, after.toString());
        assertTrue(after.stanzasInPerSecond() >= after.telemetryHz() * 0.8, after.toString());
        assertTrue(after.telemetryAgeS() < 1, after.toString());

        // the view shows the same, and plots the robot
        // (the plug-in's other tests' requests and refusals are counted too: the same connection)
        java.util.regex.Pattern invalid = java.util.regex.Pattern.compile("invalid-value (\\d+)");
        waitFor(() -> {
            Map<String, String> cells = traffic.cells(ROBOT_JID);
            java.util.regex.Matcher m = invalid.matcher(cells.getOrDefault("Errors", ""));
            return m.find() && Long.parseLong(m.group(1)) >= after.errors().get(condition) && Long.parseLong(cells
                    .get("Requests")) >= after.requests();
        }, 5, () -> "view: " + traffic.cells(ROBOT_JID) + "; FleetState: " + after);
        assertEquals(ROBOT_JID, traffic.selected());
        long refreshesBefore = traffic.refreshes();
        waitFor(() -> traffic.plotted("in") >= 10 && traffic.plotted("p99") >= 3, 30, () -> "plotted: in "
                + traffic.plotted("in") + ", p99 " + traffic.plotted("p99"));
        long refreshes = traffic.refreshes() - refreshesBefore;
        System.out.printf(Locale.ROOT, "[figure] Traffic view: %d refreshes, slowest %.2f ms on the UI thread; %s%n",
                traffic.refreshes(), traffic.slowestRefreshNanos() / 1e6, traffic.cells(ROBOT_JID));
        assertTrue(refreshes >= 1, "no refresh while waiting");
        assertTrue(traffic.slowestRefreshNanos() < 100_000_000L, "a refresh held the UI thread "
                + traffic.slowestRefreshNanos() / 1e6 + " ms");
        // the server's figures: this Prosody keeps no archive, and the view says so (ServerStatisticsTest: ejabberd's)
        waitFor(() -> traffic.serverLine().contains("keeps no archive"), 15, traffic::serverLine);
        IWorkbenchPage page = page();
        org.eclipse.ui.IWorkbenchPartReference ref = page.getReference(traffic);
        page.setPartState(ref, IWorkbenchPage.STATE_MAXIMIZED);
        try {
            capture(traffic.content(), "traffic-statistics.png");
        } finally {
            page.setPartState(ref, IWorkbenchPage.STATE_RESTORED);
        }
    }

    // ------------------------------------------------------------------------------------------------ helpers

    /** Gains as the board holds them. */
    private static void assertGains(PidGains expected, PidGains actual) {
        assertNotNull(actual);
        assertEquals(expected.motors().size(), actual.motors().size(), actual.toString());
        for (int i = 0; i < expected.motors().size(); i++) {
            MotorGains e = expected.motors().get(i);
            MotorGains a = actual.motors().get(i);
            assertEquals(e.motor(), a.motor());
            assertEquals(e.kp(), a.kp(), 0, actual.toString());
            assertEquals(e.ki(), a.ki(), 0, actual.toString());
            assertEquals(e.kd(), a.kd(), 0, actual.toString());
        }
    }

    private static SimProcess.Truth truth() {
        try {
            return sim.truth();
        } catch (java.io.IOException e) {
            throw new AssertionError("simulator truth: " + e, e);
        }
    }

    private static IWorkbenchPage page() {
        return PlatformUI.getWorkbench().getActiveWorkbenchWindow().getActivePage();
    }

    private static <T extends IViewPart> T open(String id, Class<T> type) throws Exception {
        return type.cast(page().showView(id));
    }

    /** Waits until the view has chosen the robot and the robot is live (present, telemetry fresh). */
    private static void awaitLive(RobotView view) {
        waitFor(() -> {
            RobotState r = view.robotState();
            return ROBOT_JID.equals(view.robot()) && r != null && r.availability() != Availability.OFFLINE && r
                    .pose() != null && !r.isStale(Instant.now());
        }, 60, () -> "robot not live in the view: " + view.robotState() + "; " + view.message());
    }

    /** Waits for a job and for its outcome on the view's message line. */
    private static void finish(RobotView view, Job job, String what) {
        assertNotNull(job, view.message());
        waitFor(() -> job.getResult() != null && view.message().contains(what), 60, () -> what + " not finished: "
                + view.message());
    }

    /**
     * Runs the UI's event loop until {@code condition} holds: the robot, the server and the jobs live on other threads
     * and processes, so a 20 ms timer wakes the loop to look again, up to the deadline.
     */
    static void waitFor(BooleanSupplier condition, double seconds, Supplier<String> what) {
        Display d = Display.getCurrent();
        long deadline = System.nanoTime() + (long) (seconds * 1e9);
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() > deadline) {
                String console = onboard == null ? "" : onboard.output();
                throw new AssertionError("within " + seconds + " s: " + what.get() + "\nonboard console tail:\n"
                        + console.substring(Math.max(0, console.length() - 3000)));
            }
            d.timerExec(20, () -> {
            });
            if (!d.readAndDispatch()) {
                d.sleep();
            }
        }
    }

    private static void mouse(Control c, int type, int x, int y) {
        Event e = new Event();
        e.x = x;
        e.y = y;
        e.button = 1;
        c.notifyListeners(type, e);
    }

    /** Saves a screenshot of a view, maximised for the picture, then restored. */
    private static void shot(RobotView view, String name) throws Exception {
        IWorkbenchPage page = page();
        org.eclipse.ui.IWorkbenchPartReference ref = page.getReference(view);
        page.setPartState(ref, IWorkbenchPage.STATE_MAXIMIZED);
        try {
            capture(view.content().getParent(), name);
        } finally {
            page.setPartState(ref, IWorkbenchPage.STATE_RESTORED);
        }
    }

    /** Saves what the screen shows of a control (a view's area) to target/screenshots and docs/images. */
    private static void capture(Control c, String name) throws Exception {
        Display d = c.getDisplay();
        while (d.readAndDispatch()) {
            // layout and paint
        }
        Rectangle b = c.getBounds();
        Point origin = c.getParent().toDisplay(b.x, b.y);
        Image image = new Image(d, b.width, b.height);
        GC gc = new GC(d);
        Path png = Files.createDirectories(Paths.get(System.getProperty("sabot.screenshots", "target/screenshots")))
                .resolve(name);
        try {
            gc.copyArea(image, origin.x, origin.y);
            ImageLoader loader = new ImageLoader();
            loader.data = new ImageData[] { image.getImageData() };
            loader.save(png.toString(), SWT.IMAGE_PNG);
        } finally {
            gc.dispose();
            image.dispose();
        }
        String root = System.getProperty("sabot.root");
        if (root != null && Files.isDirectory(Paths.get(root, "docs"))) {
            Files.copy(png, Files.createDirectories(Paths.get(root, "docs", "images")).resolve(name),
                    StandardCopyOption.REPLACE_EXISTING);
        }
    }

    /** @return the operator's account on 127.0.0.1:{@code port}, trusting the private server's lab CA */
    private static XmppAccount operatorAccount(int port) {
        return new XmppAccount("127.0.0.1", port, OPERATOR + "@" + PrivateXmppServer.DOMAIN, xmpp.caFile().toString());
    }
}
