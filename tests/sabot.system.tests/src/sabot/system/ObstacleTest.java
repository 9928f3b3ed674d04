package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.SimProcess;

/**
 * Proof 2: an obstacle placed on the path while the robot drives. The sonar sees it, the robot replans around it and
 * still arrives without contact (simulator truth).
 */
class ObstacleTest extends RigTest {

    static final double[] START = CORRIDOR_WEST;
    static final Pose2D GOAL = new Pose2D(7.5, 1.0, 0.0);
    /** A crate dropped on the straight path, 3.5 m ahead of the start. */
    static final double[] CRATE = { 5.0, 1.0, 0.2 };

    @Test
    void obstacleOnThePathIsSeenAndDrivenAround(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(GOAL, 0.15, 0.3)).isSuccess(),
                    rig.onboard.output());
            SimProcess.Truth driving = awaitTruth(rig.sim, t -> t.x() >= 2.2, 30, "past x = 2.2 m");
            rig.sim.command(String.format(java.util.Locale.ROOT, "obstacle add crate %.2f %.2f %.2f", CRATE[0],
                    CRATE[1], CRATE[2]));
            System.out.println("[obstacle] crate placed while driving at " + driving);

            rig.onboard.await(l -> l.contains("obstacle on the path ahead"), "seeing the obstacle", 60);
            rig.onboard.await(l -> l.contains("replanned around the obstacle"), "replanning around it", 60);
            rig.onboard.await(l -> l.contains("goal reached"), "saying the goal is reached", 90);

            assertEquals(MissionState.DONE, rig.get(Resources.MISSION).state());
            SimProcess.Truth truth = rig.sim.truth();
            System.out.println("[obstacle] arrived: " + truth);
            assertTrue(truth.distanceTo(GOAL.x(), GOAL.y()) <= 0.15, truth + "\n" + rig.onboard.output());
            assertEquals(0, truth.contacts(), "touched something: " + truth);
            assertEquals(0, rig.sim.contactsInTruthFile(), "the truth file records a contact");
        }
    }
}
