package sabot.onboard.task;

import java.net.URI;
import java.util.Optional;

import org.osgi.annotation.versioning.ConsumerType;

/**
 * A unit of robot work that the onboard product starts when its configuration file enables it (planner,
 * tracker, localizer, Modbus master, diagnostics...).
 * <p>
 * A task is a Declarative Services component named {@code sabot.task.<name>} with
 * {@code configuration-policy = REQUIRE} that provides this service: the onboard application creates the
 * component's configuration (PID = component name) from the file's {@code <name>.<setting>} keys when the task is
 * listed in {@code tasks}, and deletes it otherwise, so DS activates exactly the configured tasks. The settings a
 * task accepts, with types, ranges ({@code min}, {@code max}) and options, are declared in an OSGi Metatype
 * description for that PID: an {@code @ObjectClassDefinition} on the task's configuration annotation and
 * {@code @Designate} on the component, from which bnd generates {@code OSGI-INF/metatype/<pid>.xml} at build time (a
 * bundle's {@code pde.bnd} with {@code -metatypeannotations: *}). The file is checked against it before anything
 * starts, and so are the checks a {@link TaskSettingsCheck} service adds.
 * Besides its own settings, every task's configuration carries {@link #ROBOT_NAME} (the file's {@code robot.name}).
 */
@ConsumerType
public interface OnboardTask {

    /** Prefix of every task's component name and configuration PID. */
    String PID_PREFIX = "sabot.task.";

    /**
     * Configuration property every task receives besides its own settings: the robot's name from the file's
     * {@code robot.name} (in a component property type, the method {@code robot_name()}).
     */
    String ROBOT_NAME = "robot.name";

    /**
     * Property marking a configuration that a task writes for another service (e.g. the {@code portal} task's
     * configuration of the HTTP service): its value is the task's name. The task deletes it when it stops; at start
     * the onboard application also deletes those of the tasks not enabled, as a process that was killed leaves them
     * in Config Admin. The same property as a {@link TaskSettingsCheck}'s ({@link TaskSettingsCheck#TASK}).
     *
     * @since 0.3
     */
    String TASK_PROPERTY = TaskSettingsCheck.TASK;

    /** @return the task's name as written in the configuration file, e.g. {@code heartbeat}; never null */
    String name();

    /** @return a one-line human-readable state of the task, e.g. for an operator's task list; never null */
    String status();

    /**
     * @return the address of a web page this task serves for people standing at the robot (the {@code portal} task's
     *         status and configuration page); the robot's session puts the first running task's page into its vCard's
     *         {@code URL}. Empty for a task that serves no page (this default).
     * @since 0.2
     */
    default Optional<URI> page() {
        return Optional.empty();
    }
}
