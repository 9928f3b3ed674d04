package sabot.workbench.internal;

import static sabot.workbench.internal.LiveFleetUiTest.fleetView;
import static sabot.workbench.internal.LiveFleetUiTest.live;
import static sabot.workbench.internal.LiveFleetUiTest.statusLineText;
import static sabot.workbench.internal.LiveFleetUiTest.waitFor;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Instant;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.eclipse.swt.widgets.Shell;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.MethodOrderer;
import org.junit.jupiter.api.Order;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestMethodOrder;
import org.jxmpp.jid.EntityBareJid;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.framework.ServiceReference;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.TelemetryPublication;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.fleet.AccessRules;
import sabot.fleet.ArchivedCommand;
import sabot.fleet.PresenceLevels;
import sabot.model.geometry.Pose2D;
import sabot.workbench.account.XmppAccount;
import sabot.workbench.account.XmppAccountStore;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.workbench.views.CommandHistoryDialog;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The workbench on a two-node ejabberd cluster (docs/CLUSTER.md): its account names both nodes
 * ({@code 127.0.0.1,127.0.0.2}); it connects through node 1 and shows a robot logged in on node 2 (telemetry crossing
 * the nodes); the robot's command history from the cluster's archive (docs/ARCHIVE.md); node 1 dies; the workbench
 * is back through node 2 and the robot live again in Fleet.
 */
@TestMethodOrder(MethodOrderer.OrderAnnotation.class)
class ClusterFleetUiTest {

    static final String OPERATOR = "operator";
    static PrivateXmppServer xmpp;
    static XMPPTCPConnection robot;
    static TelemetryPublication poses;

    @BeforeAll
    static void startCluster() throws Exception {
        xmpp = PrivateXmppServer.ejabberdCluster().sqlArchive().start();
        EntityBareJid robotJid = xmpp.register("cl-robot", PrivateXmppServer.DOMAIN, "robot-pw");
        EntityBareJid operator = xmpp.register(OPERATOR, PrivateXmppServer.DOMAIN, "operator-pw");
        xmpp.enrolRobot(robotJid);
        xmpp.grant(operator, Role.OPERATOR);
        // a device on node 2, which stays: it publishes its pose at 10 Hz and says it is free
        robot = xmpp.connect(xmpp.configuration(2, "cl-robot", PrivateXmppServer.DOMAIN, "robot-pw").setResource(
                "onboard").build());
        ControlMlManager manager = ControlMlManager.getInstanceFor(robot);
        manager.setAccessPolicy(AccessRules.labGroups().on(robot));
        manager.onSet(Resources.GOAL, (requester, goal) -> Outcome.done());
        robot.sendStanza(PresenceLevels.presenceFor(robot, MissionState.IDLE, false));
        poses = manager.telemetry().publish(Resources.POSITION, () -> new PoseEstimate(Instant.now(), new Pose2D(2, 3,
                0), PoseCovariance.diagonal(0.01, 0.01, 0.01)), 10);
    }

    @AfterAll
    static void stopCluster() throws Exception {
        try {
            XmppAccountStore store = XmppAccountStore.workbenchStore();
            store.forgetPassword();
            // a password alone changed: the plug-in is told (FleetState.reconnect), and drops the fleet without one
            BundleContext context = FrameworkUtil.getBundle(ClusterFleetUiTest.class).getBundleContext();
            ServiceReference<FleetState> ref = context.getServiceReference(FleetState.class);
            try {
                context.getService(ref).reconnect();
            } finally {
                context.ungetService(ref);
            }
            waitFor(() -> fleetView().rows().isEmpty(), 20, () -> "fleet not emptied: " + fleetView().rows());
        } finally {
            if (poses != null) {
                poses.close();
            }
            xmpp.close();
        }
    }

    /** The workbench's account names both nodes; it connects through node 1 and the robot (on node 2) is live. */
    private static String online() throws IOException {
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        XmppAccount account = new XmppAccount(xmpp.address(1).getHostAddress() + "," + xmpp.address(2)
                .getHostAddress(), xmpp.port(), OPERATOR + "@" + PrivateXmppServer.DOMAIN, xmpp.caFile().toString());
        if (!account.equals(store.load())) {
            store.saveRobots(List.of());
            store.saveLobby("");
            store.save(account, "operator-pw".toCharArray());
        }
        String jid = robot.getUser().asBareJid().toString();
        waitFor(() -> statusLineText().contains("online") && statusLineText().contains("127.0.0.1:") && live(row(jid)),
                30, () -> "robot not live through node 1: " + fleetView().rows() + "; " + statusLineText());
        return jid;
    }

    /** The archive of every ControlML stanza (docs/ARCHIVE.md), read from the Fleet view's context menu. */
    @Test
    @Order(1)
    void theCommandHistoryShowsTheGoalTheWorkbenchSentWithTheRobotsAnswer() throws Exception {
        String jid = online();
        FleetState fleet = fleetView().fleetState();
        CompletableFuture<Void> sent = fleet.goTo(jid, new Goal(new Pose2D(1.5, 0.5, 0), 0.1, 0.1));
        waitFor(sent::isDone, 10, () -> "goal not answered");
        sent.join();
        CommandHistoryDialog dialog = fleetView().openCommandHistory(jid);
        try {
            waitFor(() -> !dialog.shown().isEmpty(), 10, dialog::statusText);
            ArchivedCommand goal = dialog.shown().get(0);
            List<String> row = CommandHistoryDialog.texts(goal);
            assertEquals("cm.goal", row.get(2), row.toString());
            assertEquals("result", row.get(3), row.toString());
            assertTrue(row.get(1).startsWith(OPERATOR + "@" + PrivateXmppServer.DOMAIN + "/"), row.toString());
            assertTrue(dialog.statusText().startsWith("1 command(s)"), dialog.statusText());
            // what the screen shows: the rows painted first
            Shell shell = dialog.getShell();
            shell.layout(true, true);
            shell.redraw();
            shell.update();
            while (shell.getDisplay().readAndDispatch()) {
                // layout and paint
            }
            Path png = LiveFleetUiTest.screenshots().resolve("command-history.png");
            SabotWindowAdvisor.saveScreenshot(shell, png);
            LiveFleetUiTest.toDocs(png);
        } finally {
            dialog.close();
        }
    }

    @Test
    @Order(2)
    void theWorkbenchFailsOverToTheOtherNodeAndTheRobotIsLiveAgain() throws Exception {
        String jid = online();

        long t0 = System.nanoTime();
        xmpp.killNode(1);
        waitFor(() -> statusLineText().contains("online") && statusLineText().contains("127.0.0.2:") && live(row(jid)),
                30, () -> "not back through node 2: " + fleetView().rows() + "; " + statusLineText());
        System.out.printf(Locale.ROOT, "[figure] ejabberd cluster: node 1 killed to the robot live again in the "
                + "workbench's Fleet through node 2: %d ms%n", TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0));
    }

    private static RobotState row(String jid) {
        return fleetView().rows().stream().filter(r -> r.jid().equals(jid)).findFirst().orElse(null);
    }
}
