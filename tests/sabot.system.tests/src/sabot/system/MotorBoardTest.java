package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.PidGains;

/** Proof 6: {@code cm.pid} writes the SACT board's gain registers and reads them back; bad gains change nothing. */
class MotorBoardTest extends RigTest {

    static final double[] START = CORRIDOR_MIDDLE;

    @Test
    void gainsAreWrittenToTheBoardAndReadBack(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            PidGains before = rig.get(Resources.PID);
            assertEquals(2, before.motors().size(), before.toString());

            PidGains wanted = new PidGains(List.of(new MotorGains(0, 170, 9, 1700), new MotorGains(1, 175, 7, 1750)));
            Outcome<PidGains> set = rig.operator.set(rig.robot, Resources.PID, wanted);
            assertTrue(set.isSuccess(), String.valueOf(set.errorOrNull()));
            PidGains readBack = rig.get(Resources.PID);
            assertEquals(wanted.motors(), readBack.motors());

            PidGains bad = new PidGains(List.of(new MotorGains(0, 100, 1, 100), new MotorGains(1, 40_000, 1, 1)));
            Outcome<PidGains> refused = rig.operator.set(rig.robot, Resources.PID, bad);
            assertFalse(refused.isSuccess());
            assertEquals(ControlMlCondition.INVALID_VALUE, refused.errorOrNull().cmCondition(),
                    refused.errorOrNull().toString());
            assertTrue(refused.errorOrNull().text().contains("kp"), refused.errorOrNull().toString());
            assertEquals(wanted.motors(), rig.get(Resources.PID).motors(), "a refused set changed the board");
        }
    }
}
