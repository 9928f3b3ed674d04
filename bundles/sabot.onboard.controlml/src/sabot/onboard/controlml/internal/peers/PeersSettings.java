package sabot.onboard.controlml.internal.peers;

import java.util.List;
import java.util.Map;

import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;

import sabot.fleet.AccessRules;
import sabot.onboard.task.OnboardTask;
import sabot.onboard.task.SettingsParser;
import sabot.onboard.task.TaskProperties;
import sabot.onboard.task.TaskSettingsCheck.Problem;

/**
 * The settings of the {@code peers} task (declared by {@link Config}): how fast the other robots' telemetry is leased
 * and which of the server's shared groups says who is a robot.
 *
 * @param rateHz the rate leased of each followed robot's {@code cm.position}, {@code cm.velocity} and
 *               {@code cm.passage}, Hz (the robot publishes them at most at its own {@code controlml.positionRate},
 *               {@code velocityRate} and {@code passageRate})
 * @param group  the server's shared group of the lab's robots: only its members, as this robot's roster shows them,
 *               are followed
 */
public record PeersSettings(double rateHz, String group) {

    /** The task's name. */
    public static final String TASK = "peers";

    /** Default leased rate, Hz: a robot crossing at 0.5 m/s moves 10 cm between two poses. */
    static final double DEFAULT_RATE_HZ = 5;
    /** Lowest leased rate, Hz: slower, a moving robot is a metre away from its last pose. */
    static final double MIN_RATE_HZ = 0.5;
    /**
     * Highest leased rate, Hz: twice a robot's default full rate of poses ({@code controlml.positionRate}, 10 Hz); more
     * costs every robot's traffic with no gain for a costmap.
     */
    static final double MAX_RATE_HZ = 20;

    /** Keys (setting ids) of the settings read here. */
    static final String RATE = "rate", GROUP = "group";

    /**
     * The task's settings: its Metatype description, generated from these annotations. The task reads its
     * configuration through {@link PeersSettings#of}, which checks it again for any other Config Admin client.
     */
    @ObjectClassDefinition(id = OnboardTask.PID_PREFIX + TASK, name = "Fleet peers", description = "Follows the other "
            + "robots of the lab over the controlml session (their position, velocity and passage claim telemetry) "
            + "for the motion task's costmap, collision guard and passage rule: the robots the server puts in its "
            + "robots' group, online in the roster or in the fleet lobby (controlml.lobby).")
    public @interface Config {
        @AttributeDefinition(name = "Telemetry rate", description = "Hz of position, velocity and passage claim "
                + "leased from each followed robot (it publishes them at most at its own controlml.positionRate, "
                + "velocityRate and passageRate); the lease is renewed before it ends.", min = "" + MIN_RATE_HZ,
                max = "" + MAX_RATE_HZ)
        double rate() default DEFAULT_RATE_HZ;

        @AttributeDefinition(name = "Robots' group", description = "The XMPP server's shared group of the lab's "
                + "robots (Prosody mod_groups, ejabberd shared roster), which the server writes into this robot's "
                + "roster: only its members are followed, never an account that merely says it is a robot.")
        String group() default AccessRules.ROBOTS_GROUP;
    }

    /**
     * @param properties the task's configuration
     * @return the settings
     * @throws sabot.onboard.task.InvalidSettings listing every problem
     */
    public static PeersSettings of(Map<String, ?> properties) {
        return PARSER.of(TASK, properties);
    }

    /** @return the problems of a configuration, in the order found; empty when {@link #of} succeeds */
    public static List<Problem> problems(Map<String, ?> properties) {
        return PARSER.problems(properties);
    }

    /** The one parse behind {@link #of} and {@link #problems}. */
    private static final SettingsParser<PeersSettings> PARSER = PeersSettings::parse;

    private static PeersSettings parse(Map<String, ?> properties, List<Problem> problems) {
        TaskProperties p = new TaskProperties(properties);
        double rate = DEFAULT_RATE_HZ;
        try {
            rate = p.number(RATE, DEFAULT_RATE_HZ);
            if (!(rate >= MIN_RATE_HZ && rate <= MAX_RATE_HZ)) {
                problems.add(new Problem(RATE, "'" + rate + "' Hz is outside " + MIN_RATE_HZ + ".." + MAX_RATE_HZ));
            }
        } catch (IllegalArgumentException e) {
            problems.add(new Problem(RATE, e.getMessage()));
        }
        String group = p.string(GROUP, AccessRules.ROBOTS_GROUP);
        if (group.isEmpty()) {
            problems.add(new Problem(GROUP, "no group given (the server's shared group of the lab's robots, e.g. "
                    + AccessRules.ROBOTS_GROUP + ")"));
        } else if (group.chars().anyMatch(Character::isISOControl)) {
            problems.add(new Problem(GROUP, "group name '" + group.replaceAll("\\p{Cntrl}", "?") + "' has a control "
                    + "character"));
        }
        return problems.isEmpty() ? new PeersSettings(rate, group) : null;
    }
}
