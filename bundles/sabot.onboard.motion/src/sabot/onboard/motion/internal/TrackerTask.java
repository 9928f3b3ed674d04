package sabot.onboard.motion.internal;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;
import org.osgi.service.metatype.annotations.Option;

import sabot.control.Controllers;
import sabot.control.DflGains;
import sabot.control.MotionLimits;
import sabot.control.PseudoinverseGains;
import sabot.control.TrackingController;
import sabot.onboard.motion.loop.LoopControllers;
import sabot.onboard.motion.loop.LoopDefaults;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code tracker}: the trajectory-tracking controller (dynamic feedback linearization by default, or the
 * pseudoinverse controller), the point stabilizer that brings the robot onto the goal, and the goal and progress
 * checkers' settings. Swapping the controller is a configuration change. Settings: {@link Config}.
 */
@Designate(ocd = TrackerTask.Config.class, factory = false)
@Component(name = "sabot.task.tracker", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, TrackerTask.class })
public final class TrackerTask implements OnboardTask, LoopControllers {

    /** Values of {@code controller}. */
    static final String DFL = "dfl", PSEUDOINVERSE = "pseudoinverse";

    /** The task's settings: its Metatype description, generated from these annotations. */
    @ObjectClassDefinition(id = "sabot.task.tracker", name = "Tracker task",
            description = "Trajectory tracking and point stabilization.")
    public @interface Config {
        @AttributeDefinition(name = "Controller", description = "Tracking controller.", options = {
                @Option(label = "Dynamic feedback linearization", value = DFL),
                @Option(label = "Pseudoinverse", value = PSEUDOINVERSE) })
        String controller() default DFL;

        @AttributeDefinition(name = "Natural frequency", description = "Natural frequency of the DFL error dynamics, "
                + "rad/s.", min = "0.1", max = "20")
        double omegaN() default LoopDefaults.OMEGA_N;

        @AttributeDefinition(name = "Damping", description = "Damping ratio of the DFL error dynamics.", min = "0.1",
                max = "5")
        double zeta() default LoopDefaults.ZETA;

        @AttributeDefinition(name = "Pseudoinverse kp", description = "Pseudoinverse gain on the position error, 1/s.",
                min = "0.01", max = "50")
        double kp() default LoopDefaults.KP;

        @AttributeDefinition(name = "Pseudoinverse ktheta", description = "Pseudoinverse gain on the heading error, "
                + "1/s.", min = "0.01", max = "50")
        double kTheta() default LoopDefaults.K_THETA;

        /** {@code DflGains.stabilizing}: the one-parameter family that meets its stability condition. */
        @AttributeDefinition(name = "Stabilizer rate", description = "Rate c (1/s) of the DFL point stabilizer: x "
                + "eigenvalues -c, -2c; y eigenvalues -2.5c, -3.5c.", min = "0.05", max = "10")
        double stabilizerRate() default LoopDefaults.STABILIZER_RATE;

        /** A lag while cruising is made up when the reference slows down, so little is kept back. */
        @AttributeDefinition(name = "Speed headroom", description = "Fraction of the top speeds (linear, angular) a "
                + "trajectory is planned with.", min = "0.1", max = "1")
        double speedHeadroom() default LoopDefaults.SPEED_HEADROOM;

        @AttributeDefinition(name = "Acceleration headroom", description = "Fraction of the accelerations (linear, "
                + "lateral, angular) a trajectory is planned with; the rest is the feedback's authority.", min = "0.1",
                max = "1")
        double accelerationHeadroom() default LoopDefaults.ACCELERATION_HEADROOM;

        @AttributeDefinition(name = "Progress radius", description = "Distance, m, the robot must move within the "
                + "progress time, or the mission replans, then fails.", min = "0.01", max = "10")
        double progressRadius() default LoopDefaults.PROGRESS_RADIUS;

        @AttributeDefinition(name = "Progress time", description = "Seconds allowed to move the progress radius "
                + "before replanning.", min = "0.5", max = "600")
        double progressTime() default LoopDefaults.PROGRESS_TIME;

        @AttributeDefinition(name = "Settle timeout", description = "Seconds allowed to settle on the goal after the "
                + "trajectory ends before the mission fails.", min = "0.5", max = "600")
        double settleTimeout() default LoopDefaults.SETTLE_TIMEOUT;
    }

    private Config config;

    @Activate
    void activate(Config c) {
        if (!c.controller().equals(DFL) && !c.controller().equals(PSEUDOINVERSE)) {
            throw new IllegalArgumentException("tracker.controller must be " + DFL + " or " + PSEUDOINVERSE + ", was "
                    + c.controller());
        }
        this.config = c;
    }

    @Override
    public TrackingController tracker(MotionLimits limits) {
        if (config.controller().equals(PSEUDOINVERSE)) {
            return Controllers.pseudoinverse(new PseudoinverseGains(config.kp(), config.kTheta()));
        }
        return Controllers.dynamicFeedbackLinearization(DflGains.of(config.omegaN(), config.zeta()), limits);
    }

    /** The DFL point stabilizer. */
    @Override
    public TrackingController stabilizer(MotionLimits limits) {
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
