package sabot.onboard.internal.session;

import java.nio.file.Path;
import java.nio.file.Paths;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;

import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.stringprep.XmppStringprepException;

import sabot.controlml.StaleCommandPolicy;
import sabot.onboard.internal.InvalidSettings;
import sabot.onboard.internal.TaskProperties;
import sabot.onboard.task.OnboardTask;
import sabot.onboard.task.TaskSettingsCheck.Problem;

/**
 * The settings of the {@code controlml} task that the session uses (OSGI-INF/metatype/controlml.xml; the telemetry
 * rates there belong to the ControlML endpoint). Types and ranges are the Metatype's; this adds what it cannot say:
 * JID syntax, the password file's existence and permissions, reconnectMin &le; reconnectMax. A test checks that the
 * Metatype defaults are the ones here.
 *
 * @param server            the XMPP server's host name or IP address
 * @param port              its c2s port
 * @param jid               the robot's account
 * @param password          read from the password file
 * @param resource          the resource the session binds
 * @param reconnectMin      first delay after a loss or failed attempt; doubles up to {@code reconnectMax}
 * @param reconnectMax      longest delay between two attempts
 * @param operators         who may set; empty: contacts with a mutual subscription (see {@link OperatorPolicy})
 * @param staleCommandAfter sets that waited longer at the server are refused
 * @param robotName         the robot's name (the file's {@code robot.name}), used as the vCard's nickname
 */
public record ControlMlSettings(String server, int port, EntityBareJid jid, String password, String resource,
        Duration reconnectMin, Duration reconnectMax, Set<EntityBareJid> operators, Duration staleCommandAfter,
        String robotName) {

    /** The task's name. */
    public static final String TASK = "controlml";

    static final String DEFAULT_SERVER = "127.0.0.1";
    static final int DEFAULT_PORT = 5222;
    static final String DEFAULT_RESOURCE = "onboard";
    static final double DEFAULT_RECONNECT_MIN_S = 1;
    static final double DEFAULT_RECONNECT_MAX_S = 30;
    static final double DEFAULT_STALE_COMMAND_AFTER_S = StaleCommandPolicy.DEFAULT.maxAge().toMillis() / 1000.0;

    /** Keys (setting ids) of the settings read here. */
    static final String SERVER = "server", PORT = "port", JID = "jid", PASSWORD_FILE = "passwordFile",
            RESOURCE = "resource", RECONNECT_MIN = "reconnectMin", RECONNECT_MAX = "reconnectMax",
            OPERATORS = "operators", STALE_COMMAND_AFTER = "staleCommandAfter";

    public ControlMlSettings {
        operators = Set.copyOf(operators);
    }

    /**
     * @param properties the task's configuration
     * @throws InvalidSettings listing every problem
     */
    public static ControlMlSettings of(Map<String, ?> properties) {
        List<Problem> problems = new ArrayList<>();
        ControlMlSettings s = parse(properties, problems);
        if (s == null) {
            throw new InvalidSettings(TASK, problems);
        }
        return s;
    }

    /** @return the problems of a configuration, in key order of the Metatype; empty when {@link #of} succeeds */
    public static List<Problem> problems(Map<String, ?> properties) {
        List<Problem> problems = new ArrayList<>();
        parse(properties, problems);
        return problems;
    }

    @Override
    public String toString() { // never the password
        return "ControlMlSettings[server=" + server + ", port=" + port + ", jid=" + jid + ", resource=" + resource
                + ", reconnect " + reconnectMin + ".." + reconnectMax + ", operators=" + operators + "]";
    }

    private static ControlMlSettings parse(Map<String, ?> properties, List<Problem> problems) {
        TaskProperties p = new TaskProperties(properties);
        String server = p.string(SERVER, DEFAULT_SERVER);
        if (server.isEmpty()) {
            problems.add(new Problem(SERVER, "no server given (a host name or an IP address)"));
        }
        int port = DEFAULT_PORT;
        try {
            long n = p.integer(PORT, DEFAULT_PORT);
            if (n < 1 || n > 65535) {
                problems.add(new Problem(PORT, "'" + n + "' is not a TCP port (1..65535)"));
            }
            port = (int) n;
        } catch (IllegalArgumentException e) {
            problems.add(new Problem(PORT, e.getMessage()));
        }
        EntityBareJid jid = null;
        if (!p.has(JID)) {
            problems.add(new Problem(JID, "no account given (the robot's bare JID, e.g. sabot-01@sabot.local)"));
        } else {
            jid = bareJid(p.string(JID, ""), JID, "", problems);
        }
        String password = null;
        if (!p.has(PASSWORD_FILE)) {
            problems.add(new Problem(PASSWORD_FILE, "no password file given"));
        } else {
            Path file = Paths.get(p.string(PASSWORD_FILE, "")).toAbsolutePath().normalize();
            try {
                password = PasswordFile.read(file);
            } catch (PasswordFile.Refused e) {
                problems.add(new Problem(PASSWORD_FILE, e.getMessage()));
            }
        }
        String resource = p.string(RESOURCE, DEFAULT_RESOURCE);
        if (resource.isEmpty() || resource.chars().anyMatch(c -> Character.isWhitespace(c) || c == '/')) {
            problems.add(new Problem(RESOURCE, "'" + resource + "' is not a resource (a word without spaces or /)"));
        }
        Duration reconnectMin = seconds(p, RECONNECT_MIN, DEFAULT_RECONNECT_MIN_S, 0.001, problems);
        Duration reconnectMax = seconds(p, RECONNECT_MAX, DEFAULT_RECONNECT_MAX_S, 0.001, problems);
        if (reconnectMin != null && reconnectMax != null && reconnectMax.compareTo(reconnectMin) < 0) {
            problems.add(new Problem(RECONNECT_MAX, "reconnectMax (" + seconds(reconnectMax)
                    + " s) is below reconnectMin (" + seconds(reconnectMin) + " s)"));
        }
        Set<EntityBareJid> operators = new LinkedHashSet<>();
        for (String item : p.string(OPERATORS, "").split(",")) {
            if (!item.isBlank()) {
                EntityBareJid op = bareJid(item.strip(), OPERATORS, " in the operator list", problems);
                if (op != null) {
                    operators.add(op);
                }
            }
        }
        Duration stale = seconds(p, STALE_COMMAND_AFTER, DEFAULT_STALE_COMMAND_AFTER_S, 0, problems);
        String robotName = p.string(OnboardTask.ROBOT_NAME, "");
        if (robotName.isEmpty() && jid != null) {
            robotName = jid.getLocalpart().toString();
        }
        if (!problems.isEmpty()) {
            return null;
        }
        return new ControlMlSettings(server, port, jid, password, resource, reconnectMin, reconnectMax, operators,
                stale, robotName);
    }

    private static EntityBareJid bareJid(String text, String key, String where, List<Problem> problems) {
        try {
            Jid jid = JidCreate.from(text);
            if (jid.isEntityBareJid()) {
                return jid.asEntityBareJidIfPossible();
            }
        } catch (XmppStringprepException | IllegalArgumentException e) {
            // reported below, with the expected form
        }
        problems.add(new Problem(key, "'" + text + "'" + where
                + " is not a bare JID (local@domain without a resource, e.g. sabot-01@sabot.local)"));
        return null;
    }

    private static Duration seconds(TaskProperties p, String key, double fallback, double min,
            List<Problem> problems) {
        try {
            double s = p.number(key, fallback);
            if (!Double.isFinite(s) || s < min) {
                problems.add(new Problem(key, "'" + s + "' s is not a duration of at least " + min + " s"));
                return null;
            }
            return Duration.ofNanos(Math.round(s * 1e9));
        } catch (IllegalArgumentException e) {
            problems.add(new Problem(key, e.getMessage()));
            return null;
        }
    }

    private static String seconds(Duration d) {
        return Double.toString(d.toNanos() / 1e9);
    }
}
