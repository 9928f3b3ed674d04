package sabot.model.robot;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

/** The robot description: the seed constants, derived figures and precise errors for bad input. */
class RobotDescriptionTest {

    private static final String VALID = """
            robot.name = test
            wheel.radius.m = 0.075
            track.width.m = 0.40
            gear.ratio = 43
            encoder.lines = 512
            encoder.quadrature = 4
            motor.noLoadSpeed.rpm = 7000
            limit.linearSpeed.mps = 0.5
            limit.linearAcceleration.mps2 = 0.5
            limit.angularSpeed.radps = 2.0
            limit.lateralAcceleration.mps2 = 0.3
            control.period.s = 0.02
            """;

    @Test
    void referenceRobotLoadsWithTheSeedConstants() {
        RobotDescription r = RobotDescriptions.defaults();
        assertEquals(0.075, r.wheelRadius());
        assertEquals(43, r.gearRatio());
        assertEquals(512 * 4 * 43, r.countsPerWheelRevolution());
        assertEquals(0.5, r.maxLinearSpeed());
        assertEquals(0.5, r.maxLinearAcceleration());
    }

    @Test
    void parsedFileGivesEncoderResolution() {
        RobotDescription r = RobotDescriptions.parse(VALID);
        assertEquals(2 * Math.PI * 0.075 / (512 * 4 * 43), r.metresPerCount(), 1e-15);
    }

    @Test
    void missingAndUnknownKeysAreAllReported() {
        var e = assertThrows(InvalidRobotDescriptionException.class,
                () -> RobotDescriptions.parse(VALID.replace("gear.ratio = 43\n", "gear.ration = 43\n")));
        assertTrue(e.problems().stream().anyMatch(p -> p.contains("missing key 'gear.ratio'")), e.getMessage());
        assertTrue(e.problems().stream().anyMatch(p -> p.contains("unknown key 'gear.ration'")), e.getMessage());
    }

    @Test
    void malformedOrNonPositiveValuesAreRejected() {
        assertThrows(InvalidRobotDescriptionException.class,
                () -> RobotDescriptions.parse(VALID.replace("0.075", "seven")));
        var e = assertThrows(InvalidRobotDescriptionException.class,
                () -> RobotDescriptions.parse(VALID.replace("track.width.m = 0.40", "track.width.m = -1")));
        assertTrue(e.getMessage().contains("track width"), e.getMessage());
    }

    @Test
    void speedLimitAboveWhatTheMotorCanDeliverIsRejected() {
        var e = assertThrows(InvalidRobotDescriptionException.class,
                () -> RobotDescriptions.parse(VALID.replace("limit.linearSpeed.mps = 0.5", "limit.linearSpeed.mps = 5")));
        assertTrue(e.getMessage().contains("no-load"), e.getMessage());
    }
}
