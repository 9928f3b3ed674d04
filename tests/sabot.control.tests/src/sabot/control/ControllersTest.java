package sabot.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import java.util.stream.Stream;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

import sabot.model.geometry.Pose2D;
import sabot.model.path.TrajectorySample;
import sabot.model.robot.RobotDescriptions;

class ControllersTest {

    private static final MotionLimits LIMITS = MotionLimits.of(RobotDescriptions.defaults());

    static Stream<TrackingController> controllers() {
        return Stream.of(Controllers.pseudoinverse(new PseudoinverseGains(2, 4)),
                Controllers.dynamicFeedbackLinearization(DflGains.of(2, 1), LIMITS),
                Controllers.dflPointStabilization(DflGains.stabilizing(0.5), LIMITS));
    }

    private static TrajectorySample moving(double t) {
        // straight line along x at 0.3 m/s
        return new TrajectorySample(t, 0.3 * t, 0, 0, 0.3, 0, 0.3, 0, 0, 0);
    }

    @ParameterizedTest
    @MethodSource("controllers")
    void nanOrInfinitePoseStopsTheRobot(TrackingController c) {
        ControlCommand cmd = c.update(0, new Pose2D(Double.NaN, 0, 0), moving(0));
        assertEquals(ControlStatus.STOPPED_INVALID_POSE, cmd.status());
        assertEquals(0, cmd.twist().linear());
        assertEquals(ControlStatus.STOPPED_INVALID_POSE,
                c.update(0.02, new Pose2D(0, Double.POSITIVE_INFINITY, 0), moving(0.02)).status());
    }

    @ParameterizedTest
    @MethodSource("controllers")
    void nanReferenceStopsTheRobot(TrackingController c) {
        TrajectorySample bad = new TrajectorySample(0, 0, 0, 0, Double.NaN, 0, 0, 0, 0, 0);
        assertEquals(ControlStatus.STOPPED_INVALID_REFERENCE, c.update(0, Pose2D.ORIGIN, bad).status());
    }

    @ParameterizedTest
    @MethodSource("controllers")
    void timeGoingBackwardsStopsTheRobot(TrackingController c) {
        c.update(1.0, new Pose2D(-1, 0.2, 0), moving(1.0));
        ControlCommand cmd = c.update(0.98, new Pose2D(-1, 0.2, 0), moving(0.98));
        assertEquals(ControlStatus.STOPPED_INVALID_TIME, cmd.status());
        assertEquals(0, cmd.twist().angular());
        assertEquals(ControlStatus.STOPPED_INVALID_TIME, c.update(Double.NaN, Pose2D.ORIGIN, moving(0)).status());
    }

    @ParameterizedTest
    @MethodSource("controllers")
    void outputsStayFiniteOverAHostileGridOfPoses(TrackingController c) {
        double t = 0;
        for (double x : new double[] { -3, -1e-9, 0, 1e-9, 2 }) {
            for (double y : new double[] { -2, 0, 1e-12, 3 }) {
                for (double th : new double[] { -Math.PI, -Math.PI / 2, 0, Math.PI / 2, 1e6 }) {
                    t += 0.02;
                    ControlCommand cmd = c.update(t, new Pose2D(x, y, th), TrajectorySample.stationary(t, Pose2D.ORIGIN));
                    assertTrue(cmd.twist().isFinite(), cmd::toString);
                    cmd = c.update(t += 0.02, new Pose2D(x, y, th), moving(t));
                    assertTrue(cmd.twist().isFinite(), cmd::toString);
                }
            }
        }
    }

    @Test
    void pseudoinverseGivesFeedforwardWhenOnTheReference() {
        TrackingController c = Controllers.pseudoinverse(new PseudoinverseGains(2, 4));
        TrajectorySample r = new TrajectorySample(0, 1, 2, 0.5, 0.3, 0.1, 0.3 * Math.cos(0.5), 0.3 * Math.sin(0.5), 0, 0);
        ControlCommand cmd = c.update(0, r.pose(), r);
        assertEquals(0.3, cmd.twist().linear(), 1e-12);
        assertEquals(0.1, cmd.twist().angular(), 1e-12);
    }

    @Test
    void pseudoinverseCorrectsHeadingAndAlongTrackErrors() {
        TrackingController c = Controllers.pseudoinverse(new PseudoinverseGains(2, 4));
        TrajectorySample r = TrajectorySample.stationary(0, new Pose2D(1, 0, 0.1));
        ControlCommand cmd = c.update(0, Pose2D.ORIGIN, r);
        assertEquals(2 * 1, cmd.twist().linear(), 1e-12);
        assertEquals(4 * 0.1, cmd.twist().angular(), 1e-12);
    }

    @Test
    void dflReproducesFeedforwardOnTheReferenceOnceMoving() {
        TrackingController c = Controllers.dynamicFeedbackLinearization(DflGains.of(2, 1), LIMITS);
        // circle of radius 1 at 0.3 m/s, counter-clockwise, reference at angle phi
        double v = 0.3;
        double t = 0;
        ControlCommand cmd = null;
        c.commandApplied(new sabot.model.geometry.Twist2D(v, v)); // the robot is already moving at the reference speed
        for (int k = 0; k < 50; k++, t += 0.02) {
            double phi = v * t;
            double th = phi + Math.PI / 2;
            TrajectorySample r = new TrajectorySample(t, Math.cos(phi), Math.sin(phi), th, v, v, v * Math.cos(th),
                    v * Math.sin(th), -v * v * Math.cos(phi), -v * v * Math.sin(phi));
            cmd = c.update(t, r.pose(), r);
            c.commandApplied(cmd.twist());
        }
        assertEquals(ControlStatus.TRACKING, cmd.status());
        assertEquals(0.3, cmd.twist().linear(), 1e-9);
        assertEquals(0.3, cmd.twist().angular(), 1e-9);
    }

    @Test
    void dflWaitsInStaticRegulationWhileTheReferenceRests() {
        TrackingController c = Controllers.dynamicFeedbackLinearization(DflGains.of(2, 1), LIMITS);
        ControlCommand cmd = c.update(0, Pose2D.ORIGIN, TrajectorySample.stationary(0, Pose2D.ORIGIN));
        assertEquals(ControlStatus.REGULATING_AT_REST, cmd.status());
        assertEquals(0, cmd.twist().linear());
    }

    @Test
    void stabilizationGainsViolatingEqualDiscriminantsAreRejectedWithTheCondition() {
        var e = assertThrows(InfeasibleGainsException.class,
                () -> Controllers.dflPointStabilization(new DflGains(2, 3, 9, 6), LIMITS));
        assertTrue(e.getMessage().contains("kd1^2 - 4 kp1 = kd2^2 - 4 kp2"), e.getMessage());
    }

    @Test
    void stabilizationGainsWithUnderdampedDynamicsAreRejected() {
        // kd^2 - 4 kp = 0 for both: equal discriminants but not > 0
        var e = assertThrows(InfeasibleGainsException.class,
                () -> Controllers.dflPointStabilization(new DflGains(1, 2, 4, 4), LIMITS));
        assertTrue(e.getMessage().contains("overdamped"), e.getMessage());
    }

    @Test
    void stabilizationGainsWhoseYModesAreNotFasterAreRejected() {
        // discriminants both 1, kd2 - kd1 = 1 < 2
        var e = assertThrows(InfeasibleGainsException.class,
                () -> Controllers.dflPointStabilization(new DflGains(2, 3, 3.75, 4), LIMITS));
        assertTrue(e.getMessage().contains("kd2 - kd1 > 2 sqrt"), e.getMessage());
    }

    @Test
    void nonPositiveOrNanGainsAreRejected() {
        assertThrows(InfeasibleGainsException.class, () -> new PseudoinverseGains(0, 1));
        assertThrows(InfeasibleGainsException.class, () -> new PseudoinverseGains(1, Double.NaN));
        assertThrows(InfeasibleGainsException.class, () -> new DflGains(1, -1, 1, 1));
        assertThrows(InfeasibleGainsException.class, () -> DflGains.stabilizing(0));
    }

    @Test
    void stabilizerStartsForwardWhenBehindTheGoalAndBackwardWhenBeyondIt() {
        TrackingController behind = Controllers.dflPointStabilization(DflGains.stabilizing(0.5), LIMITS);
        TrajectorySample goal = TrajectorySample.stationary(0, Pose2D.ORIGIN);
        assertTrue(behind.update(0, new Pose2D(-1, 0.2, 0), goal).twist().linear() > 0);
        TrackingController beyond = Controllers.dflPointStabilization(DflGains.stabilizing(0.5), LIMITS);
        assertTrue(beyond.update(0, new Pose2D(1, 0.2, 0), goal).twist().linear() < 0);
    }

    @Test
    void stabilizerYawRateStaysBoundedThroughTheSingularity() {
        TrackingController c = Controllers.dflPointStabilization(DflGains.stabilizing(0.5), LIMITS);
        TrajectorySample goal = TrajectorySample.stationary(0, Pose2D.ORIGIN);
        // Start facing away, exactly on the goal's x axis: the degenerate case where xi must pass through zero.
        double bound = 0;
        double t = 0;
        Pose2D p = new Pose2D(-1, 0, Math.PI);
        for (int k = 0; k < 1000; k++, t += 0.02) {
            ControlCommand cmd = c.update(t, p, goal);
            var applied = VelocitySmoother.clampSpeeds(cmd.twist(), LIMITS);
            c.commandApplied(applied);
            p = UnicycleModel.rk4Step(p, applied, 0.02);
            bound = Math.max(bound, Math.abs(cmd.twist().angular()));
            assertTrue(cmd.twist().isFinite());
        }
        assertTrue(Double.isFinite(bound), "yaw rate must stay finite, max " + bound);
        assertTrue(Math.hypot(p.x(), p.y()) < 0.05, "ends near the goal: " + p);
    }

    @Test
    void controlCommandRefusesNonFiniteTwist() {
        assertThrows(IllegalArgumentException.class,
                () -> new ControlCommand(new sabot.model.geometry.Twist2D(Double.NaN, 0), ControlStatus.TRACKING));
        assertTrue(List.of(ControlStatus.values()).stream().filter(ControlStatus::isStop).count() >= 4);
    }
}
