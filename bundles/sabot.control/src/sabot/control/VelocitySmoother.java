package sabot.control;

import sabot.model.geometry.Twist2D;

/**
 * Limits a stream of twist commands to the robot's envelope, as Nav2's {@code velocity_smoother} does for its users:
 * speed limits (|v| &le; v_max, |&omega;| &le; &omega;_max, each wheel's rim speed &le; the motor's no-load limit) and
 * acceleration limits (each wheel's rim acceleration &le; a_max, hence |dv/dt| &le; a_max and
 * |d&omega;/dt| &le; 2a_max/d), plus a command timeout.
 * <p>
 * Speed limits scale v and &omega; together so the commanded curvature is kept; the acceleration step moves from the
 * previous output towards the target along a straight line in wheel-speed space, so the path's curvature is kept
 * too. Every output is therefore inside the (convex) envelope whenever the previous one was.
 * <p>
 * Safe behaviour: a target with a NaN or infinite component, or no new target for longer than the timeout, is
 * treated as a stop request (decelerating within the limits). A time that is not finite or does not increase leaves
 * the output unchanged.
 */
public final class VelocitySmoother {

    private final MotionLimits limits;
    private final double timeout;
    private double lastTime = Double.NaN;
    private double lastTargetTime = Double.NaN;
    private Twist2D output = Twist2D.ZERO;

    /**
     * @param limits  the envelope
     * @param timeout seconds without a new target after which the smoother brings the robot to rest (deadman)
     */
    public VelocitySmoother(MotionLimits limits, double timeout) {
        if (!(timeout > 0)) {
            throw new IllegalArgumentException("timeout must be > 0 s, was " + timeout);
        }
        this.limits = limits;
        this.timeout = timeout;
    }

    /**
     * Accepts a new target and returns the command to apply now.
     *
     * @param time   seconds, monotonic
     * @param target desired twist; non-finite means stop
     */
    public Twist2D smooth(double time, Twist2D target) {
        if (target != null) {
            lastTargetTime = time;
        }
        return step(time, target != null && target.isFinite() ? target : Twist2D.ZERO);
    }

    /** Advances without a new target: keeps the last target until the timeout, then stops. */
    public Twist2D tick(double time, Twist2D lastTarget) {
        boolean expired = Double.isNaN(lastTargetTime) || time - lastTargetTime > timeout;
        return step(time, expired || lastTarget == null || !lastTarget.isFinite() ? Twist2D.ZERO : lastTarget);
    }

    private Twist2D step(double time, Twist2D target) {
        if (!Double.isFinite(time)) {
            return output;
        }
        double dt;
        if (Double.isNaN(lastTime)) {
            dt = 0;
        } else if (time <= lastTime) {
            return output;
        } else {
            dt = time - lastTime;
        }
        lastTime = time;
        Twist2D bounded = clampSpeeds(target, limits);
        double half = limits.trackWidth() / 2;
        double l0 = output.linear() - half * output.angular();
        double r0 = output.linear() + half * output.angular();
        double l1 = bounded.linear() - half * bounded.angular();
        double r1 = bounded.linear() + half * bounded.angular();
        double maxStep = limits.maxLinearAcceleration() * dt;
        double need = Math.max(Math.abs(l1 - l0), Math.abs(r1 - r0));
        double f = need <= maxStep ? 1 : maxStep / need;
        double l = l0 + f * (l1 - l0);
        double r = r0 + f * (r1 - r0);
        output = new Twist2D((l + r) / 2, (r - l) / limits.trackWidth());
        return output;
    }

    /** @return the last output, (0, 0) before the first call */
    public Twist2D lastOutput() {
        return output;
    }

    /** Forgets the history: the next output starts from rest. */
    public void reset() {
        lastTime = Double.NaN;
        lastTargetTime = Double.NaN;
        output = Twist2D.ZERO;
    }

    /**
     * Scales a twist down (keeping v/&omega;) until |v| &le; v_max, |&omega;| &le; &omega;_max and both wheel rim speeds
     * &le; the wheel limit. Non-finite input gives zero.
     */
    public static Twist2D clampSpeeds(Twist2D t, MotionLimits limits) {
        if (t == null || !t.isFinite()) {
            return Twist2D.ZERO;
        }
        double v = t.linear();
        double w = t.angular();
        double scale = 1;
        if (Math.abs(v) > limits.maxLinearSpeed()) {
            scale = Math.min(scale, limits.maxLinearSpeed() / Math.abs(v));
        }
        if (Math.abs(w) > limits.maxAngularSpeed()) {
            scale = Math.min(scale, limits.maxAngularSpeed() / Math.abs(w));
        }
        double rim = Math.abs(v) + Math.abs(w) * limits.trackWidth() / 2;
        if (rim > limits.maxWheelRimSpeed()) {
            scale = Math.min(scale, limits.maxWheelRimSpeed() / rim);
        }
        return scale == 1 ? t : new Twist2D(v * scale, w * scale);
    }
}
