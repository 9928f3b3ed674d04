package sabot.onboard.internal.motion;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;

import sabot.control.Controllers;
import sabot.control.DflGains;
import sabot.control.MotionLimits;
import sabot.control.PseudoinverseGains;
import sabot.control.TrackingController;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code tracker}: the trajectory-tracking controller (dynamic feedback linearization by default, or the
 * pseudoinverse controller), the point stabilizer that brings the robot onto the goal, and the goal and progress
 * checkers' settings. Swapping the controller is a configuration change. Settings: OSGI-INF/metatype/tracker.xml.
 */
@Component(name = "sabot.task.tracker", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, TrackerTask.class })
public final class TrackerTask implements OnboardTask {

    /** Settings (names match the Metatype description). */
    public @interface Config {
        /** @return dfl or pseudoinverse */
        String controller() default "dfl";

        /** @return natural frequency of the DFL error dynamics, rad/s */
        double omegaN() default 2.0;

        /** @return damping ratio of the DFL error dynamics */
        double zeta() default 0.9;

        /** @return pseudoinverse controller gain on the position error, 1/s */
        double kp() default 1.5;

        /** @return pseudoinverse controller gain on the heading error, 1/s */
        double kTheta() default 2.0;

        /**
         * @return rate c (1/s) of the DFL point stabilizer: x eigenvalues −c, −2c, y eigenvalues −2.5c, −3.5c
         *         ({@code DflGains.stabilizing}, the one-parameter family that meets its stability condition)
         */
        double stabilizerRate() default 0.5;

        /**
         * @return fraction of the top speeds (linear, angular) a trajectory is planned with; a lag while cruising is
         *         made up when the reference slows down, so little is kept back
         */
        double speedHeadroom() default 0.95;

        /**
         * @return fraction of the accelerations (linear, lateral, angular) a trajectory is planned with; the rest is
         *         the feedback's authority while the reference accelerates
         */
        double accelerationHeadroom() default 0.8;

        /** @return the robot must move this far (m) within progressTime, or the mission replans, then fails */
        double progressRadius() default 0.1;

        /** @return seconds allowed to move progressRadius */
        double progressTime() default 8;

        /** @return seconds after the trajectory's end allowed to settle on the goal before the mission fails */
        double settleTimeout() default 15;
    }

    private Config config;

    @Activate
    void activate(Config c) {
        if (!c.controller().equals("dfl") && !c.controller().equals("pseudoinverse")) {
            throw new IllegalArgumentException("tracker.controller must be dfl or pseudoinverse, was " + c.controller());
        }
        this.config = c;
    }

    /** @return a new tracking controller for these limits */
    TrackingController newTracker(MotionLimits limits) {
        if (config.controller().equals("pseudoinverse")) {
            return Controllers.pseudoinverse(new PseudoinverseGains(config.kp(), config.kTheta()));
        }
        return Controllers.dynamicFeedbackLinearization(DflGains.of(config.omegaN(), config.zeta()), limits);
    }

    /** @return a new point stabilizer (DFL) for these limits */
    TrackingController newStabilizer(MotionLimits limits) {
        return Controllers.dflPointStabilization(DflGains.stabilizing(config.stabilizerRate()), limits);
    }

    /** @return the configured settings */
    Config config() {
        return config;
    }

    @Override
    public String name() {
        return "tracker";
    }

    @Override
    public String status() {
        return config.controller() + " tracking (omegaN " + config.omegaN() + ", zeta " + config.zeta()
                + "), DFL point stabilization (rate " + config.stabilizerRate() + ")";
    }
}
