package sabot.onboard.motion.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.util.List;
import java.util.Map;

import org.junit.jupiter.api.Test;

import sabot.onboard.task.TaskSettingsCheck.Problem;

/** The motion task's battery thresholds, checked before anything starts. */
class BatterySettingsCheckTest {

    private final MotionSettingsChecks.Motion check = new MotionSettingsChecks.Motion();

    @Test
    void batteryLowMustLieBelowBatteryCharged() {
        assertEquals(List.of(), check.check(Map.of()), "the defaults");
        assertEquals(List.of(), check.check(Map.of("batteryLow", "0.1", "batteryCharged", 0.5)));
        assertEquals(List.of(new Problem("batteryLow", "motion.batteryLow (0.9) must be below motion.batteryCharged "
                + "(0.9): a robot charged to 0.9 would be low at once")), check.check(Map.of("batteryLow", 0.9)));
        assertEquals(List.of(), check.check(Map.of("batteryLow", "low")), "a malformed number is Metatype's");
    }
}
