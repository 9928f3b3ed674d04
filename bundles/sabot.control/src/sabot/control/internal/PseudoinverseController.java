package sabot.control.internal;

import sabot.control.ControlCommand;
import sabot.control.ControlStatus;
import sabot.control.PseudoinverseGains;
import sabot.control.TrackingController;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.path.TrajectorySample;

/**
 * Kinematic inversion of the unicycle q' = G(&theta;) u with the Moore-Penrose pseudoinverse
 * G&#8314; = (G&#7488;G)&#8315;&sup1;G&#7488; = [[cos&theta;, sin&theta;, 0], [0, 0, 1]] and a proportional
 * correction: u = G&#8314;(q&#775;_d + K e), K = diag(k_p, k_p, k_&theta;) (the closed-loop inverse-kinematics
 * scheme of Siciliano et al., <i>Robotics: Modelling, Planning and Control</i>, 2009, &sect;3.7, applied to the
 * unicycle of &sect;11.2). The lateral error lies in the kernel of G&#8314; and is only corrected through the
 * heading: the price of a law without internal state.
 */
public final class PseudoinverseController implements TrackingController {

    private final PseudoinverseGains gains;
    private final ControllerClock clock = new ControllerClock();

    public PseudoinverseController(PseudoinverseGains gains) {
        this.gains = gains;
    }

    @Override
    public ControlCommand update(double time, Pose2D estimate, TrajectorySample reference) {
        ControlStatus refused = ControllerInputs.refusal(clock.advance(time), estimate, reference);
        if (refused != null) {
            return ControlCommand.stop(refused);
        }
        Twist2D t = law(gains.kp(), gains.kTheta(), estimate, reference);
        if (!t.isFinite()) {
            return ControlCommand.stop(ControlStatus.STOPPED_NUMERICAL_FAULT);
        }
        boolean atRest = Math.abs(reference.linearVelocity()) < 1e-9;
        return new ControlCommand(t, atRest ? ControlStatus.REGULATING_AT_REST : ControlStatus.TRACKING);
    }

    /** The law itself, shared with the DFL controller's rest regulation. */
    static Twist2D law(double kp, double kTheta, Pose2D q, TrajectorySample r) {
        double c = Math.cos(q.theta());
        double s = Math.sin(q.theta());
        double v = c * (r.xDot() + kp * (r.x() - q.x())) + s * (r.yDot() + kp * (r.y() - q.y()));
        double w = r.angularVelocity() + kTheta * Pose2D.normalizeAngle(r.theta() - q.theta());
        return new Twist2D(v, w);
    }

    @Override
    public void reset() {
        clock.reset();
    }

    @Override
    public String name() {
        return "pseudoinverse";
    }
}
