package sabot.control.internal;

import sabot.control.ControlCommand;
import sabot.control.ControlStatus;
import sabot.control.DflGains;
import sabot.control.MotionLimits;
import sabot.control.TrackingController;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.path.TrajectorySample;

/**
 * Point (posture) stabilization by dynamic feedback linearization: the DFL law with a constant reference,
 * u1 = &minus;k_p1 x &minus; k_d1 x&#775;, u2 = &minus;k_p2 y &minus; k_d2 y&#775;, written in the goal's frame
 * (Oriolo, De Luca, Vendittelli, IEEE TCST 2002, &sect;IV "set-point regulation via DFL").
 * <p>
 * With gains meeting {@link DflGains#requireStabilizing()} both error dynamics are overdamped with the same
 * eigenvalue spread and every y mode is faster than every x mode, so y/x &rarr; 0 and the robot arrives moving along
 * the goal's x axis. Which way it moves along that axis is fixed by the sign of &xi;, which generically never changes:
 * the slow x mode's amplitude has the sign of x&#775;(0) + |&lambda;_fast| x(0), so choosing
 * sign(&xi;(0)) = &minus;sign(x(0)) with |&xi;(0) cos&theta;(0)| &lt; |&lambda;_fast x(0)| makes the robot arrive with the
 * goal's heading: forward when it starts behind the goal, backward when it starts beyond it.
 * <p>
 * Near &xi; = 0 (reached only at the goal, or in the degenerate start &theta;(0) = &plusmn;&pi;/2 exactly aligned)
 * &omega; is computed with the floored |&xi;|, which bounds it; the velocity smoother bounds it further.
 */
public final class DflPointStabilizer implements TrackingController {

    /** Fraction of |&lambda;_fast x(0)| used as the initial speed. */
    static final double INITIAL_SPEED_FRACTION = 0.5;

    private final DflGains gains;
    private final MotionLimits limits;
    private final double xiMin;
    private final double fastX;
    private final ControllerClock clock = new ControllerClock();

    private Pose2D goal;
    private double xi;
    private double xiDot;
    private boolean seeded;

    public DflPointStabilizer(DflGains gains, MotionLimits limits, double xiMin) {
        this.gains = gains;
        this.limits = limits;
        this.xiMin = xiMin;
        this.fastX = (gains.kd1() + Math.sqrt(gains.kd1() * gains.kd1() - 4 * gains.kp1())) / 2;
    }

    @Override
    public ControlCommand update(double time, Pose2D q, TrajectorySample r) {
        double dt = clock.advance(time);
        ControlStatus refused = ControllerInputs.refusal(dt, q, r);
        if (refused != null) {
            if (refused == ControlStatus.STOPPED_INVALID_TIME) {
                seeded = false; // no step to integrate the compensator over
            }
            return ControlCommand.stop(refused);
        }
        Pose2D g = r.pose();
        if (!g.equals(goal)) {
            goal = g;
            seeded = false;
        }
        // Robot pose in the goal frame.
        double cg = Math.cos(g.theta());
        double sg = Math.sin(g.theta());
        double dx = q.x() - g.x();
        double dy = q.y() - g.y();
        double x = cg * dx + sg * dy;
        double y = -sg * dx + cg * dy;
        double th = Pose2D.normalizeAngle(q.theta() - g.theta());
        double c = Math.cos(th);
        double s = Math.sin(th);
        if (!seeded) {
            double direction = x > 0 ? -1 : 1;
            double speed = INITIAL_SPEED_FRACTION * fastX * Math.abs(x) / Math.max(Math.abs(c), 0.5);
            xi = direction * Math.max(xiMin, Math.min(limits.maxLinearSpeed(), speed));
            seeded = true;
        } else {
            xi += dt * xiDot;
        }
        xi = Math.max(-limits.maxLinearSpeed(), Math.min(limits.maxLinearSpeed(), xi));
        double u1 = -gains.kp1() * x - gains.kd1() * xi * c;
        double u2 = -gains.kp2() * y - gains.kd2() * xi * s;
        xiDot = u1 * c + u2 * s;
        boolean nearSingular = Math.abs(xi) < xiMin;
        double denominator = nearSingular ? (xi < 0 ? -xiMin : xiMin) : xi;
        double w = (u2 * c - u1 * s) / denominator;
        Twist2D t = new Twist2D(xi, w);
        if (!t.isFinite()) {
            seeded = false;
            return ControlCommand.stop(ControlStatus.STOPPED_NUMERICAL_FAULT);
        }
        return new ControlCommand(t, nearSingular ? ControlStatus.NEAR_SINGULARITY : ControlStatus.TRACKING);
    }

    @Override
    public void commandApplied(Twist2D applied) {
        if (applied != null && Double.isFinite(applied.linear()) && seeded) {
            // Keep the sign of xi: a smoother decelerating towards zero must not flip the compensator's direction.
            double v = applied.linear();
            xi = (v == 0 || Math.signum(v) != Math.signum(xi)) ? Math.copySign(Math.min(Math.abs(xi), xiMin), xi) : v;
        }
    }

    @Override
    public void reset() {
        clock.reset();
        seeded = false;
        goal = null;
        xi = 0;
        xiDot = 0;
    }

    @Override
    public String name() {
        return "dfl-stabilization";
    }
}
