package sabot.onboard.internal.motion;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;

import sabot.onboard.task.OnboardTask;

/**
 * Task {@code teleop}: joystick twists (ControlML {@code cm.velocity} sets) are accepted only when this task runs;
 * the deadman timeout brings the robot to rest when they stop. Settings: OSGI-INF/metatype/teleop.xml.
 */
@Component(name = "sabot.task.teleop", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, TeleopTask.class })
public final class TeleopTask implements OnboardTask {

    /** Settings (names match the Metatype description). */
    public @interface Config {
        /** @return seconds without a twist after which the robot brakes (deadman) */
        double timeout() default 0.5;

        /** @return largest joystick linear speed, m/s (also bounded by the motion limits) */
        double maxLinear() default 0.5;

        /** @return largest joystick angular speed, rad/s (also bounded by the motion limits) */
        double maxAngular() default 1.5;
    }

    private Config config;

    @Activate
    void activate(Config c) {
        this.config = c;
    }

    /** @return the configured settings */
    Config config() {
        return config;
    }

    @Override
    public String name() {
        return "teleop";
    }

    @Override
    public String status() {
        return "joystick, deadman " + config.timeout() + " s";
    }
}
