package sabot.onboard.motion.internal;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;

import sabot.onboard.motion.loop.LoopDefaults;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code teleop}: joystick twists (ControlML {@code cm.velocity} sets) are accepted only when this task runs;
 * the deadman timeout brings the robot to rest when they stop. It is the control loop's one deadman: judged on each
 * twist's receive time, it brakes the robot whatever the smoother holds; the velocity smoother is given the same
 * timeout (the loop feeds it a target every period, so it would act only if the loop stopped feeding it), and the
 * motor board's own deadman ({@code motion.boardDeadman}) stops the wheels when the loop stops writing altogether.
 * Settings: {@link Config}.
 */
@Designate(ocd = TeleopTask.Config.class, factory = false)
@Component(name = "sabot.task.teleop", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, TeleopTask.class })
public final class TeleopTask implements OnboardTask {

    /** The task's settings: its Metatype description, generated from these annotations. */
    @ObjectClassDefinition(id = "sabot.task.teleop", name = "Teleop task",
            description = "Joystick twists with a deadman timeout.")
    public @interface Config {
        @AttributeDefinition(name = "Deadman timeout", description = "Seconds without a joystick twist (judged on "
                + "the time it was received) after which the robot brakes: the control loop's one deadman; the "
                + "velocity smoother's command timeout is the same.", min = "0.05", max = "10")
        double timeout() default LoopDefaults.DEADMAN;

        @AttributeDefinition(name = "Oldest twist", description = "Seconds since a joystick twist was sent (its "
                + "send time on the operator's clock, moved by the measured clock offset) after which it is dropped "
                + "(stale-command), whenever it arrives: a twist held by the network must not drive.", min = "0.01",
                max = "10")
        double maxAge() default LoopDefaults.TELEOP_MAX_AGE;

        @AttributeDefinition(name = "Largest linear speed", description = "Largest joystick linear speed, m/s (also "
                + "bounded by the motion limits).", min = "0.01", max = "10")
        double maxLinear() default 0.5;

        @AttributeDefinition(name = "Largest angular speed", description = "Largest joystick angular speed, rad/s "
                + "(also bounded by the motion limits).", min = "0.01", max = "20")
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
