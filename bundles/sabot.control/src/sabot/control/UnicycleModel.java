package sabot.control;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;

/**
 * The unicycle kinematic model x' = u1 cos &theta;, y' = u1 sin &theta;, &theta;' = u2 (Siciliano et al. 2009,
 * eq. 11.13), integrated with the classical fourth-order Runge-Kutta scheme for simulation.
 */
public final class UnicycleModel {

    private UnicycleModel() {
    }

    /**
     * Integrates the model over {@code dt} with the inputs held constant (zero-order hold, as a motor board applies
     * a set-point), using one RK4 step.
     *
     * @param pose  start pose
     * @param twist (u1 in m/s, u2 in rad/s), held over the step
     * @param dt    step in seconds, &ge; 0
     * @return the pose after {@code dt}; the heading is not wrapped
     */
    public static Pose2D rk4Step(Pose2D pose, Twist2D twist, double dt) {
        if (!(dt >= 0) || !Double.isFinite(dt)) {
            throw new IllegalArgumentException("time step must be finite and >= 0, was " + dt);
        }
        double v = twist.linear();
        double w = twist.angular();
        double th = pose.theta();
        // With constant inputs only theta varies inside the step, so the stages reduce to these headings.
        double th2 = th + 0.5 * dt * w;
        double th4 = th + dt * w;
        double cx = (Math.cos(th) + 4 * Math.cos(th2) + Math.cos(th4)) / 6;
        double cy = (Math.sin(th) + 4 * Math.sin(th2) + Math.sin(th4)) / 6;
        return new Pose2D(pose.x() + dt * v * cx, pose.y() + dt * v * cy, th4);
    }

    /**
     * Integrates over {@code dt} in {@code steps} RK4 sub-steps.
     */
    public static Pose2D integrate(Pose2D pose, Twist2D twist, double dt, int steps) {
        if (steps < 1) {
            throw new IllegalArgumentException("steps must be >= 1, was " + steps);
        }
        Pose2D p = pose;
        double h = dt / steps;
        for (int i = 0; i < steps; i++) {
            p = rk4Step(p, twist, h);
        }
        return p;
    }
}
