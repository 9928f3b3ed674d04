package sabot.workbench.internal;

import static sabot.workbench.internal.LiveFleetUiTest.fleetView;
import static sabot.workbench.internal.LiveFleetUiTest.live;
import static sabot.workbench.internal.LiveFleetUiTest.statusLineText;
import static sabot.workbench.internal.LiveFleetUiTest.waitFor;

import java.time.Instant;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.jxmpp.jid.EntityBareJid;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.framework.ServiceReference;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.TelemetryPublication;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.fleet.AccessRules;
import sabot.fleet.PresenceLevels;
import sabot.model.geometry.Pose2D;
import sabot.workbench.account.XmppAccount;
import sabot.workbench.account.XmppAccountStore;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The workbench on a two-node ejabberd cluster (docs/CLUSTER.md): its account names both nodes
 * ({@code 127.0.0.1,127.0.0.2}); it connects through node 1 and shows a robot logged in on node 2 (telemetry crossing
 * the nodes); node 1 dies; the workbench is back through node 2 and the robot live again in Fleet.
 */
class ClusterFleetUiTest {

    static final String OPERATOR = "operator";
    static PrivateXmppServer xmpp;
    static XMPPTCPConnection robot;
    static TelemetryPublication poses;

    @BeforeAll
    static void startCluster() throws Exception {
        xmpp = PrivateXmppServer.ejabberdCluster().start();
        EntityBareJid robotJid = xmpp.register("cl-robot", PrivateXmppServer.DOMAIN, "robot-pw");
        EntityBareJid operator = xmpp.register(OPERATOR, PrivateXmppServer.DOMAIN, "operator-pw");
        xmpp.enrolRobot(robotJid);
        xmpp.grant(operator, Role.OPERATOR);
        // a device on node 2, which stays: it publishes its pose at 10 Hz and says it is free
        robot = xmpp.connect(xmpp.configuration(2, "cl-robot", PrivateXmppServer.DOMAIN, "robot-pw").setResource(
                "onboard").build());
        ControlMlManager manager = ControlMlManager.getInstanceFor(robot);
        manager.setAccessPolicy(AccessRules.labGroups().on(robot));
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

    @Test
    void theWorkbenchFailsOverToTheOtherNodeAndTheRobotIsLiveAgain() throws Exception {
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        store.saveRobots(List.of());
        store.saveLobby("");
        store.save(new XmppAccount(xmpp.address(1).getHostAddress() + "," + xmpp.address(2).getHostAddress(), xmpp
                .port(), OPERATOR + "@" + PrivateXmppServer.DOMAIN, xmpp.caFile().toString()), "operator-pw"
                        .toCharArray());
        String jid = robot.getUser().asBareJid().toString();
        waitFor(() -> statusLineText().contains("online") && statusLineText().contains("127.0.0.1:") && live(row(jid)),
                30, () -> "robot not live through node 1: " + fleetView().rows() + "; " + statusLineText());

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
