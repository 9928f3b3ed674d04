package sabot.system;

import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.SimProcess;

/**
 * Landmark fixes: the robot is placed 0.28 m from where its configuration says it stands (an operator's rough
 * placement, with an initial uncertainty to match). Odometry and the inertial board cannot see such an offset; only
 * the ceiling landmarks the map names (onboard-bridge/maps/lab.landmarks, seen by the simulated landmark board) can.
 * Judged on the simulator's ground truth: the robot arrives where it was sent, and its estimate agrees with the truth.
 */
class LocalizationTest extends RigTest {

    /** Where the robot stands: landmark 1 (1.2, 1.2) is overhead, within the board's view radius. */
    static final double[] TRUE_START = CORRIDOR_WEST;
    /** Where its configuration says it stands: 0.2 m off in x and in y. */
    static final double[] BELIEVED_START = { TRUE_START[0] + 0.2, TRUE_START[1] + 0.2, TRUE_START[2] };
    /** East along the corridor, past landmarks 2 and 3. */
    static final Pose2D GOAL = new Pose2D(7.5, 1.0, 0.0);
    static final double TOLERANCE = 0.1;
    /** The product's gyro bias learning at rest (docs/USER-GUIDE.md), not the rig's quicker one. */
    static final String AS_SHIPPED = "localizer.imuSettleTime = 3\n";

    @Test
    void landmarkFixesCorrectAWrongStartAndTheGoalIsReachedInTruth(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, TRUE_START, BELIEVED_START, new String[0],
                "localizer.initialSigmaXY = 0.3\n" + AS_SHIPPED)) {
            assertTrue(Math.hypot(BELIEVED_START[0] - TRUE_START[0], BELIEVED_START[1] - TRUE_START[1]) > 2 * TOLERANCE,
                    "the offset must exceed what the goal tolerance forgives");
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(GOAL, TOLERANCE, 0.3)).isSuccess(),
                    rig.onboard.output());
            rig.onboard.await(l -> l.contains("goal reached"), "saying the goal is reached", 90);

            SimProcess.Truth truth = rig.sim.truth();
            Pose2D estimate = rig.get(Resources.POSITION).pose();
            double estimateError = truth.distanceTo(estimate.x(), estimate.y());
            System.out.printf("[localization] truth %s, %.3f m from the goal; estimate %s, %.3f m from the truth%n",
                    truth, truth.distanceTo(GOAL.x(), GOAL.y()), estimate, estimateError);
            assertTrue(truth.distanceTo(GOAL.x(), GOAL.y()) <= TOLERANCE, "truth " + truth + " not within "
                    + TOLERANCE + " m of " + GOAL + "\n" + rig.onboard.output());
            assertTrue(estimateError <= 0.05, "estimate " + estimate + " is " + estimateError + " m from the truth "
                    + truth);
        }
        // the product's summary at stop says how many sightings were fused
        assertTrue(java.nio.file.Files.readString(dir.resolve("onboard.log")).matches(
                "(?s).*landmark fixes [1-9]\\d* \\(\\d+ rejected by the gate\\).*"), "no landmark fix in the log");
    }
}
