package sabot.motion.sim;

import java.util.Locale;

import sabot.control.Controllers;
import sabot.control.DflGains;
import sabot.control.MotionLimits;
import sabot.control.PseudoinverseGains;
import sabot.control.TrackingController;

/** The controllers the harness compares, with the gains used for every figure. */
public enum ControllerKind {
    DFL, PSEUDOINVERSE;

    /** DFL tracking: both axes at &omega;_n = 2 rad/s, critically damped. */
    public static final DflGains DFL_TRACKING_GAINS = DflGains.of(2.0, 1.0);
    /** DFL stabilization: x eigenvalues -0.5, -1; y eigenvalues -1.25, -1.75 (1/s). */
    public static final DflGains DFL_STABILIZATION_GAINS = DflGains.stabilizing(0.5);
    /** Pseudoinverse: k_p = 2 /s, k_theta = 4 /s. */
    public static final PseudoinverseGains PSEUDOINVERSE_GAINS = new PseudoinverseGains(2.0, 4.0);

    /** @return a fresh tracking controller */
    public TrackingController tracking(MotionLimits limits) {
        return this == DFL ? Controllers.dynamicFeedbackLinearization(DFL_TRACKING_GAINS, limits)
                : Controllers.pseudoinverse(PSEUDOINVERSE_GAINS);
    }

    /** @return a fresh controller for point stabilization */
    public TrackingController stabilizing(MotionLimits limits) {
        return this == DFL ? Controllers.dflPointStabilization(DFL_STABILIZATION_GAINS, limits)
                : Controllers.pseudoinverse(PSEUDOINVERSE_GAINS);
    }

    public String cliName() {
        return name().toLowerCase(Locale.ROOT);
    }

    public static ControllerKind parse(String s) {
        for (ControllerKind v : values()) {
            if (v.cliName().equals(s)) {
                return v;
            }
        }
        throw new IllegalArgumentException("unknown controller '" + s + "' (expected dfl|pseudoinverse)");
    }
}
