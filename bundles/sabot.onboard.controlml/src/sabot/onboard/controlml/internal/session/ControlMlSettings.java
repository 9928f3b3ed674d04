package sabot.onboard.controlml.internal.session;

import java.io.IOException;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;

import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.stringprep.XmppStringprepException;
import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;

import sabot.controlml.ControlMl;
import sabot.controlml.Role;
import sabot.controlml.payload.TelemetryRates;
import sabot.fleet.AccessRules;
import sabot.fleet.LinkWatch;
import sabot.fleet.ServerTrust;
import sabot.onboard.task.SettingsParser;
import sabot.onboard.task.TaskProperties;
import sabot.onboard.task.OnboardTask;
import sabot.onboard.task.TaskSettingsCheck.Problem;

/**
 * The settings of the {@code controlml} task that the session uses (all of {@link Config} but the telemetry rates,
 * which belong to the ControlML endpoint). Types and ranges are the Metatype's; this adds what it cannot say: JID
 * syntax, the password file's existence and permissions, reconnectMin &le; reconnectMax.
 *
 * @param servers           the XMPP server's host name or IP address; several: the nodes of a cluster on one port,
 *                          tried in turn (the first until it fails)
 * @param port              its c2s port
 * @param jid               the robot's account
 * @param password          read from the password file: the account's password, or an enrolment token that the
 *                          session replaces at its first login ({@link sabot.fleet.Enrolment})
 * @param passwordFile      that file (absolute)
 * @param resource          the resource the session binds
 * @param reconnectMin      first delay after a loss or failed attempt; doubles up to {@code reconnectMax}
 * @param reconnectMax      longest delay between two attempts
 * @param access            who holds which role: the lab's server groups of the configuration, or everyone a
 *                          maintainer when {@code openPolicy} says so
 * @param open              whether {@code access} is the open policy (everyone a maintainer), said so explicitly
 * @param staleCommandAfter sets that waited longer at the server are refused
 * @param liveness          silence from the server after which it is pinged; twice it, the link is taken as lost
 * @param robotName         the robot's name (the file's {@code robot.name}), used as the vCard's nickname
 * @param trust             whom the session trusts for the server's certificate (TLS is always required)
 * @param lobby             the fleet lobby the session joins after each login (roster rule 11), or empty for none
 */
public record ControlMlSettings(List<String> servers, int port, EntityBareJid jid, String password, Path passwordFile,
        String resource,
        Duration reconnectMin, Duration reconnectMax, AccessRules access, boolean open, Duration staleCommandAfter,
        Duration liveness, String robotName, ServerTrust trust, Optional<EntityBareJid> lobby) {

    /** The task's name. */
    public static final String TASK = "controlml";

    static final String DEFAULT_SERVER = "127.0.0.1";
    static final int DEFAULT_PORT = 5222;
    static final String DEFAULT_RESOURCE = "onboard";
    static final double DEFAULT_RECONNECT_MIN_S = 1;
    static final double DEFAULT_RECONNECT_MAX_S = 30;
    /** {@code StaleCommandPolicy.DEFAULT}'s age, s. */
    static final double DEFAULT_STALE_COMMAND_AFTER_S = ControlMl.DEFAULT_STALE_COMMAND_S;
    /** Default liveness interval, s: a silent link is noticed within 2¼ of it, so that a moving robot brakes. */
    static final double DEFAULT_LIVENESS_S = LinkWatch.DEFAULT_INTERVAL_S;
    /** Telemetry while nobody watches: every 5 s (docs/CONTROLML.md section 6, "Leases"). */
    static final double DEFAULT_BASE_RATE_HZ = 0.2;
    static final double DEFAULT_LEASE_MAX_S = 60;
    /**
     * The lab's groups, the defaults of the group settings (one source: {@link AccessRules}). The lab's robots observe
     * one another: each needs the others' positions to keep clear of them (the {@code peers} task leases them), and
     * an observer cannot command.
     */
    static final String LAB_OBSERVERS = AccessRules.OBSERVERS_GROUP + "," + AccessRules.ROBOTS_GROUP,
            LAB_OPERATORS = AccessRules.OPERATORS_GROUP, LAB_MAINTAINERS = AccessRules.MAINTAINERS_GROUP;
    /** Shortest reconnection delay, s. */
    static final double MIN_RECONNECT_S = 0.001;

    /** Keys (setting ids) of the settings read here. */
    static final String SERVER = "server", PORT = "port", JID = "jid", PASSWORD_FILE = "passwordFile",
            RESOURCE = "resource", RECONNECT_MIN = "reconnectMin", RECONNECT_MAX = "reconnectMax",
            OBSERVER_GROUPS = "observerGroups", OPERATOR_GROUPS = "operatorGroups",
            MAINTAINER_GROUPS = "maintainerGroups", OPEN_POLICY = "openPolicy", STALE_COMMAND_AFTER = "staleCommandAfter", LIVENESS = "liveness",
            CA_FILE = "caFile", LOBBY = "lobby";

    /**
     * The {@code controlml} task's settings: its Metatype description, generated from these annotations. The session
     * reads them through {@link ControlMlSettings#of}; the ControlML endpoint, which shares the configuration, takes
     * the telemetry rates through this type.
     */
    @ObjectClassDefinition(id = OnboardTask.PID_PREFIX + TASK, name = "ControlML session", description = "The "
            + "robot's XMPP account, its reconnection, who may command it, and the telemetry rates.")
    public @interface Config {
        /** Highest telemetry rate, Hz. */
        double MAX_RATE_HZ = TelemetryRates.MAX_RATE_HZ;

        @AttributeDefinition(name = "Server", description = "The XMPP server: a host name or an IP address; several,"
                + " comma-separated, for the nodes of a cluster on one port (docs/CLUSTER.md): the session keeps to one"
                + " until an attempt there fails, then tries the next at once. The session always requires TLS "
                + "(STARTTLS), with a certificate that names the account's domain and is signed by the CA of caFile.")
        String server() default DEFAULT_SERVER;

        @AttributeDefinition(name = "CA file", required = false, description = "PEM file of the certificate "
                + "authority that signs the server's certificate: the lab CA that ./sabot xmpp start makes (its state "
                + "folder's ca/ca.pem) or a lab's own. Empty: the JVM's default trust store (a server with a publicly "
                + "signed certificate).")
        String caFile() default "";

        @AttributeDefinition(name = "Port", description = "The server's client-to-server TCP port.", min = "1",
                max = "65535")
        int port() default DEFAULT_PORT;

        @AttributeDefinition(name = "Account", description = "The robot's bare JID, e.g. sabot-01@sabot.local.")
        String jid();

        @AttributeDefinition(name = "Password file", description = "File whose first line is the account's password; "
                + "a regular file readable by its owner only (chmod 600). An enrolment token there (./sabot enrol "
                + "token) is replaced at the first login with a password of the robot's own.")
        String passwordFile();

        @AttributeDefinition(name = "Resource", description = "The XMPP resource of the robot's session.")
        String resource() default DEFAULT_RESOURCE;

        @AttributeDefinition(name = "First reconnection delay", description = "Seconds before the first new attempt "
                + "after a loss or a failed attempt; the delay doubles after each failure.", min = "" + MIN_RECONNECT_S,
                max = "3600")
        double reconnectMin() default DEFAULT_RECONNECT_MIN_S;

        @AttributeDefinition(name = "Longest reconnection delay", description = "Seconds between two attempts at "
                + "most; at least reconnectMin.", min = "" + MIN_RECONNECT_S, max = "3600")
        double reconnectMax() default DEFAULT_RECONNECT_MAX_S;

        @AttributeDefinition(name = "Observer groups", required = false, description = "Comma-separated shared "
                + "groups of the lab's XMPP server whose members are observers of this robot: every get, its "
                + "presence and telemetry (docs/SECURITY.md: roles). By default also the lab's robots, which follow "
                + "one another's positions to keep clear of them (the peers task) and cannot command.")
        String observerGroups() default LAB_OBSERVERS;

        @AttributeDefinition(name = "Operator groups", required = false, description = "Comma-separated shared "
                + "groups whose members are operators: also goals, trajectories, the joystick, re-localisation, "
                + "mission commands (stop, pause, resume).")
        String operatorGroups() default LAB_OPERATORS;

        @AttributeDefinition(name = "Maintainer groups", required = false, description = "Comma-separated shared "
                + "groups whose members are maintainers: also PID gains and the step test, limits, the map, file "
                + "writes and deletes, maintenance mode. At least one group must hold a role (or openPolicy).")
        String maintainerGroups() default LAB_MAINTAINERS;

        @AttributeDefinition(name = "Open policy", description = "true: everyone who can reach the robot is its "
                + "maintainer, whatever the groups say. For a lab whose server admits only its own people; the robot "
                + "warns of it at each start.")
        boolean openPolicy() default false;

        @AttributeDefinition(name = "Stale command age", description = "Seconds since a set was sent (its send "
                + "time, on the sender's clock as measured by XEP-0202, or the server's delay stamp of an offline "
                + "delivery) after which it is refused as stale; keep it below the workbench's request timeout (10 s)"
                + " so that a command its operator saw time out is never applied.", min = "0", max = "86400")
        double staleCommandAfter() default DEFAULT_STALE_COMMAND_AFTER_S;

        @AttributeDefinition(name = "Fleet lobby", required = false, description = "Bare JID of the lab's fleet "
                + "lobby, a multi-user chat room (XEP-0045) such as fleet@conference.sabot.local, that the session "
                + "joins after each login so that workbenches and other robots find it online (roster rule 11, "
                + "docs/CONTROLML.md); its occupants are candidates of the peers task. Empty: no lobby. A lobby that "
                + "cannot be joined is logged and the session goes on without it.")
        String lobby() default "";

        @AttributeDefinition(name = "Liveness interval", description = "Seconds without anything from the server "
                + "after which the session pings it (XEP-0199); after twice as long the link is taken as lost (a "
                + "silent network: nothing closed, nothing passing): the robot brakes if it moves and reconnects.",
                min = "0.1", max = "60")
        double liveness() default DEFAULT_LIVENESS_S;

        @AttributeDefinition(name = "Position telemetry rate", description = "Hz at which cm.position is published "
                + "while a watcher leases it (the most a lease gets); 0: not published.", min = "0", max = ""
                        + MAX_RATE_HZ)
        double positionRate() default 10;

        @AttributeDefinition(name = "Velocity telemetry rate", description = "Hz at which cm.velocity is published "
                + "while leased; 0: not published.", min = "0", max = "" + MAX_RATE_HZ)
        double velocityRate() default 10;

        @AttributeDefinition(name = "Mission telemetry rate", description = "Hz at which cm.mission is published "
                + "while leased; 0: not published.", min = "0", max = "" + MAX_RATE_HZ)
        double missionRate() default 1;

        @AttributeDefinition(name = "Obstacles telemetry rate", description = "Hz at which cm.obstacles is published "
                + "while leased; 0: not published.", min = "0", max = "" + MAX_RATE_HZ)
        double obstaclesRate() default 2;

        @AttributeDefinition(name = "Battery telemetry rate", description = "Hz at which cm.battery is published "
                + "while leased (the power board is read about once a second); 0: not published.", min = "0",
                max = "" + MAX_RATE_HZ)
        double batteryRate() default 1;

        @AttributeDefinition(name = "Passage telemetry rate", description = "Hz at which cm.passage (the robot's "
                + "claim on a narrow passage of its map) is published while leased: the other robots take turns by it "
                + "(docs/PASSAGES.md); 0: not published.", min = "0", max = "" + MAX_RATE_HZ)
        double passageRate() default 5;

        @AttributeDefinition(name = "Telemetry base rate", description = "Hz at which each telemetry resource is "
                + "published while nobody leases it (never above that resource's rate): a robot nobody watches "
                + "still shows where it is and what it does. 0: only while leased (a watcher's explicit "
                + "subscription then waits for a lease to create the node).", min = "0", max = "" + MAX_RATE_HZ)
        double baseRate() default DEFAULT_BASE_RATE_HZ;

        @AttributeDefinition(name = "Longest telemetry lease", description = "Seconds a watcher's lease of faster "
                + "telemetry lasts at most before it must be renewed (a longer one is cut to it).", min = "1",
                max = "" + TelemetryRates.MAX_LEASE_S)
        double leaseMax() default DEFAULT_LEASE_MAX_S;
    }


    /**
     * @param properties the task's configuration
     * @throws sabot.onboard.task.InvalidSettings listing every problem
     */
    public static ControlMlSettings of(Map<String, ?> properties) {
        return PARSER.of(TASK, properties);
    }

    /** @return the problems of a configuration, in key order of the Metatype; empty when {@link #of} succeeds */
    public static List<Problem> problems(Map<String, ?> properties) {
        return PARSER.problems(properties);
    }

    /** The one parse behind {@link #of} and {@link #problems}. */
    private static final SettingsParser<ControlMlSettings> PARSER = ControlMlSettings::parse;

    @Override
    public String toString() { // never the password
        return "ControlMlSettings[servers=" + servers + ", port=" + port + ", jid=" + jid + ", resource=" + resource
                + ", reconnect " + reconnectMin + ".." + reconnectMax + ", roles " + (open ? "open" : access.describe())
                + ", trust "
                + trust.describe() + lobby.map(l -> ", lobby " + l).orElse("") + "]";
    }

    private static ControlMlSettings parse(Map<String, ?> properties, List<Problem> problems) {
        TaskProperties p = new TaskProperties(properties);
        List<String> servers = new ArrayList<>();
        for (String item : p.string(SERVER, DEFAULT_SERVER).split(",")) {
            String server = item.strip();
            if (server.isEmpty() || server.chars().anyMatch(c -> Character.isWhitespace(c) || Character.isISOControl(c)
                    || c == '/')) {
                problems.add(new Problem(SERVER, "'" + server.replaceAll("\\p{Cntrl}", "?") + "' is not a server (a "
                        + "host name or an IP address; several, comma-separated)"));
            } else {
                servers.add(server);
            }
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
            jid = bareJid(p.string(JID, ""), JID, "sabot-01@sabot.local", problems);
        }
        String password = null;
        Path file = null;
        if (!p.has(PASSWORD_FILE)) {
            problems.add(new Problem(PASSWORD_FILE, "no password file given"));
        } else {
            file = Paths.get(p.string(PASSWORD_FILE, "")).toAbsolutePath().normalize();
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
        Duration reconnectMin = seconds(p, RECONNECT_MIN, DEFAULT_RECONNECT_MIN_S, MIN_RECONNECT_S, problems);
        Duration reconnectMax = seconds(p, RECONNECT_MAX, DEFAULT_RECONNECT_MAX_S, MIN_RECONNECT_S, problems);
        if (reconnectMin != null && reconnectMax != null && reconnectMax.compareTo(reconnectMin) < 0) {
            problems.add(new Problem(RECONNECT_MAX, "reconnectMax (" + seconds(reconnectMax)
                    + " s) is below reconnectMin (" + seconds(reconnectMin) + " s)"));
        }
        boolean open = p.bool(OPEN_POLICY, false);
        AccessRules access = AccessRules.none();
        access = access.withGroups(Role.OBSERVER, groups(p, OBSERVER_GROUPS, LAB_OBSERVERS, problems));
        access = access.withGroups(Role.OPERATOR, groups(p, OPERATOR_GROUPS, LAB_OPERATORS, problems));
        access = access.withGroups(Role.MAINTAINER, groups(p, MAINTAINER_GROUPS, LAB_MAINTAINERS, problems));
        if (!open && access.grantsNothing()) {
            problems.add(new Problem(MAINTAINER_GROUPS, "no group holds a role, so nobody could command this robot: "
                    + "name the lab's maintainer group (or set openPolicy = true, for a lab whose server admits only "
                    + "its own people)"));
        }
        Duration stale = seconds(p, STALE_COMMAND_AFTER, DEFAULT_STALE_COMMAND_AFTER_S, 0, problems);
        Duration liveness = seconds(p, LIVENESS, DEFAULT_LIVENESS_S, 0.1, problems);
        ServerTrust trust = null;
        try {
            trust = ServerTrust.of(p.string(CA_FILE, ""));
        } catch (IOException e) {
            problems.add(new Problem(CA_FILE, e.getMessage()));
        }
        Optional<EntityBareJid> lobby = Optional.empty();
        if (p.has(LOBBY)) {
            lobby = Optional.ofNullable(bareJid(p.string(LOBBY, ""), LOBBY, "fleet@conference.sabot.local", problems));
        }
        String robotName = p.string(OnboardTask.ROBOT_NAME, "");
        if (robotName.isEmpty() && jid != null) {
            robotName = jid.getLocalpart().toString();
        }
        if (!problems.isEmpty()) {
            return null;
        }
        return new ControlMlSettings(List.copyOf(servers), port, jid, password, file, resource, reconnectMin, reconnectMax,
                open ? AccessRules.none() : access, open, stale, liveness, robotName, trust, lobby);
    }

    /** @return the comma-separated group names of {@code key}; a name with a control character is a problem */
    private static Set<String> groups(TaskProperties p, String key, String fallback, List<Problem> problems) {
        Set<String> names = new LinkedHashSet<>();
        for (String item : p.string(key, fallback).split(",")) {
            String name = item.strip();
            if (name.chars().anyMatch(Character::isISOControl)) {
                problems.add(new Problem(key, "group name '" + name.replaceAll("\\p{Cntrl}", "?") + "' has a control "
                        + "character"));
            } else if (!name.isEmpty()) {
                names.add(name);
            }
        }
        return names;
    }

    /** @return the bare JID {@code text}, or null when it is none (a problem added, naming {@code example}) */
    private static EntityBareJid bareJid(String text, String key, String example, List<Problem> problems) {
        try {
            Jid jid = JidCreate.from(text);
            if (jid.isEntityBareJid()) {
                return jid.asEntityBareJidIfPossible();
            }
        } catch (XmppStringprepException | IllegalArgumentException e) {
            // reported below, with the expected form
        }
        problems.add(new Problem(key, "'" + text + "' is not a bare JID (local@domain without a resource, e.g. "
                + example + ")"));
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
