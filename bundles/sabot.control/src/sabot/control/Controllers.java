package sabot.control;

import sabot.control.internal.DflPointStabilizer;
import sabot.control.internal.DflTrackingController;
import sabot.control.internal.PseudoinverseController;

/** Builds the {@link TrackingController} implementations. */
public final class Controllers {

    /**
     * Floor on |&xi;| (m/s) used in &omega; = (u2 cos &theta; &minus; u1 sin &theta;)/&xi;. 2 cm/s: below it, a 1 m/s&sup2;
     * transverse demand would already ask for 50 rad/s, far beyond what the wheels can do.
     */
    public static final double DEFAULT_XI_MIN = 0.02;

    private Controllers() {
    }

    /**
     * The pseudoinverse law: u = G&#8314;(&theta;)(p&#775;_d + K e), with G the unicycle's input matrix, i.e.
     * v = cos&theta;(x&#775;_d + k_p e_x) + sin&theta;(y&#775;_d + k_p e_y), &omega; = &omega;_d + k_&theta; e_&theta;.
     */
    public static TrackingController pseudoinverse(PseudoinverseGains gains) {
        return new PseudoinverseController(gains);
    }

    /**
     * Trajectory tracking by dynamic feedback linearization (Oriolo, De Luca, Vendittelli 2002), with the compensator
     * state clamped to &plusmn;v_max and re-seeded from the applied command (anti-windup), and a static regulation law
     * while the reference is at rest (where &xi; would have to cross zero).
     */
    public static TrackingController dynamicFeedbackLinearization(DflGains gains, MotionLimits limits) {
        return new DflTrackingController(gains, limits, DEFAULT_XI_MIN);
    }

    /**
     * Point stabilization to the reference pose by dynamic feedback linearization.
     *
     * @throws InfeasibleGainsException when the gains violate {@link DflGains#requireStabilizing()}
     */
    public static TrackingController dflPointStabilization(DflGains gains, MotionLimits limits) {
        return new DflPointStabilizer(gains.requireStabilizing(), limits, DEFAULT_XI_MIN);
    }
}
