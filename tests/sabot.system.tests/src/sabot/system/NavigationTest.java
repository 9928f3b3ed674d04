package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.SimProcess;

/**
 * Proof 1 of the onboard issue: a goal sent over XMPP moves the simulated robot. Real processes: a private Prosody,
 * sabot-sim on the lab map, the onboard product on the simulator's pty; the operator is a Smack client. Success is
 * judged on the simulator's ground truth, not on what the robot believes.
 */
class NavigationTest extends RigTest {

    static final double[] START = WEST_OF_PARTITION;
    /** Behind the partition, 5.2 m away in a straight line; the path goes round the partition's end. */
    static final Pose2D GOAL = new Pose2D(6.5, 3.0, 0.0);
    /** Goal position tolerance, m (Nav2 default: 0.25): judged on the truth, so it bounds estimate and control error. */
    static final double TOLERANCE = 0.15;

    @Test
    void goalBehindThePartitionIsReachedWithoutContact(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            assertTrue(Math.hypot(GOAL.x() - START[0], GOAL.y() - START[1]) >= 5.0);
            MissionStatus idle = rig.get(Resources.MISSION);
            assertEquals(MissionState.IDLE, idle.state(), idle + "\n" + rig.onboard.output());

            Goal goal = new Goal(GOAL, TOLERANCE, 0.2);
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, goal).isSuccess(), rig.onboard.output());
            MissionStatus running = rig.get(Resources.MISSION);
            assertEquals(MissionState.RUNNING, running.state(), running.toString());

            rig.onboard.await(l -> l.contains("goal reached"), "saying the goal is reached", 120);
            MissionStatus done = rig.get(Resources.MISSION);
            assertEquals(MissionState.DONE, done.state(), done.toString());

            SimProcess.Truth truth = rig.sim.truth();
            System.out.printf("[navigation] goal %s reached; truth %s, %.3f m from the goal; robot's estimate %s%n",
                    GOAL, truth, truth.distanceTo(GOAL.x(), GOAL.y()), rig.get(Resources.POSITION).pose());
            assertTrue(truth.distanceTo(GOAL.x(), GOAL.y()) <= TOLERANCE, "truth " + truth + " not within "
                    + TOLERANCE + " m of " + GOAL + "\n" + rig.onboard.output());
            assertEquals(0, truth.contacts(), "contacts: " + truth);
            assertEquals(0, rig.sim.contactsInTruthFile(), "the truth file records a contact");
        }
    }
}
