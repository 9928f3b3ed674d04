package sabot.localization;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Pose2D;
import sabot.model.robot.RobotDescription;
import sabot.model.robot.RobotDescriptions;

class EncoderOdometryTest {

    private static final RobotDescription ROBOT = RobotDescriptions.defaults();
    private static final double COUNTS_PER_METRE = ROBOT.countsPerWheelRevolution() / (2 * Math.PI * ROBOT.wheelRadius());

    @Test
    void equalCountsDriveStraightAlongTheHeading() {
        EncoderOdometry o = new EncoderOdometry(ROBOT, OdometryCalibration.nominal(ROBOT), new Pose2D(1, 1, Math.PI / 2));
        o.update(0, 0);
        int n = (int) Math.round(COUNTS_PER_METRE);
        Pose2D p = o.update(n, n);
        assertEquals(1, p.x(), 1e-9);
        assertEquals(2, p.y(), 1e-5);
    }

    @Test
    void runge2UpdateIsExactOnArcs() {
        // Right wheel on a 1.2 m radius arc, left on 0.8 m: centre on a 1 m radius arc, quarter turn.
        EncoderOdometry o = new EncoderOdometry(ROBOT, OdometryCalibration.nominal(ROBOT), Pose2D.ORIGIN);
        o.update(0, 0);
        int steps = 400;
        double quarter = Math.PI / 2;
        Pose2D p = null;
        for (int k = 1; k <= steps; k++) {
            double a = quarter * k / steps;
            p = o.update((int) Math.round(0.8 * a * COUNTS_PER_METRE), (int) Math.round(1.2 * a * COUNTS_PER_METRE));
        }
        assertEquals(1, p.x(), 1e-4);
        assertEquals(1, p.y(), 1e-4);
        assertEquals(quarter, p.theta(), 1e-4);
    }

    @Test
    void counterWrapAroundIsHarmless() {
        EncoderOdometry o = new EncoderOdometry(ROBOT, OdometryCalibration.nominal(ROBOT), Pose2D.ORIGIN);
        o.update(Integer.MAX_VALUE - 10, Integer.MAX_VALUE - 10);
        Pose2D p = o.update(Integer.MIN_VALUE + 9, Integer.MIN_VALUE + 9); // +20 counts each
        assertEquals(20 / COUNTS_PER_METRE, p.x(), 1e-12);
    }

    @Test
    void calibrationChangesTheIncrementsItIsAppliedTo() {
        EncoderOdometry o = new EncoderOdometry(ROBOT, OdometryCalibration.nominal(ROBOT), Pose2D.ORIGIN);
        o.update(0, 0);
        o.setCalibration(new OdometryCalibration(ROBOT.wheelRadius() * 0.99, ROBOT.wheelRadius() * 1.01, ROBOT.trackWidth()));
        int n = (int) Math.round(COUNTS_PER_METRE);
        Pose2D p = o.update(n, n);
        assertEquals(0.02 / ROBOT.trackWidth(), p.theta(), 1e-5);
    }

    @Test
    void nonFiniteStartIsRejected() {
        assertThrows(IllegalArgumentException.class,
                () -> new EncoderOdometry(ROBOT, OdometryCalibration.nominal(ROBOT), new Pose2D(Double.NaN, 0, 0)));
    }
}
