package sabot.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;

/** Goal checker, progress checker and velocity smoother: the behaviours Nav2 users expect. */
class NavigationHelpersTest {

    private static final MotionLimits LIMITS = new MotionLimits(0.5, 0.5, 2.0, 0.3, 1.2, 0.4);

    @Test
    void goalIsReachedOnlyWithinPositionAndHeadingTolerance() {
        GoalChecker g = new GoalChecker(0.05, 0.1, false);
        Pose2D goal = new Pose2D(1, 1, 0);
        assertTrue(g.isGoalReached(new Pose2D(1.03, 0.98, 0.05), goal));
        assertFalse(g.isGoalReached(new Pose2D(1.06, 1, 0), goal));
        assertFalse(g.isGoalReached(new Pose2D(1, 1, 0.2), goal));
        assertTrue(g.isGoalReached(new Pose2D(1, 1, 2 * Math.PI + 0.05), goal), "heading compared modulo 2 pi");
        assertFalse(g.isGoalReached(new Pose2D(Double.NaN, 1, 0), goal));
    }

    @Test
    void statefulGoalCheckerLatchesThePosition() {
        GoalChecker g = new GoalChecker(0.05, 0.1, true);
        Pose2D goal = Pose2D.ORIGIN;
        assertFalse(g.isGoalReached(new Pose2D(0.01, 0, 1.0), goal));
        assertTrue(g.isGoalReached(new Pose2D(0.07, 0, 0.0), goal), "position latched, heading now good");
        g.reset();
        assertFalse(g.isGoalReached(new Pose2D(0.07, 0, 0.0), goal));
    }

    @Test
    void robotThatDoesNotLeaveTheRadiusInTimeIsReportedStuck() {
        ProgressChecker p = new ProgressChecker(0.5, 10);
        assertTrue(p.isMakingProgress(0, Pose2D.ORIGIN));
        assertTrue(p.isMakingProgress(9.9, new Pose2D(0.4, 0, 0)));
        assertFalse(p.isMakingProgress(10.1, new Pose2D(0.45, 0, 0)));
    }

    @Test
    void movingRobotResetsTheProgressBaseline() {
        ProgressChecker p = new ProgressChecker(0.5, 10);
        p.isMakingProgress(0, Pose2D.ORIGIN);
        assertTrue(p.isMakingProgress(8, new Pose2D(0.6, 0, 0)));
        assertTrue(p.isMakingProgress(17, new Pose2D(0.7, 0, 0)));
        assertFalse(p.isMakingProgress(18.1, new Pose2D(0.7, 0, 0)));
        assertFalse(p.isMakingProgress(Double.NaN, Pose2D.ORIGIN));
    }

    @Test
    void smootherHonoursSpeedAndAccelerationLimits() {
        VelocitySmoother s = new VelocitySmoother(LIMITS, 0.5);
        Twist2D prev = s.smooth(0, new Twist2D(5, 3));
        for (int k = 1; k < 200; k++) {
            Twist2D out = s.smooth(k * 0.02, new Twist2D(5 * Math.sin(k), 3 * Math.cos(k)));
            assertTrue(Math.abs(out.linear()) <= 0.5 + 1e-12);
            assertTrue(Math.abs(out.angular()) <= 2.0 + 1e-12);
            double l = out.linear() - 0.2 * out.angular(), r = out.linear() + 0.2 * out.angular();
            double l0 = prev.linear() - 0.2 * prev.angular(), r0 = prev.linear() + 0.2 * prev.angular();
            assertTrue(Math.abs(l - l0) <= 0.5 * 0.02 + 1e-12 && Math.abs(r - r0) <= 0.5 * 0.02 + 1e-12);
            assertTrue(Math.max(Math.abs(l), Math.abs(r)) <= 1.2 + 1e-12);
            prev = out;
        }
    }

    @Test
    void speedClampKeepsTheCommandedCurvature() {
        Twist2D t = VelocitySmoother.clampSpeeds(new Twist2D(1.0, 1.0), LIMITS);
        assertEquals(0.5, t.linear(), 1e-12);
        assertEquals(0.5, t.angular(), 1e-12);
    }

    @Test
    void nanTargetBringsTheRobotToRestWithinDecelerationLimits() {
        VelocitySmoother s = new VelocitySmoother(LIMITS, 0.5);
        double t = 0;
        for (; t < 2; t += 0.02) {
            s.smooth(t, new Twist2D(0.4, 0));
        }
        Twist2D out = s.smooth(t, new Twist2D(Double.NaN, 0));
        assertTrue(out.isFinite());
        assertEquals(0.4 - 0.01, out.linear(), 1e-9, "decelerates, does not jump");
        for (int k = 0; k < 100; k++) {
            out = s.smooth(t += 0.02, new Twist2D(0, Double.POSITIVE_INFINITY));
        }
        assertEquals(0, out.linear(), 1e-12);
    }

    @Test
    void robotStopsWhenCommandsGoSilent() {
        VelocitySmoother s = new VelocitySmoother(LIMITS, 0.5);
        Twist2D target = new Twist2D(0.3, 0.2);
        double t = 0;
        for (; t < 2; t += 0.02) {
            s.smooth(t, target);
        }
        Twist2D out = s.tick(t + 0.3, target);
        assertTrue(out.linear() > 0.29, "within the timeout the last target holds");
        for (double u = t + 0.52; u < t + 3; u += 0.02) {
            out = s.tick(u, target);
        }
        assertEquals(Twist2D.ZERO, out);
    }

    @Test
    void smootherIgnoresTimeGoingBackwards() {
        VelocitySmoother s = new VelocitySmoother(LIMITS, 0.5);
        s.smooth(1.0, new Twist2D(0.1, 0));
        Twist2D a = s.smooth(1.02, new Twist2D(0.3, 0));
        assertEquals(a, s.smooth(0.5, new Twist2D(0.5, 0)));
    }
}
