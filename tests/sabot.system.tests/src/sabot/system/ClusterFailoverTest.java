package sabot.system;

import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.util.Locale;
import java.util.concurrent.TimeUnit;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The product on a two-node ejabberd cluster (docs/CLUSTER.md): the robot configured with both nodes logs in through
 * node 1; node 1 dies; the robot is back through node 2 within seconds, and the operator (on node 2) sends it a goal
 * that it drives (the simulator's truth).
 */
class ClusterFailoverTest extends RigTest {

    @Override
    protected PrivateXmppServer newServer() {
        return PrivateXmppServer.ejabberdCluster();
    }

    @Test
    void aRobotWhoseNodeDiesIsBackThroughTheOtherAndDrives(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.startOnCluster(xmpp, dir, CORRIDOR_WEST)) {
            rig.onboard.await(l -> l.contains("online as") && l.contains("through 127.0.0.1"),
                    "saying it is online through node 1");
            long t0 = System.nanoTime();
            xmpp.killNode(1);
            rig.onboard.await(l -> l.contains("online as") && l.contains("through 127.0.0.2"),
                    "saying it is online again, through node 2");
            System.out.printf(Locale.ROOT, "[figure] ejabberd cluster: node 1 killed to the product online through "
                    + "node 2: %d ms (reconnectMin 1 s)%n", TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0));

            SimProcess.Truth before = rig.sim.truth();
            Goal goal = new Goal(new Pose2D(before.x() + 1.0, before.y(), 0), 0.1, 0.3);
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, goal).isSuccess(), rig.onboard.output());
            awaitTruth(rig.sim, t -> t.x() > before.x() + 0.3, 20, "driving to the goal sent after the failover");
        }
    }
}
