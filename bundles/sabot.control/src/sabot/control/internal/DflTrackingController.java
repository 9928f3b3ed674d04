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
 * Trajectory tracking by dynamic feedback linearization of the unicycle (G. Oriolo, A. De Luca, M. Vendittelli,
 * "WMR control via dynamic feedback linearization: design, implementation, and experimental validation",
 * IEEE Trans. Control Systems Technology 10(6):835-852, 2002, &sect;III-D, eqs. 18-20; also Siciliano et al. 2009,
 * &sect;11.6.3).
 * <p>
 * With the flat output (x, y) and the compensator state &xi; (the forward speed):
 * <pre>
 *   &xi;' = u1 cos&theta; + u2 sin&theta;,   v = &xi;,   &omega; = (u2 cos&theta; &minus; u1 sin&theta;) / &xi;
 *   u1 = x&#776;_d + k_p1 (x_d &minus; x) + k_d1 (x&#775;_d &minus; &xi; cos&theta;)
 *   u2 = y&#776;_d + k_p2 (y_d &minus; y) + k_d2 (y&#775;_d &minus; &xi; sin&theta;)
 * </pre>
 * the Cartesian errors obey e&#776; + k_d e&#775; + k_p e = 0 exactly. Protections, which the paper leaves to the
 * implementer:
 * <ul>
 * <li>&xi; = 0 is the law's singularity: there the transverse demand u2 cos&theta; &minus; u1 sin&theta; cannot be
 * met by turning, because turning rate = demand/&xi;. While |&xi;| &lt; max(&xi;_min, |demand|/&omega;_max), i.e. while
 * the exact &omega; would be beyond the robot's yaw-rate limit anyway, the controller keeps integrating &xi;
 * but steers the robot's axis towards the demanded acceleration u (forward along u when the reference drives
 * forward, backward when it reverses), &omega; = k_align&middot;wrap(&ang;(&plusmn;u) &minus; &theta;): then &xi;' = u&middot;(cos&theta;, sin&theta;)
 * becomes positive (negative) and &xi; leaves the band on the reference's side. This happens at start-up and when a
 * large initial error makes the linear error dynamics ask the robot to reverse;</li>
 * <li>while the reference is slow ({@link #REST_SPEED}) or at rest, &xi; would have to pass through zero; the
 * controller then regulates with the static pseudoinverse law and re-seeds &xi; from the robot's applied speed when
 * the reference is fast enough again;</li>
 * <li>&xi; is clamped to &plusmn;v_max and replaced by the applied speed reported through {@link #commandApplied}
 * (anti-windup), so saturation in the velocity smoother does not make the compensator run away.</li>
 * </ul>
 * The compensator is integrated with forward Euler at the caller's update times.
 */
public final class DflTrackingController implements TrackingController {

    /**
     * Reference speed (m/s) below which the static law regulates instead of the DFL law. Near &xi; = 0 the exact law
     * turns any lateral error into a yaw rate error/&xi;, which at the start of a leg spends the wheels' acceleration
     * budget on turning instead of following the ramp (measured: 3 cm lag at the legs of the square with 0.01 m/s,
     * 5 mm with 0.1 m/s). A 0.4 m/s&sup2; ramp crosses 0.1 m/s in a quarter of a second.
     */
    static final double REST_SPEED = 0.1;
    /** Gains of the static law used while the reference rests, 1/s. */
    static final double REST_POSITION_GAIN = 1.0;
    static final double REST_HEADING_GAIN = 3.0;
    /** Gain steering the robot's axis towards the demanded acceleration while |&xi;| &lt; &xi;_min, 1/s. */
    static final double ALIGN_GAIN = 2.0;

    private final DflGains gains;
    private final MotionLimits limits;
    private final double xiMin;
    private final ControllerClock clock = new ControllerClock();

    private boolean seeded;
    private double xi;
    private double xiDot;
    private double appliedSpeed;

    public DflTrackingController(DflGains gains, MotionLimits limits, double xiMin) {
        this.gains = gains;
        this.limits = limits;
        this.xiMin = xiMin;
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
        if (Math.abs(r.linearVelocity()) < REST_SPEED) {
            seeded = false;
            Twist2D t = PseudoinverseController.law(REST_POSITION_GAIN, REST_HEADING_GAIN, q, r);
            return finite(t, ControlStatus.REGULATING_AT_REST);
        }
        if (!seeded) {
            // Leaving rest: the compensator state is the robot's forward speed, so start from what is applied.
            xi = appliedSpeed;
            seeded = true;
        } else {
            xi += dt * xiDot;
        }
        xi = Math.max(-limits.maxLinearSpeed(), Math.min(limits.maxLinearSpeed(), xi));

        double c = Math.cos(q.theta());
        double s = Math.sin(q.theta());
        double u1 = r.xDdot() + gains.kp1() * (r.x() - q.x()) + gains.kd1() * (r.xDot() - xi * c);
        double u2 = r.yDdot() + gains.kp2() * (r.y() - q.y()) + gains.kd2() * (r.yDot() - xi * s);
        xiDot = u1 * c + u2 * s;
        double transverse = u2 * c - u1 * s;
        // The exact law needs |omega| = |transverse|/|xi|; beyond omega_max it saturates and the linearization is lost.
        double band = Math.max(xiMin, Math.abs(transverse) / limits.maxAngularSpeed());
        if (Math.abs(xi) >= band) {
            return finite(new Twist2D(xi, transverse / xi), ControlStatus.TRACKING);
        }
        double w;
        if (Math.hypot(u1, u2) < 1e-9) {
            w = r.angularVelocity();
        } else {
            double side = Math.signum(r.linearVelocity());
            w = ALIGN_GAIN * Pose2D.normalizeAngle(Math.atan2(side * u2, side * u1) - q.theta());
        }
        return finite(new Twist2D(xi, w), ControlStatus.NEAR_SINGULARITY);
    }

    private ControlCommand finite(Twist2D t, ControlStatus status) {
        if (!t.isFinite()) {
            seeded = false;
            return ControlCommand.stop(ControlStatus.STOPPED_NUMERICAL_FAULT);
        }
        return new ControlCommand(t, status);
    }

    @Override
    public void commandApplied(Twist2D applied) {
        if (applied != null && Double.isFinite(applied.linear())) {
            appliedSpeed = applied.linear();
            if (seeded) {
                xi = applied.linear();
            }
        }
    }

    @Override
    public void reset() {
        clock.reset();
        seeded = false;
        xi = 0;
        xiDot = 0;
        appliedSpeed = 0;
    }

    @Override
    public String name() {
        return "dfl";
    }
}
