package sabot.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.RobotDescriptions;

class KinematicsTest {

    @Test
    void rk4FollowsACircleToMachinePrecision() {
        // v = 0.3 m/s, omega = 0.3 rad/s: circle of radius 1 m centred at (0, 1); half a turn ends at (0, 2).
        Pose2D p = UnicycleModel.integrate(Pose2D.ORIGIN, new Twist2D(0.3, 0.3), Math.PI / 0.3, 500);
        assertEquals(0, p.x(), 1e-9);
        assertEquals(2, p.y(), 1e-9);
        assertEquals(Math.PI, p.theta(), 1e-12);
    }

    @Test
    void rk4DrivesStraightWithoutRotation() {
        Pose2D p = UnicycleModel.rk4Step(new Pose2D(1, 1, Math.PI / 2), new Twist2D(0.5, 0), 2);
        assertEquals(1, p.x(), 1e-12);
        assertEquals(2, p.y(), 1e-12);
    }

    @Test
    void rk4RejectsNegativeOrNanStep() {
        assertThrows(IllegalArgumentException.class, () -> UnicycleModel.rk4Step(Pose2D.ORIGIN, Twist2D.ZERO, -0.01));
        assertThrows(IllegalArgumentException.class, () -> UnicycleModel.rk4Step(Pose2D.ORIGIN, Twist2D.ZERO, Double.NaN));
    }

    @Test
    void wheelSpeedsMapToUnicycleInputsAndBack() {
        DifferentialDrive d = new DifferentialDrive(0.075, 0.40);
        // u1 = r(wR + wL)/2, u2 = r(wR - wL)/d
        Twist2D t = d.toTwist(new WheelSpeeds(2, 4));
        assertEquals(0.075 * 3, t.linear(), 1e-12);
        assertEquals(0.075 * 2 / 0.40, t.angular(), 1e-12);
        WheelSpeeds w = d.toWheelSpeeds(t);
        assertEquals(2, w.left(), 1e-12);
        assertEquals(4, w.right(), 1e-12);
    }

    @Test
    void wheelSpeedLimitComesFromMotorNoLoadSpeedThroughTheGearhead() {
        var robot = RobotDescriptions.defaults();
        double expected = robot.motorNoLoadSpeedRpm() * 2 * Math.PI / 60 / robot.gearRatio();
        assertEquals(expected, robot.maxWheelAngularSpeed(), 1e-12);
        MotionLimits limits = MotionLimits.of(robot);
        assertEquals(expected * robot.wheelRadius(), limits.maxWheelRimSpeed(), 1e-12);
        assertEquals(2 * robot.maxLinearAcceleration() / robot.trackWidth(), limits.maxAngularAcceleration(), 1e-12);
    }

    @Test
    void curvatureLimitsTheSpeedThroughLateralAccelerationYawRateAndOuterWheel() {
        MotionLimits l = new MotionLimits(0.5, 0.5, 2.0, 0.3, 1.0, 0.4);
        assertEquals(0.5, l.maxSpeedForCurvature(0), 1e-12);
        assertEquals(Math.sqrt(0.3 / 2.0), l.maxSpeedForCurvature(2.0), 1e-12);
        assertEquals(2.0 / 50, l.maxSpeedForCurvature(-50), 1e-12);
    }
}
