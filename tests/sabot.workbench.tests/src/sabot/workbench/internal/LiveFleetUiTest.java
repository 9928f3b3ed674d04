package sabot.workbench.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.nio.file.StandardCopyOption;
import java.time.Duration;
import java.time.Instant;
import java.time.LocalDate;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Set;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.BooleanSupplier;
import java.util.function.Supplier;

import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.ImageLoader;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.graphics.RGB;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Control;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Event;
import org.eclipse.ui.IWorkbenchPage;
import org.eclipse.ui.PlatformUI;
import org.jivesoftware.smack.AbstractXMPPConnection;
import org.jivesoftware.smack.ConnectionCreationListener;
import org.jivesoftware.smack.ConnectionListener;
import org.jivesoftware.smack.StanzaListener;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPConnectionRegistry;
import org.jivesoftware.smack.packet.Message;
import org.jivesoftware.smack.packet.Stanza;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.MethodOrderer;
import org.junit.jupiter.api.Order;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestMethodOrder;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.jxmpp.jid.impl.JidCreate;
import org.osgi.framework.ServiceReference;

import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceProfile;
import sabot.identity.DeviceUrn;
import sabot.identity.Inventory;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.workbench.account.XmppAccount;
import sabot.workbench.account.XmppAccountStore;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.FleetListener;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.PoseLag;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.map.MapViewport;
import sabot.workbench.views.FleetView;
import sabot.workbench.views.FrameStatistics;
import sabot.workbench.views.WorkspaceView;
import sabot.testsupport.net.SilentRelay;
import sabot.testsupport.robot.OnboardProcess;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The real workbench against the real stack: a private Prosody, {@code sabot-sim} on the lab map and the onboard
 * product as processes; the workbench's ControlML plug-in connects with the account typed into its preferences. Judged
 * on the simulator's ground truth and on what the views show.
 */
@TestMethodOrder(MethodOrderer.OrderAnnotation.class)
class LiveFleetUiTest {

    static final String ROBOT = "sabot-01";
    static final String ROBOT_JID = ROBOT + "@" + PrivateXmppServer.DOMAIN;
    static final String OPERATOR = "operator";
    /** The demo's start: the lab's east room, facing +x. */
    static final double[] START = { 6.0, 2.8, 0.0 };
    /** A goal 1.6 m north in the same room (the demo's third robot stands there), facing +y. */
    static final double[] GOAL = { 6.0, 4.4, Math.PI / 2 };

    static PrivateXmppServer xmpp;
    /** Added to the workbench's connections from the first on (posesThatArriveLate...); does nothing until armed. */
    static final IngestHold HOLD = new IngestHold();
    static SimProcess sim;
    static OnboardProcess onboard;
    static long workbenchToLiveMs;

    @BeforeAll
    static void startStack() throws Exception {
        XMPPConnectionRegistry.addConnectionCreationListener(HOLD);
        xmpp = PrivateXmppServer.prosody().start();
        xmpp.register(ROBOT, PrivateXmppServer.DOMAIN, "robot-pw");
        xmpp.register(OPERATOR, PrivateXmppServer.DOMAIN, "operator-pw");
        // goals and stops: the operator's role. The robot is not in the server's robots' group yet: the lobby test puts
        // it there
        xmpp.grant(JidCreate.bareFrom(OPERATOR + "@" + PrivateXmppServer.DOMAIN), Role.OPERATOR);
        Path dir = Files.createDirectories(Paths.get("target", "live-fleet").toAbsolutePath());
        sim = SimProcess.start(dir, START);
        onboard = OnboardProcess.start(dir, new OnboardProcess.Robot(ROBOT, sim.link(1), START, xmpp.port(), xmpp
                .caFile()), "robot-pw", "");
        // the lab map where a robot keeps it for workbenches: too large for one cm.map payload
        Path maps = PrivateXmppServer.repositoryRoot().resolve("onboard-bridge/maps");
        Files.copy(maps.resolve("lab.yaml"), dir.resolve("fs/map.yaml"), StandardCopyOption.REPLACE_EXISTING);
        Files.copy(maps.resolve("lab.pgm"), dir.resolve("fs/lab.pgm"), StandardCopyOption.REPLACE_EXISTING);
        onboard.await(l -> l.contains("XMPP session online"), "saying the XMPP session is online");
        onboard.await(l -> l.contains("ready to move"), "saying the inertial biases have settled");
    }

    @AfterAll
    static void stopStack() throws Exception {
        XMPPConnectionRegistry.removeConnectionCreationListener(HOLD);
        HOLD.release();
        try {
            XmppAccountStore store = XmppAccountStore.workbenchStore();
            store.forgetPassword();
            store.saveRobots(List.of());
            // without an account the plug-in drops the fleet: the other UI tests start from an empty workbench
            waitFor(() -> fleetView().rows().isEmpty(), 20, () -> "fleet not emptied: " + fleetView().rows());
        } finally {
            // the processes go whatever failed: one left running would hold its pty and port for the next runs
            try (AutoCloseable x = xmpp; AutoCloseable s = sim; AutoCloseable o = onboard) {
                // closed in reverse order: the onboard product, the simulator, the server
            }
        }
    }

    @Test
    @Order(1)
    void workbenchConnectsAndShowsTheRobotAtItsTruePose() throws Exception {
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        store.saveRobots(List.of(ROBOT_JID));
        // first without the lab CA: the server's certificate is refused in one line, and attempts follow
        store.save(new XmppAccount("127.0.0.1", xmpp.port(), OPERATOR + "@" + PrivateXmppServer.DOMAIN, ""),
                "operator-pw".toCharArray());
        waitFor(() -> statusLineText().contains("certificate for sabot.local is not signed by"), 20,
                () -> "no certificate refusal: " + statusLineText());
        assertEquals(0, HOLD.logins(), "logged in without trusting the server");
        long t0 = System.nanoTime();
        store.save(operatorAccount(xmpp.port()), "operator-pw".toCharArray());
        WorkspaceView workspace = workspace();
        waitFor(() -> live(robotRow()) && workspace.map() != null, 60, () -> "robot not live on the map: "
                + fleetView().rows() + ", map " + workspace.map() + ", " + workspace.lastMessage());
        workbenchToLiveMs = TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0);
        System.out.printf(Locale.ROOT, "[figure] account saved to robot live in Fleet and on the map: %d ms%n",
                workbenchToLiveMs);

        RobotState r = robotRow();
        SimProcess.Truth truth = sim.truth();
        double dx = r.pose().pose().x() - truth.x();
        double dy = r.pose().pose().y() - truth.y();
        assertTrue(Math.hypot(dx, dy) < 0.05, "shown pose " + r.pose().pose() + " vs " + truth);
        assertEquals(truth.theta(), r.pose().pose().theta(), 0.05, "heading");
        assertEquals(Availability.FREE, r.availability(), r.toString());
        assertEquals(240, workspace.map().width(), "the lab map (240 x 180 cells)");

        List<String> row = FleetView.texts(r, Instant.now());
        assertTrue(row.get(0).startsWith(ROBOT), row.toString());
        assertTrue(row.get(1).startsWith("Free"), row.toString());
        assertTrue(row.get(2).startsWith(String.format(Locale.ROOT, "%.2f m, %.2f m", r.pose().pose().x(), r.pose()
                .pose().y())), row.toString());
        assertEquals(1, fleetView().table().getItemCount());

        // the battery (cm.battery, about once a second) in its column, as the simulator has it
        waitFor(() -> robotRow().battery() != null, 10, () -> "no battery reading: " + robotRow());
        java.util.regex.Matcher soc = java.util.regex.Pattern.compile("soc=([0-9.]+)").matcher(sim.command(
                "battery 1"));
        assertTrue(soc.find(), "the simulator's battery truth");
        RobotState withBattery = robotRow();
        assertEquals(Double.parseDouble(soc.group(1)), withBattery.battery().stateOfCharge(), 0.01, "state of charge");
        assertTrue(FleetView.texts(withBattery, Instant.now()).get(5).matches("[0-9]+ % · [0-9.]+ V.*"), FleetView
                .texts(withBattery, Instant.now()).toString());

        // on the map: the footprint's fill is drawn at the robot's true position
        workspace.centreOn(ROBOT_JID);
        flush();
        MapViewport v = workspace.viewport();
        // sampled half a radius behind the centre: the heading line runs from the centre forwards
        double behind = 0.5 * WorkspaceView.FOOTPRINT_RADIUS_M;
        RGB at = pixel(workspace.canvas(), sx(v, truth.x() - behind * Math.cos(truth.theta())), sy(v, truth.y() - behind
                * Math.sin(truth.theta())));
        assertTrue(at.blue > at.red + 40, "no robot drawn at its true pose: " + at);

        assertTrue(statusLineText().contains("online"), statusLineText());

        // telemetry ingest runs below the UI thread: the fleet's threads, and the Smack reader its connection thread
        // started (this JVM's other connections, the test's own, are at the normal priority)
        Set<Thread> threads = Thread.getAllStackTraces().keySet();
        List<Thread> fleetThreads = threads.stream().filter(t -> t.getName().startsWith("sabot-fleet-")).toList();
        assertFalse(fleetThreads.isEmpty(), "no fleet thread");
        for (Thread t : fleetThreads) {
            assertEquals(Thread.MIN_PRIORITY, t.getPriority(), t.getName());
        }
        assertTrue(threads.stream().anyMatch(t -> t.getName().startsWith("Smack Reader") && t.getPriority()
                == Thread.MIN_PRIORITY), "no Smack reader below the UI thread's priority");
        // (the Eclipse workbench gives its UI thread NORM_PRIORITY + 1)
        assertTrue(workspace.canvas().getDisplay().getThread().getPriority() > Thread.MIN_PRIORITY, "the UI thread");

        screenshot("workbench.png");
        capture(fleetView().table(), "fleet.png");
        // the attempt the refusal had scheduled is not made after the account changed: it would replace the session
        waitFor(() -> System.nanoTime() - t0 > TimeUnit.SECONDS.toNanos(3), 10, () -> "three seconds");
        assertEquals(1, HOLD.logins(), "logins since the lab CA was set");

        // telemetry at the rate the views look at (docs/CONTROLML.md section 6, "Leases"): the robot on the map at its
        // full rate (10 Hz, the product's default), off the map at the Fleet table's 1 Hz, on the map again at 10 Hz
        BundleContext context = FrameworkUtil.getBundle(WorkspaceView.class).getBundleContext();
        FleetState service = context.getService(context.getServiceReference(FleetState.class));
        waitFor(() -> positionRate(service) == 10, 10, () -> "the robot on the map is not leased at its full rate: "
                + positionRate(service) + " Hz");
        workspace.viewport().panByPixels(100 * workspace.canvas().getSize().x, 0);
        flush();
        waitFor(() -> positionRate(service) == FleetState.LISTED_HZ, 10, () -> "the robot off the map is not at the "
                + "Fleet table's rate: " + positionRate(service) + " Hz");
        workspace.centreOn(ROBOT_JID);
        flush();
        waitFor(() -> positionRate(service) == 10, 10, () -> "back on the map, not at its full rate: " + positionRate(
                service) + " Hz");

        // the filter above the table: on the robot's name, presence and mission, ignoring case
        FleetView fleet = fleetView();
        assertEquals(FleetView.FILTER_HINT, fleet.filterField().getMessage());
        for (String[] c : new String[][] { { "SABOT-01", "1" }, { "free", "1" }, { "busy", "0" }, { "no-such", "0" },
            { "", "1" } }) {
            fleet.filterField().setText(c[0]); // as typed: the field's modify listener filters
            flush();
            assertEquals(Integer.parseInt(c[1]), fleet.table().getItemCount(), "rows for filter '" + c[0] + "'");
        }
    }

    @Test
    @Order(2)
    void clickToGoalDrivesTheRobotThereShowingPathAndProgress() throws Exception {
        WorkspaceView workspace = workspace();
        FrameStatistics frames = FrameStatistics.of(workspace);
        MapViewport v = workspace.viewport();
        workspace.home();
        flush();
        RobotState r = robotRow();
        // select the robot by clicking its footprint, then press at the goal and drag along +y for the heading
        click(workspace.canvas(), sx(v, r.pose().pose().x()), sy(v, r.pose().pose().y()));
        assertEquals(ROBOT_JID, workspace.selectedRobot());
        int gx = sx(v, GOAL[0]);
        int gy = sy(v, GOAL[1]);
        mouse(workspace.canvas(), SWT.MouseDown, gx, gy);
        mouse(workspace.canvas(), SWT.MouseMove, gx, gy - 40);
        mouse(workspace.canvas(), SWT.MouseUp, gx, gy - 40);

        List<String> progress = new ArrayList<>();
        List<String> messages = new ArrayList<>();
        boolean[] pathShown = { false };
        boolean[] shot = { false };
        // as ./sabot demo's screenshot: taken right after the paint that first shows the running mission's path and
        // trail (WorkspaceView.whenDrawn, the hook of -sabot.screenshot.mission)
        workspace.whenDrawn(WorkspaceView::showsRunningMission, () -> {
            shot[0] = true;
            try {
                screenshot("workbench-goal.png");
            } catch (Exception e) {
                throw new AssertionError("screenshot: " + e, e);
            }
        });
        waitFor(() -> {
            RobotState now = robotRow();
            if (workspace.lastMessage() != null && (messages.isEmpty() || !messages.get(messages.size() - 1).equals(
                    workspace.lastMessage()))) {
                messages.add(workspace.lastMessage());
            }
            if (now.mission() != null && now.mission().state() == MissionState.RUNNING) {
                progress.add(FleetView.texts(now, Instant.now()).get(3));
                if (now.path() != null && now.goal() != null) {
                    pathShown[0] = true;
                }
            }
            return now.mission() != null && now.mission().state() == MissionState.DONE;
        }, 60, () -> "mission not done: " + robotRow() + "; " + workspace.lastMessage());
        assertTrue(pathShown[0], "the planned path and goal never reached the workspace");
        assertTrue(shot[0], "the running mission (path and trail) was never drawn");
        assertTrue(progress.stream().anyMatch(p -> p.matches("running [1-9][0-9]? %.*")), "no progress shown: "
                + progress);
        assertTrue(messages.stream().anyMatch(m -> m.matches(
                ".*go to \\((5\\.9|6\\.0)\\d, 4\\.[34]\\d, 1\\.57 rad\\): done")) /* one pixel is 2-3 cm */, messages
                .toString());

        printFrameTimes(frames.wallNanos());
        frames.close();

        // the mission column is filtered too
        fleetView().setFilter("DONE");
        flush();
        assertEquals(1, fleetView().table().getItemCount());
        fleetView().setFilter("running");
        flush();
        assertEquals(0, fleetView().table().getItemCount());
        fleetView().setFilter("");

        // the goal sent is the pressed pixel (about 3 cm a pixel at Home's zoom); the robot's tolerance is 0.1 m and
        // its localisation on a busy 2-core machine adds up to ~0.1 m (as the system tests allow)
        sabot.model.geometry.Pose2D sent = robotRow().goal().pose();
        assertTrue(Math.hypot(sent.x() - GOAL[0], sent.y() - GOAL[1]) < 0.05, "goal sent " + sent);
        SimProcess.Truth truth = sim.truth();
        assertTrue(truth.distanceTo(sent.x(), sent.y()) < 0.2, "robot not at the goal " + sent + ": " + truth);
        assertEquals(GOAL[2], truth.theta(), 0.3, "heading at the goal: " + truth);
    }

    @Test
    @Order(3)
    void aRefusedGoalShowsTheRobotsReason() {
        WorkspaceView workspace = workspace();
        // (3.25, 4.0) is inside the lab's partition: the robot refuses a goal in an obstacle
        workspace.sendGoal(ROBOT_JID, new sabot.controlml.payload.Goal(new sabot.model.geometry.Pose2D(3.25, 4.0, 0),
                0.1, 0.2));
        waitFor(() -> workspace.lastMessage().contains("3.25"), 20, workspace::lastMessage);
        assertTrue(workspace.lastMessage().contains("obstacle") && workspace.lastMessage().contains("invalid-value"),
                workspace.lastMessage());
    }

    /**
     * A mission of three targets built on the map (a pass, a stop facing south, a stop facing west), started with
     * Enter: the robot reaches them in order, its telemetry brings each target's state and Fleet says which target it
     * is on; it ends on the last target with its heading.
     */
    @Test
    @Order(4)
    void aMissionOfTargetsClickedOnTheMapIsDrivenTargetByTargetWithItsProgressShown() throws Exception {
        WorkspaceView workspace = workspace();
        MapViewport v = workspace.viewport();
        workspace.home();
        flush();
        RobotState r = robotRow();
        click(workspace.canvas(), sx(v, r.pose().pose().x()), sy(v, r.pose().pose().y()));
        assertEquals(ROBOT_JID, workspace.selectedRobot());
        workspace.newMission();
        assertTrue(workspace.editsMission());
        // 1: (7.2, 4.4) facing east, passed through; 2: (7.2, 3.0) facing south; 3: a click at (4.8, 3.0), facing
        // away from 2 (west). Target 3 is 1.2 m from the start, where the next test sends the robot to stop it on
        // its way: a mission ending next to it would leave that test no way to stop short of it
        double[][] targets = { { 7.2, 4.4, 0 }, { 7.2, 3.0, -Math.PI / 2 }, { 4.8, 3.0, Math.PI } };
        int[][] drags = { { 40, 0 }, { 0, 40 }, { 0, 0 } };
        for (int i = 0; i < targets.length; i++) {
            int px = sx(v, targets[i][0]);
            int py = sy(v, targets[i][1]);
            mouse(workspace.canvas(), SWT.MouseDown, px, py);
            mouse(workspace.canvas(), SWT.MouseMove, px + drags[i][0], py + drags[i][1]);
            mouse(workspace.canvas(), SWT.MouseUp, px + drags[i][0], py + drags[i][1]);
        }
        WorkbenchUiTest.key(workspace.canvas(), 0, '1', 0);
        WorkbenchUiTest.key(workspace.canvas(), 0, 'p', 0);
        WorkbenchUiTest.key(workspace.canvas(), SWT.CR, '\r', 0);

        List<Integer> currents = new ArrayList<>();
        List<String> column = new ArrayList<>();
        waitFor(() -> {
            RobotState now = robotRow();
            MissionStatus m = now.mission();
            if (m != null && !m.targets().isEmpty() && m.state() == MissionState.RUNNING) {
                if (currents.isEmpty() || currents.get(currents.size() - 1) != m.current()) {
                    currents.add(m.current());
                }
                column.add(FleetView.texts(now, Instant.now()).get(3));
            }
            return m != null && m.targets().size() == targets.length && m.state() == MissionState.DONE;
        }, 120, () -> "mission not done: " + robotRow().mission() + "; " + workspace.lastMessage());
        MissionStatus done = robotRow().mission();
        for (int i = 0; i < targets.length; i++) {
            MissionTarget t = done.targets().get(i);
            assertEquals(MissionTarget.State.REACHED, t.state(), "target " + (i + 1) + ": " + done);
            // the pressed pixel: about 3 cm a pixel at Home's zoom
            assertEquals(targets[i][0], t.goal().pose().x(), 0.05, "target " + (i + 1) + " sent: " + t);
            assertEquals(targets[i][1], t.goal().pose().y(), 0.05, "target " + (i + 1) + " sent: " + t);
            assertEquals(targets[i][2], t.goal().pose().theta(), 0.05, "target " + (i + 1) + " sent: " + t);
        }
        assertEquals(MissionTarget.Action.PASS, done.targets().get(0).action());
        assertEquals(MissionTarget.Action.STOP, done.targets().get(2).action());
        assertTrue(currents.equals(currents.stream().sorted().toList()) && currents.stream().anyMatch(c -> c > 0),
                "targets not reached in order, or no progress seen: " + currents);
        assertTrue(column.stream().anyMatch(c -> c.matches("running · target [2-3]/3 · \\d+ %.*")), "Fleet never said "
                + "which target: " + column);
        SimProcess.Truth truth = sim.truth();
        assertTrue(truth.distanceTo(targets[2][0], targets[2][1]) < 0.2, "robot not at target 3: " + truth);
        assertEquals(Math.PI, Math.abs(truth.theta()), 0.3, "heading at target 3: " + truth);
        assertTrue(workspace.lastMessage().endsWith("start a mission of 3 target(s): done"), workspace.lastMessage());
    }

    @Test
    @Order(5)
    void ctrlShiftHStopsADrivingRobot() throws Exception {
        WorkspaceView workspace = workspace();
        long sentAt = System.nanoTime();
        workspace.sendGoal(ROBOT_JID, new sabot.controlml.payload.Goal(new sabot.model.geometry.Pose2D(START[0],
                START[1], START[2]), 0.1, 0.2));
        SimProcess.Truth[] moving = new SimProcess.Truth[1];
        waitFor(() -> {
            moving[0] = truth();
            RobotState r = robotRow();
            return Math.abs(moving[0].v()) > 0.1 && r.mission() != null && r.mission().state() == MissionState.RUNNING;
        }, 30, () -> "robot not driving to the start: " + moving[0] + "; " + robotRow() + "; "
                + workspace.lastMessage());
        // the key goes where the operator's key goes: to the focus control, through the display's filters, where the
        // workbench's key-binding dispatcher looks it up in the active contexts (the Workspace view is active)
        page().activate(workspace);
        workspace.canvas().setFocus();
        flush();
        Event key = new Event();
        key.type = SWT.KeyDown;
        key.keyCode = 'h';
        key.character = (char) 0x08; // Ctrl+H as a control character, as GTK delivers it
        key.stateMask = SWT.CTRL | SWT.SHIFT;
        SimProcess.Truth atKey = truth();
        Display.getCurrent().getFocusControl().notifyListeners(SWT.KeyDown, key);
        SimProcess.Truth[] now = new SimProcess.Truth[1];
        waitFor(() -> {
            now[0] = truth();
            RobotState r = robotRow();
            return Math.abs(now[0].v()) < 0.005 && Math.abs(now[0].omega()) < 0.01 && r.mission() != null && r
                    .mission().state() == MissionState.ABORTED;
        }, 10, () -> "robot not stopped by Ctrl+Shift+H: " + now[0] + "; " + robotRow() + "; "
                + workspace.lastMessage());
        System.out.printf(Locale.ROOT, "[figure] Ctrl+Shift+H to standstill (simulator clock): %.3f s from %.3f m/s%n",
                now[0].t() - atKey.t(), atKey.v());
        waitFor(() -> String.valueOf(workspace.lastMessage()).startsWith(FleetJobs.STOP_ALL), 10,
                workspace::lastMessage);
        assertEquals(FleetJobs.STOP_ALL + ": 1 of 1 robot(s) stopped", workspace.lastMessage());
        assertTrue(truth().distanceTo(START[0], START[1]) > 0.2, "it was not stopped: it arrived");
    }

    @Test
    @Order(6)
    void theServersRobotsGroupBringsARobotIntoTheFleetAndALobbyImpostorNever() throws Exception {
        String room = "fleet@conference." + PrivateXmppServer.DOMAIN;
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        // forget the robot: not configured (rule 12), not in the operator's roster
        store.saveRobots(List.of());
        org.jivesoftware.smack.tcp.XMPPTCPConnection admin = xmpp.connect(xmpp.configuration(OPERATOR,
                PrivateXmppServer.DOMAIN, "operator-pw").setResource("admin").setSendPresence(false).build());
        org.jivesoftware.smack.roster.Roster roster = org.jivesoftware.smack.roster.Roster.getInstanceFor(admin);
        roster.reloadAndWait();
        roster.removeEntry(roster.getEntry(JidCreate.entityBareFrom(ROBOT_JID)));
        waitFor(() -> fleetView().rows().isEmpty(), 20, () -> "robot still in the fleet: " + fleetView().rows());
        // in the lobby: the robot (its account's second resource, which sends no presence of its own) and an
        // impostor, an account whose own vCard says it is one of the lab's robots
        org.jivesoftware.smack.tcp.XMPPTCPConnection robotInLobby = xmpp.connect(xmpp.configuration(ROBOT,
                PrivateXmppServer.DOMAIN, "robot-pw").setResource("lobby").setSendPresence(false).build());
        org.jivesoftware.smack.tcp.XMPPTCPConnection impostor = xmpp.login("impostor");
        DeviceProfile claim = new DeviceProfile("mobile robot", "Sabot", "SabotOne", "sabot-99", null, 45.76, 4.83,
                DeviceUrn.urnOf("SN-impostor"), impostor.getUser().asBareJid().toString(), "robot", LocalDate.of(
                        2026, 11, 29), null, null);
        try {
            DeviceIdentityManager.getInstanceFor(impostor).publish(claim, new Inventory(1, claim.uid(),
                    new Inventory.Mechanic("chassis", List.of()), List.of(new Inventory.Board("pc", "x86_64", null,
                            List.of(), List.of(new Inventory.Item("sabot.onboard", "0.1.0")), List.of())), List.of()))
                    .orElseThrow();
            for (var c : List.of(robotInLobby, impostor)) {
                new sabot.fleet.FleetLobby(c, JidCreate.entityBareFrom(room)).join();
            }
            int logins = HOLD.logins();
            store.saveLobby(room);
            // the new session compiles the lobby before its status says online
            waitFor(() -> HOLD.logins() > logins && statusLineText().contains("online"), 30, () -> "not online "
                    + "again with the lobby: " + statusLineText());
            assertTrue(fleetView().rows().isEmpty(), "followed on its own vCard: " + fleetView().rows());
            // the server's word: the lab's administrator puts the robot into the robots' group
            long t0 = System.nanoTime();
            xmpp.enrolRobot(JidCreate.bareFrom(ROBOT_JID));
            waitFor(() -> live(robotRow()), 30, () -> "robot not in the fleet: " + fleetView().rows());
            System.out.printf(Locale.ROOT, "[figure] robot put into the server's robots' group to live in Fleet: %d "
                    + "ms%n", TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0));
            assertEquals(List.of(ROBOT_JID), fleetView().rows().stream().map(RobotState::jid).toList(),
                    "only the server's robot");
        } finally {
            store.saveLobby("");
            store.saveRobots(List.of(ROBOT_JID)); // as before: the class's end empties it, and the fleet with it
            robotInLobby.instantShutdown();
            impostor.instantShutdown();
            admin.instantShutdown();
        }
    }

    /**
     * Poses that keep arriving but late grey the robot (RobotState.isLate), as when the workbench's ingest falls behind
     * on a busy CPU: {@link #HOLD} holds the workbench connection's in-order listener thread on the robot's next
     * message until the last receipt is older than {@link RobotState#STALE_AFTER} + 1 s. The robot's telemetry queues
     * behind it, then arrives in a burst, each pose received just now: judged by the lag over the robot's fastest
     * pose the first ones are stale, the Fleet row says how late, and once the backlog is through the robot is live
     * again.
     */
    @Test
    @Order(7)
    void posesThatArriveLateGreyTheRobotUntilTheBacklogIsThrough() throws Exception {
        BundleContext context = FrameworkUtil.getBundle(WorkspaceView.class).getBundleContext();
        ServiceReference<FleetState> ref = context.getServiceReference(FleetState.class);
        FleetState fleet = context.getService(ref);
        List<RobotState> late = new CopyOnWriteArrayList<>();
        AtomicInteger restarts = new AtomicInteger();
        FleetListener onLate = r -> {
            if (r.jid().equals(ROBOT_JID) && r.poseLag() == null) {
                restarts.incrementAndGet(); // offline, or online again: the lag's measurement starts anew
            } else if (r.jid().equals(ROBOT_JID) && r.isLate()) {
                late.add(r);
            }
        };
        fleet.addListener(onLate);
        Duration stall = RobotState.STALE_AFTER.plusSeconds(1);
        try {
            // the lag is measured against the fastest pose since the robot last came online: half a second of poses
            // on time since then first. The previous test's end saves the account twice, and each save connects the
            // workbench anew, which starts the measurement again with the robot's first pose: counted by the listener
            // and read before the lag, so that the half second counts from the last start
            int[] seenRestarts = {-1};
            Instant[] since = {null};
            waitFor(() -> {
                int now = restarts.get();
                RobotState robot = fleet.robot(ROBOT_JID).orElse(null);
                PoseLag lag = robot == null ? null : robot.poseLag();
                if (lag == null || now != seenRestarts[0]) {
                    seenRestarts[0] = lag == null ? -1 : now;
                    since[0] = lag == null ? null : lag.stamp();
                    return false;
                }
                return live(robot) && lag.stamp().isAfter(since[0].plusMillis(500));
            }, 30, () -> "robot not live with half a second of poses: " + fleet.robot(ROBOT_JID));
            assertTrue(late.isEmpty(), "late before the ingest was held: " + late);
            HOLD.arm();
            try {
                // nothing is taken in while the ingest is held: stale by the age of the last receipt
                waitFor(() -> HOLD.holding() && fleet.robot(ROBOT_JID).map(r -> r.telemetryAge(Instant.now())
                        .compareTo(stall) > 0).orElse(false), 20, () -> "ingest not held: " + fleet.robot(ROBOT_JID));
                assertTrue(late.isEmpty(), "late while the ingest was held: " + late);
            } finally {
                HOLD.release();
            }
            waitFor(() -> !late.isEmpty() && live(fleet.robot(ROBOT_JID).orElse(null)), 20, () -> "no late pose, or "
                    + "not live again: " + late.size() + " late; " + fleet.robot(ROBOT_JID).map(RobotState::poseLag));
            RobotState first = late.get(0);
            Instant received = first.lastTelemetry();
            assertTrue(first.isStale(received), "received at once but late: " + first.poseLag());
            assertTrue(first.poseLag().lag().compareTo(RobotState.STALE_AFTER) > 0, first.poseLag().toString());
            String age = FleetView.texts(first, received).get(4);
            assertTrue(age.matches("0\\.0 s, [0-9.]+ s late"), age);
            System.out.printf(Locale.ROOT, "[figure] ingest held %.1f s: first pose after it %.2f s late, %d late "
                    + "pose(s) until live again%n", stall.toMillis() / 1e3, first.poseLag().lagNanos() / 1e9, late
                            .stream().map(r -> r.pose().time()).distinct().count());
        } finally {
            HOLD.release();
            fleet.removeListener(onLate);
            context.ungetService(ref);
        }
    }

    /**
     * The workbench's own link goes silent — nothing passes, nothing is closed (a relay between the workbench and the
     * server stops forwarding, as a Wi-Fi dead spot does): the workbench notices within two liveness intervals and a
     * quarter, shows the robot offline and says why on its status line; once traffic passes again it reconnects and
     * the robot is live again.
     */
    @Test
    @Order(8)
    void aSilentLinkGreysTheRobotAndTheWorkbenchReconnects() throws Exception {
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        BundleContext context = FrameworkUtil.getBundle(WorkspaceView.class).getBundleContext();
        ServiceReference<FleetState> ref = context.getServiceReference(FleetState.class);
        FleetState fleet = context.getService(ref);
        List<String> statuses = new CopyOnWriteArrayList<>();
        FleetListener watch = new FleetListener() {
            @Override
            public void robotChanged(RobotState robot) {
            }

            @Override
            public void connectionChanged(sabot.workbench.fleet.ConnectionStatus status) {
                statuses.add(status.summary());
            }
        };
        fleet.addListener(watch);
        try (SilentRelay relay = new SilentRelay(xmpp.port())) {
            store.save(operatorAccount(relay.port()),
                    "operator-pw".toCharArray());
            waitFor(() -> live(robotRow()) && statusLineText().contains(":" + relay.port()), 60,
                    () -> "robot not live through the relay: " + fleetView().rows() + "; " + statusLineText());
            long silenced = System.nanoTime();
            relay.silence();
            waitFor(() -> robotRow() != null && robotRow().availability() == Availability.OFFLINE, 20,
                    () -> "silence not noticed: " + statusLineText() + "; " + robotRow());
            System.out.printf(Locale.ROOT, "[figure] workbench link silent to robot shown offline: %d ms (liveness "
                    + "%.1f s)%n", TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - silenced),
                    sabot.fleet.LinkWatch.DEFAULT_INTERVAL_S);
            assertTrue(statuses.stream().anyMatch(t -> t.contains("offline (connection silent for")),
                    "the status line never said why: " + statuses);
            relay.resume();
            waitFor(() -> live(robotRow()), 60, () -> "robot not live again after the silence: " + fleetView().rows()
                    + "; " + statusLineText());
        } finally {
            fleet.removeListener(watch);
            context.ungetService(ref);
            store.save(operatorAccount(xmpp.port()),
                    "operator-pw".toCharArray());
        }
    }

    /**
     * A robot new to the lab, enrolled with a token (docs/SECURITY.md, "Enrolment"): asking for access, it is listed
     * below the Fleet table with the identity of its vCard (UUID, the QR code of its inventory) and is not in the
     * fleet; approved on the server, it joins the fleet and leaves the list.
     */
    @Test
    @Order(9)
    void aRobotAskingForAccessIsListedWithItsIdentityAndJoinsTheFleetWhenApproved() throws Exception {
        String jid = "sabot-07@" + PrivateXmppServer.DOMAIN;
        org.jxmpp.jid.EntityBareJid robot = JidCreate.entityBareFrom(jid);
        String token = xmpp.enrolToken(robot);
        org.jivesoftware.smack.tcp.XMPPTCPConnection asking = xmpp.connect(xmpp.configuration("sabot-07",
                PrivateXmppServer.DOMAIN, token).setResource("onboard").build());
        try {
            sabot.fleet.Enrolment.replaceToken(asking, sabot.fleet.Enrolment.newPassword());
            DeviceProfile profile = new DeviceProfile("mobile robot", "Sabot", "SabotOne", "sabot-07", null, 45.76,
                    4.83, DeviceUrn.urnOf("SN-0007"), jid, "robot", LocalDate.of(2026, 11, 29), null, null);
            DeviceIdentityManager.getInstanceFor(asking).publish(profile, new Inventory(1, profile.uid(),
                    new Inventory.Mechanic("chassis", List.of()), List.of(new Inventory.Board("pc", "x86_64", null,
                            List.of(), List.of(new Inventory.Item("sabot.onboard", "0.1.0")), List.of())), List.of()))
                    .orElseThrow();
            // the vCard is stored before the roster shows the request: the row reads it at once
            List<String> expected = List.of("sabot-07 <" + jid + ">", profile.uid().toString());
            waitFor(() -> fleetView().accessRequestRows().contains(expected), 30, () -> "no request from " + jid
                    + " with its identity: " + fleetView().accessRequestRows());
            assertTrue(fleetView().rows().stream().noneMatch(r -> r.jid().equals(jid)), "in the fleet unapproved");
            assertEquals(FleetView.ACCESS_REQUESTS_TOOLTIP, fleetView().accessRequestTable().getToolTipText());
            capture(fleetView().accessRequestTable().getParent(), "fleet-asking-for-access.png");

            long t0 = System.nanoTime();
            xmpp.approve(robot);
            waitFor(() -> fleetView().rows().stream().anyMatch(r -> r.jid().equals(jid) && r.availability()
                    != Availability.OFFLINE) && fleetView().accessRequestRows().isEmpty(), 30,
                    () -> "not in the fleet once approved: " + fleetView().rows() + "; asking: "
                            + fleetView().accessRequestRows());
            System.out.printf(Locale.ROOT, "[figure] robot approved (sabot-xmpp enrol approve) to online in Fleet: "
                    + "%d ms%n", TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0));
            assertFalse(fleetView().accessRequestTable().isVisible(), "the empty list is still shown");
        } finally {
            asking.instantShutdown();
            // out of the lab's robots again: the class ends with the fleet it started with
            xmpp.group("remove", sabot.fleet.AccessRules.ROBOTS_GROUP, robot);
            waitFor(() -> fleetView().rows().stream().noneMatch(r -> r.jid().equals(jid)), 20,
                    () -> "still in the fleet: " + fleetView().rows());
        }
    }

    /**
     * A goal for a robot that is down (docs/CONTROLML.md section 5): the workbench queues it at the server and Fleet
     * lists it; the robot's product, back after more than its stale limit (5 s), refuses it
     * and stays where it is; the refusal reaches the status line and the list empties.
     */
    @Test
    @Order(10)
    void aGoalForARobotThatIsDownWaitsInFleetAndIsRefusedAsStaleWhenItComesBackLate() throws Exception {
        onboard.close();
        waitFor(() -> robotRow() != null && robotRow().availability() == Availability.OFFLINE, 20,
                () -> "robot not offline: " + robotRow());
        WorkspaceView workspace = workspace();
        workspace.sendGoal(ROBOT_JID, new sabot.controlml.payload.Goal(new sabot.model.geometry.Pose2D(GOAL[0], GOAL[1],
                GOAL[2]), 0.1, 0.3));
        waitFor(() -> missionText().startsWith("queued until online: go to (6.00, 4.40, 1.57 rad)"), 10,
                () -> "not listed as queued: " + missionText());
        assertTrue(workspace.lastMessage().contains("queued until sabot-01 is online"), workspace.lastMessage());
        SimProcess.Truth before = truth();
        // back later than its stale limit: the rule is one of time, so the test lets that time pass from the moment
        // the command left (the fleet's request pool may send it later than the click), not a wait for an event
        Instant queuedAt = queuedAt(ROBOT_JID);
        long late = Duration.between(Instant.now(), queuedAt.plusMillis(STALE_LIMIT_MS + 500)).toMillis();
        if (late > 0) {
            TimeUnit.MILLISECONDS.sleep(late);
        }
        onboard = OnboardProcess.start(onboard.config());
        onboard.await(l -> l.contains("XMPP session online"), "saying the XMPP session is online again");
        waitFor(() -> workspace.lastMessage().contains("(queued): ") && !missionText().startsWith("queued"), 30,
                () -> "no answer shown: " + workspace.lastMessage() + "; " + missionText());
        assertTrue(workspace.lastMessage().contains("stale-command"), workspace.lastMessage());
        onboard.await(l -> l.contains("ready to move"), "saying the inertial biases have settled");
        waitFor(() -> live(robotRow()), 30, () -> "robot not live again: " + robotRow());
        assertTrue(truth().distanceTo(before.x(), before.y()) < 0.02, "a stale goal moved the robot");
    }

    /** The robot's {@code controlml.staleCommandAfter}: the product's default, ms. */
    static final long STALE_LIMIT_MS = TimeUnit.SECONDS.toMillis(sabot.controlml.ControlMl.DEFAULT_STALE_COMMAND_S);

    /** @return when the fleet sent the command it has queued for {@code robot} (the workbench's clock) */
    private static Instant queuedAt(String robot) {
        BundleContext context = FrameworkUtil.getBundle(WorkspaceView.class).getBundleContext();
        ServiceReference<FleetState> ref = context.getServiceReference(FleetState.class);
        try {
            return context.getService(ref).queuedCommands().stream().filter(q -> q.robot().equals(robot)).findFirst()
                    .orElseThrow(() -> new AssertionError("nothing queued for " + robot)).queuedAt();
        } finally {
            context.ungetService(ref);
        }
    }

    /** @return the robot's Mission cell as Fleet shows it */
    private static String missionText() {
        for (org.eclipse.swt.widgets.TableItem item : fleetView().table().getItems()) {
            if (item.getData() instanceof RobotState r && r.jid().equals(ROBOT_JID)) {
                return item.getText(3);
            }
        }
        return "(no row)";
    }

    /**
     * Holds the workbench's ingest once when armed: a synchronous stanza listener that the test's code adds to each
     * connection the workbench makes (Smack's connection-creation hook; the plug-in's code is unchanged). Smack calls a
     * connection's synchronous listeners in order on one thread, so everything received after the held message waits.
     */
    private static final class IngestHold implements ConnectionCreationListener, StanzaListener {
        private final AtomicBoolean armed = new AtomicBoolean();
        private final AtomicInteger logins = new AtomicInteger();
        private volatile CountDownLatch release = new CountDownLatch(0);
        private volatile boolean holding;

        @Override
        public void connectionCreated(XMPPConnection c) {
            if (OPERATOR.equals(String.valueOf(((AbstractXMPPConnection) c).getConfiguration().getUsername()))) {
                c.addConnectionListener(new ConnectionListener() {
                    @Override
                    public void authenticated(XMPPConnection connection, boolean resumed) {
                        logins.incrementAndGet();
                    }
                });
                c.addSyncStanzaListener(this, s -> s instanceof Message && s.getFrom() != null && s.getFrom()
                        .asBareJid().toString().equals(ROBOT_JID));
            }
        }

        /** Holds the robot's next message until {@link #release()}. */
        void arm() {
            release = new CountDownLatch(1);
            armed.set(true);
        }

        /** @return how many times the workbench's connections logged in */
        int logins() {
            return logins.get();
        }

        boolean holding() {
            return holding;
        }

        void release() {
            release.countDown();
        }

        @Override
        public void processStanza(Stanza stanza) throws InterruptedException {
            if (armed.compareAndSet(true, false)) {
                holding = true;
                try {
                    release.await(30, TimeUnit.SECONDS); // the test releases it; the bound only guards a failed test
                } finally {
                    holding = false;
                }
            }
        }
    }

    // ------------------------------------------------------------------------------------------------ helpers

    private static SimProcess.Truth truth() {
        try {
            return sim.truth();
        } catch (java.io.IOException e) {
            throw new AssertionError("simulator truth: " + e, e);
        }
    }

    /** The figure of docs/WORKBENCH.md: paint time of the workspace (map, grid, robot, path, trail) while it drove. */
    private static void printFrameTimes(long[] nanos) {
        long[] sorted = nanos.clone();
        java.util.Arrays.sort(sorted);
        if (sorted.length == 0) {
            return;
        }
        System.out.printf(Locale.ROOT, "[figure] workspace frame time, 1 live robot on the lab map: n=%d p50=%.2f ms "
                + "p99=%.2f ms max=%.2f ms%n", sorted.length, sorted[sorted.length / 2] / 1e6, sorted[(int) Math.min(
                        sorted.length - 1, Math.ceil(sorted.length * 0.99) - 1)] / 1e6, sorted[sorted.length - 1] / 1e6);
    }

    static boolean live(RobotState r) {
        return r != null && r.availability() != Availability.OFFLINE && r.pose() != null && !r.isStale(Instant.now());
    }

    private static RobotState robotRow() {
        return fleetView().rows().stream().filter(r -> r.jid().equals(ROBOT_JID)).findFirst().orElse(null);
    }

    static IWorkbenchPage page() {
        return PlatformUI.getWorkbench().getActiveWorkbenchWindow().getActivePage();
    }

    private static WorkspaceView workspace() {
        WorkspaceView w = (WorkspaceView) page().findView(WorkspaceView.ID);
        assertNotNull(w, "workspace view not open");
        return w;
    }

    static FleetView fleetView() {
        FleetView f = (FleetView) page().findView(FleetView.ID);
        assertNotNull(f, "fleet view not open");
        return f;
    }

    static String statusLineText() {
        // the item's label, found in the window's widgets (the status line manager is the window's own business)
        List<String> texts = new ArrayList<>();
        collectLabels(PlatformUI.getWorkbench().getActiveWorkbenchWindow().getShell(), texts);
        return texts.stream().filter(t -> t.contains(OPERATOR + "@")).findFirst().orElse("no connection item in "
                + texts);
    }

    private static void collectLabels(Control c, List<String> texts) {
        if (c instanceof org.eclipse.swt.custom.CLabel l && l.getText() != null) {
            texts.add(l.getText());
        }
        if (c instanceof org.eclipse.swt.widgets.Composite composite) {
            for (Control child : composite.getChildren()) {
                collectLabels(child, texts);
            }
        }
    }

    private static int sx(MapViewport v, double x) {
        return (int) Math.round(v.toScreenX(x));
    }

    private static int sy(MapViewport v, double y) {
        return (int) Math.round(v.toScreenY(y));
    }

    /**
     * Runs the UI's event loop until {@code condition} holds. The robot and the server are other processes: a 20 ms
     * timer wakes the loop to look again, up to the deadline.
     */
    static void waitFor(BooleanSupplier condition, double seconds, Supplier<String> what) {
        Display d = Display.getCurrent();
        long deadline = System.nanoTime() + (long) (seconds * 1e9);
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() > deadline) {
                throw new AssertionError("within " + seconds + " s: " + what.get() + "\nonboard console tail:\n"
                        + tail(onboard == null ? "" : onboard.output()));
            }
            d.timerExec(20, () -> {
            });
            if (!d.readAndDispatch()) {
                d.sleep();
            }
        }
    }

    /** @return the rate the robot publishes its position at now, as it says (cm.telemetry), or -1 */
    private static double positionRate(FleetState fleet) {
        try {
            return fleet.get(ROBOT_JID, Resources.TELEMETRY).get(5, TimeUnit.SECONDS).stream("cm.position").rate();
        } catch (Exception e) {
            return -1;
        }
    }

    private static String tail(String s) {
        return s.length() > 3000 ? s.substring(s.length() - 3000) : s;
    }

    private static void flush() {
        Display d = Display.getCurrent();
        workspace().canvas().redraw();
        fleetView().table().redraw();
        PlatformUI.getWorkbench().getActiveWorkbenchWindow().getShell().update();
        while (d.readAndDispatch()) {
            // layout and paint
        }
    }

    private static void click(Control c, int x, int y) {
        mouse(c, SWT.MouseDown, x, y);
        mouse(c, SWT.MouseUp, x, y);
    }

    private static void mouse(Control c, int type, int x, int y) {
        WorkbenchUiTest.mouse(c, type, x, y);
    }

    private static RGB pixel(Control c, int x, int y) {
        Display d = c.getDisplay();
        Point p = c.toDisplay(x, y);
        Image image = new Image(d, 1, 1);
        GC gc = new GC(d);
        try {
            gc.copyArea(image, p.x, p.y);
            ImageData data = image.getImageData();
            return data.palette.getRGB(data.getPixel(0, 0));
        } finally {
            gc.dispose();
            image.dispose();
        }
    }

    private static void screenshot(String name) throws Exception {
        flush();
        DocScreenshots.window(name);
    }

    /** Saves what the screen shows of one control (a view's area). */
    private static void capture(Control c, String name) throws Exception {
        flush();
        Display d = c.getDisplay();
        Rectangle b = c.getBounds();
        Point origin = c.getParent().toDisplay(b.x, b.y);
        Image image = new Image(d, b.width, b.height);
        GC gc = new GC(d);
        Path png = screenshots().resolve(name);
        try {
            gc.copyArea(image, origin.x, origin.y);
            ImageLoader loader = new ImageLoader();
            loader.data = new ImageData[] { image.getImageData() };
            loader.save(png.toString(), SWT.IMAGE_PNG);
        } finally {
            gc.dispose();
            image.dispose();
        }
        toDocs(png);
    }

    static Path screenshots() throws Exception {
        return DocScreenshots.screenshots();
    }

    static void toDocs(Path png) throws Exception {
        DocScreenshots.toDocs(png);
    }

    /** @return the operator's account on 127.0.0.1:{@code port}, trusting the private server's lab CA */
    private static XmppAccount operatorAccount(int port) {
        return new XmppAccount("127.0.0.1", port, OPERATOR + "@" + PrivateXmppServer.DOMAIN, xmpp.caFile().toString());
    }
}
