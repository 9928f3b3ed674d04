package sabot.tools.load;

import java.io.IOException;
import java.io.PrintStream;
import java.nio.file.Path;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Random;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.SmackConfiguration;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.SubscribeListener.SubscribeAnswer;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smack.xml.SmackXmlParser;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.TelemetryLeases;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.LimitsPayload;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.controlml.payload.VelocityCommand;
import sabot.fleet.PresenceLevels;
import sabot.fleet.ServerTrust;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.map.MapServerFormat;
import sabot.model.map.OccupancyGrid;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * {@code ./sabot load}: N simulated robots, each a real ControlML endpoint (the {@code sabot.controlml} library's
 * device side) on its own XMPP account of a private Prosody or ejabberd. Each robot
 * drives a circle of its own (centre on a grid over the lab, radius, speed and phase drawn from a fixed seed: the same
 * seed gives the same fleet), publishes {@code cm.position} and {@code cm.velocity} at the rate given (default 10 Hz)
 * and {@code cm.mission} at 1 Hz (the onboard product's defaults, docs/CONTROLML.md §4), and answers gets of position,
 * velocity, goal, trajectory, mission, map (the lab map at 0.1 m, 120 × 90 cells: it fits one payload), obstacles
 * (none) and limits, and sets of goal, mission and velocity.
 * <p>
 * What it is not: a robot. A goal is taken (the mission runs, progress grows over {@link #MISSION_SECONDS} s, then
 * done) but the robot keeps to its circle; the onboard product with {@code sabot-sim} is the real thing, at one
 * simulator per robot.
 * <p>
 * Rules as a robot keeps them (docs/CONTROLML.md §7, §9): the operator may set, everyone else is refused; the robot
 * approves the operator's presence subscription and subscribes back; its presence carries the presence level.
 */
public final class FleetLoad implements AutoCloseable {

    /** How long a taken goal's mission runs before it is done, seconds. */
    static final double MISSION_SECONDS = 5;
    /** Lab floor the robots' circles are spread over, metres (inside the lab map, 12 m × 9 m). */
    static final double[] FLOOR = { 0.6, 0.6, 11.4, 8.4 };

    private final List<Robot> robots = new ArrayList<>();
    private final Instant epoch = Instant.now();

    /** The longest telemetry lease a load robot grants (Sabot Onboard's default). */
    static final double LEASE_MAX_S = 60;

    /** One simulated robot: its connection and its circle. */
    final class Robot {
        final String name;
        final XMPPTCPConnection connection;
        final ControlMlManager manager;
        final double cx, cy, radius, omega, phase;
        /** Its telemetry: at the base rate, faster while the operator's workbench leases it (CONTROLML.md §6). */
        TelemetryLeases leases;
        private Goal goal;
        private MissionStatus mission = new MissionStatus(MissionState.IDLE, false, 0, "");
        private Instant missionStart;

        Robot(String name, XMPPTCPConnection connection, double cx, double cy, double radius, double omega,
                double phase) {
            this.name = name;
            this.connection = connection;
            this.manager = ControlMlManager.getInstanceFor(connection);
            this.cx = cx;
            this.cy = cy;
            this.radius = radius;
            this.omega = omega;
            this.phase = phase;
        }

        EntityBareJid jid() {
            return connection.getUser().asEntityBareJid();
        }

        PoseEstimate pose(Instant now) {
            double t = Duration.between(epoch, now).toNanos() / 1e9;
            double a = phase + omega * t;
            double theta = Math.IEEEremainder(a + Math.signum(omega) * Math.PI / 2, 2 * Math.PI);
            return new PoseEstimate(now, new Pose2D(cx + radius * Math.cos(a), cy + radius * Math.sin(a), theta),
                    new PoseCovariance(0.004, 0.0005, 0, 0.003, 0, 0.002));
        }

        VelocityCommand velocity(Instant now) {
            return new VelocityCommand(now, new Twist2D(Math.abs(omega) * radius, omega));
        }

        synchronized MissionStatus mission(Instant now) {
            if (mission.state() == MissionState.RUNNING) {
                double p = Math.min(100, 100 * Duration.between(missionStart, now).toNanos() / 1e9 / MISSION_SECONDS);
                mission = p >= 100 ? new MissionStatus(MissionState.DONE, false, 100, "goal reached")
                        : new MissionStatus(MissionState.RUNNING, false, p, "to the goal");
                if (mission.state() == MissionState.DONE) {
                    announce(MissionState.DONE);
                }
            }
            return mission;
        }

        synchronized Outcome<Goal> takeGoal(Goal g) {
            goal = g;
            missionStart = Instant.now();
            mission = new MissionStatus(MissionState.RUNNING, false, 0, "to the goal");
            announce(MissionState.RUNNING);
            return Outcome.done();
        }

        synchronized Outcome<MissionStatus> command(MissionStatus m) {
            if (m.state() == MissionState.ABORTED && mission.state().isActive()) {
                mission = new MissionStatus(MissionState.ABORTED, false, mission.progress(), m.detail());
                announce(MissionState.ABORTED);
                return Outcome.done();
            }
            return Outcome.failure(ControlMlCondition.INVALID_STATE, "load robot " + name + ": mission is "
                    + mission.state().code() + "; it only aborts a running mission");
        }

        synchronized Outcome<Goal> goal() {
            return goal == null ? Outcome.failure(ControlMlCondition.INVALID_STATE, "no goal since the robot started")
                    : Outcome.success(goal);
        }

        synchronized Outcome<TrajectoryPayload> trajectory(Instant now) {
            if (goal == null || !mission.state().isActive()) {
                return Outcome.success(new TrajectoryPayload(now, List.of()));
            }
            Pose2D p = pose(now).pose();
            return Outcome.success(new TrajectoryPayload(now, List.of(new TrajectoryPoint(0, p.x(), p.y(), p.theta(), 0.3, 0),
                    new TrajectoryPoint(MISSION_SECONDS, goal.pose().x(), goal.pose().y(), goal.pose().theta(), 0,
                            0))));
        }

        private void announce(MissionState state) {
            try {
                connection.sendStanza(PresenceLevels.presenceFor(connection, state, false));
            } catch (Exception e) {
                // offline: the next login announces again
            }
        }

        void close() {
            if (leases != null) {
                leases.close();
            }
            connection.instantShutdown();
        }
    }

    /**
     * Starts the fleet: registers and logs in {@code count} robots named {@code prefix + i} (1-based, two digits at
     * least), installs their endpoints and starts their telemetry.
     *
     * @param server   the private server
     * @param count    robots, 1..1000
     * @param prefix   the robots' local part before the number
     * @param password their password
     * @param operator the account that may set (and follows them)
     * @param rateHz   position rate, Hz (mission: 1 Hz)
     * @param velocityRateHz velocity rate, Hz; 0: none
     * @param seed     the fleet's seed
     * @param map      the lab map's YAML (map_server), halved to 0.1 m a cell for {@code cm.map}
     */
    public static FleetLoad start(PrivateXmppServer server, int count, String prefix, String password,
            BareJid operator, double rateHz, double velocityRateHz, long seed, Path map) throws Exception {
        server.registerAll(accounts(count, prefix, password));
        return start(server.port(), server.trust(), count, prefix, password, operator, rateHz, velocityRateHz, seed,
                map);
    }

    /**
     * As {@link #start(PrivateXmppServer, int, String, String, BareJid, double, double, long, Path)}, on a private
     * server on the loopback port {@code port}, started by another process, whose certificate {@code trust} checks;
     * that process has made the accounts ({@link #accounts}: in-band registration is closed).
     */
    public static FleetLoad start(int port, ServerTrust trust, int count, String prefix, String password,
            BareJid operator, double rateHz, double velocityRateHz, long seed, Path map) throws Exception {
        return start(port, trust, count, prefix, password, operator, rateHz, velocityRateHz, rateHz, seed, map);
    }

    /**
     * As {@link #start(int, ServerTrust, int, String, String, BareJid, double, double, long, Path)}, each robot
     * publishing at most at {@code baseRateHz} while no workbench leases faster telemetry (docs/CONTROLML.md section
     * 6, "Leases"): {@code rateHz} and {@code velocityRateHz} are then the rates a lease gets.
     */
    public static FleetLoad start(int port, ServerTrust trust, int count, String prefix, String password,
            BareJid operator, double rateHz, double velocityRateHz, double baseRateHz, long seed, Path map)
            throws Exception {
        if (count < 1 || count > 1000) {
            throw new IllegalArgumentException("robots: " + count + " is outside 1..1000");
        }
        GridMap grid = halved(MapServerFormat.load(map).grid());
        FleetLoad load = new FleetLoad();
        Random random = new Random(seed);
        int cols = (int) Math.ceil(Math.sqrt(count * (FLOOR[2] - FLOOR[0]) / (FLOOR[3] - FLOOR[1])));
        int rows = (int) Math.ceil(count / (double) cols);
        try {
            for (int i = 0; i < count; i++) {
                String name = name(prefix, i);
                XMPPTCPConnection c = new XMPPTCPConnection(PrivateXmppServer.configuration(port, trust, name,
                        PrivateXmppServer.DOMAIN, password).setResource("onboard").setSendPresence(false).build());
                // no stream management (as ./sabot bench controlml): with it, a server that lags behind 2,000
                // publications a second leaves Smack's queue of 1,024 unacknowledged stanzas full, and the robot's
                // connection fails (measured with 100 robots on ejabberd)
                c.setUseStreamManagement(false);
                double cx = FLOOR[0] + (i % cols + 0.5) * (FLOOR[2] - FLOOR[0]) / cols;
                double cy = FLOOR[1] + (i / cols + 0.5) * (FLOOR[3] - FLOOR[1]) / rows;
                double radius = 0.15 + 0.2 * random.nextDouble();
                double omega = (random.nextBoolean() ? 1 : -1) * (0.3 + 0.5 * random.nextDouble());
                double phase = 2 * Math.PI * random.nextDouble();
                Robot r = load.new Robot(name, c, cx, cy, radius, omega, phase);
                load.robots.add(r);
                serve(r, operator, grid);
                c.connect().login();
                c.sendStanza(PresenceLevels.presenceFor(c, MissionState.IDLE, false));
                r.leases = r.manager.telemetry().serveLeases(LEASE_MAX_S);
                r.leases.offer(Resources.POSITION, () -> r.pose(Instant.now()), Math.min(baseRateHz, rateHz), rateHz);
                if (velocityRateHz > 0) {
                    r.leases.offer(Resources.VELOCITY, () -> r.velocity(Instant.now()), Math.min(baseRateHz,
                            velocityRateHz), velocityRateHz);
                }
                r.leases.offer(Resources.MISSION, () -> r.mission(Instant.now()), Math.min(baseRateHz, 1), 1);
            }
        } catch (Exception | Error e) {
            load.close();
            throw e;
        }
        return load;
    }

    private static void serve(Robot r, BareJid operator, GridMap grid) {
        Roster roster = Roster.getInstanceFor(r.connection);
        roster.setSubscriptionMode(Roster.SubscriptionMode.manual);
        // the operator's subscription is approved and asked back (the robot's server must see the workbench's caps
        // to send it PEP notifications); anyone else is denied, as the onboard product does
        roster.addSubscribeListener((from, request) -> from.asBareJid().equals(operator)
                ? SubscribeAnswer.ApproveAndAlsoRequestIfRequired : SubscribeAnswer.Deny);
        ControlMlManager m = r.manager;
        m.setAccessPolicy(j -> j.asBareJid().equals(operator) ? Role.MAINTAINER : Role.NONE);
        m.onGet(Resources.POSITION, (q, n) -> Outcome.success(r.pose(Instant.now())));
        m.onGet(Resources.VELOCITY, (q, n) -> Outcome.success(r.velocity(Instant.now())));
        m.onGet(Resources.MISSION, (q, n) -> Outcome.success(r.mission(Instant.now())));
        m.onGet(Resources.GOAL, (q, n) -> r.goal());
        m.onGet(Resources.TRAJECTORY, (q, n) -> r.trajectory(Instant.now()));
        m.onGet(Resources.MAP, (q, n) -> Outcome.success(grid));
        m.onGet(Resources.OBSTACLES, (q, n) -> Outcome.success(new Obstacles(Instant.now(), List.of())));
        m.onGet(Resources.LIMITS, (q, n) -> Outcome.success(new LimitsPayload(0.5, 1.5, 0.5, 2.0)));
        m.onSet(Resources.GOAL, (q, g) -> r.takeGoal(g));
        m.onSet(Resources.MISSION, (q, s) -> r.command(s));
        m.onSet(Resources.VELOCITY, (q, v) -> Outcome.done());
    }

    /** The map at half the resolution (a cell: the most occupied of its four), so that it fits one cm.map payload. */
    static GridMap halved(OccupancyGrid g) {
        int w = g.width() / 2;
        int h = g.height() / 2;
        byte[] cells = new byte[w * h];
        for (int row = 0; row < h; row++) {
            for (int col = 0; col < w; col++) {
                int v = Math.max(Math.max(g.get(2 * col, 2 * row), g.get(2 * col + 1, 2 * row)), Math.max(g.get(2
                        * col, 2 * row + 1), g.get(2 * col + 1, 2 * row + 1)));
                cells[row * w + col] = (byte) v;
            }
        }
        return new GridMap(2 * g.resolution(), w, h, g.geometry().origin(), cells);
    }

    /** @return the robots' bare JIDs, in order */
    public List<EntityBareJid> jids() {
        return robots.stream().map(Robot::jid).toList();
    }

    /** @return the robots' telemetry publications that failed so far (refused, timed out or not sent) */
    public long telemetryFailed() {
        return robots.stream().mapToLong(r -> r.manager.telemetry().statistics().failed()).sum();
    }

    /** @return the robots' telemetry publications the server acknowledged so far */
    public long telemetryPublished() {
        return robots.stream().mapToLong(r -> r.manager.telemetry().statistics().published()).sum();
    }

    @Override
    public void close() {
        // a thread each: a connection whose writer is blocked waits for it a while before giving up
        List<Thread> closing = robots.stream().map(r -> {
            Thread t = new Thread(r::close, "close-" + r.name);
            t.start();
            return t;
        }).toList();
        for (Thread t : closing) {
            try {
                t.join();
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return;
            }
        }
    }

    // ------------------------------------------------------------------------------------------------ ./sabot load

    public static void main(String[] args) throws Exception {
        try {
            run(args);
        } catch (IllegalArgumentException e) {
            System.err.println("[load] error: " + e.getMessage());
            System.exit(2);
        }
    }

    private static void run(String[] args) throws Exception {
        int robots = 10;
        PrivateXmppServer.Kind kind = PrivateXmppServer.Kind.PROSODY;
        double rate = 10;
        double velocityRate = -1;
        double baseRate = -1;
        long seed = 1;
        long seconds = 0;
        int attach = 0;
        String operatorJid = null;
        String caFile = null;
        String password = "sabot";
        for (int i = 0; i < args.length; i++) {
            switch (args[i]) {
                case "--robots" -> robots = Integer.parseInt(value(args, ++i, "--robots"));
                case "--server" -> kind = serverKind(value(args, ++i, "--server"));
                case "--rate" -> rate = Double.parseDouble(value(args, ++i, "--rate"));
                case "--velocity-rate" -> velocityRate = Double.parseDouble(value(args, ++i, "--velocity-rate"));
                case "--base-rate" -> baseRate = Double.parseDouble(value(args, ++i, "--base-rate"));
                case "--seed" -> seed = Long.parseLong(value(args, ++i, "--seed"));
                case "--seconds" -> seconds = Long.parseLong(value(args, ++i, "--seconds"));
                case "--attach" -> attach = Integer.parseInt(value(args, ++i, "--attach"));
                case "--ca-file" -> caFile = value(args, ++i, "--ca-file");
                case "--operator" -> operatorJid = value(args, ++i, "--operator");
                case "--password" -> password = value(args, ++i, "--password");
                case "--help", "-h" -> {
                    System.out.println("usage: ./sabot load [--robots N (10)] [--server prosody|ejabberd] [--rate HZ "
                            + "(10)] [--velocity-rate HZ (as --rate; 0: none)] [--base-rate HZ (as --rate: the rate while no "
                            + "workbench leases more)] [--seed S (1)] [--seconds S (0: until Ctrl-C)]"
                            + " [--attach PORT --ca-file PEM --operator JID [--password PW (sabot)]: on a running "
                            + "private server whose lab CA is PEM, driven on standard input]");
                    return;
                }
                default -> throw new IllegalArgumentException("unknown option " + args[i] + " (--help)");
            }
        }
        if (robots < 1 || robots > 1000) {
            throw new IllegalArgumentException("--robots " + robots + " is outside 1..1000");
        }
        if (!(rate > 0 && rate <= 100) || velocityRate > 100) {
            throw new IllegalArgumentException("--rate/--velocity-rate: 0 < position rate <= 100 Hz, velocity rate <= "
                    + "100 Hz");
        }
        if (baseRate < 0) {
            baseRate = rate;
        } else if (baseRate > rate) {
            throw new IllegalArgumentException("--base-rate " + baseRate + " Hz: at most --rate (" + rate + " Hz)");
        }
        if (attach > 0) {
            if (operatorJid == null || caFile == null) {
                throw new IllegalArgumentException("--attach needs --operator JID and --ca-file PEM (the server's lab "
                        + "CA)");
            }
            ServerTrust trust = ServerTrust.labCa(Path.of(caFile));
            // standard output is the protocol's alone: everything else (the log) goes to standard error
            PrintStream protocol = System.out;
            System.setOut(System.err);
            setUpSmack();
            attached(protocol, attach, trust, robots, password, org.jxmpp.jid.impl.JidCreate.entityBareFrom(operatorJid),
                    rate, velocityRate < 0 ? rate : velocityRate, baseRate, seed);
            return;
        }
        setUpSmack();
        try (PrivateXmppServer server = PrivateXmppServer.of(kind).start()) {
            BareJid operator = server.register("operator", PrivateXmppServer.DOMAIN, "sabot");
            Path map = PrivateXmppServer.repositoryRoot().resolve("onboard-bridge/maps/lab.yaml");
            try (FleetLoad load = start(server, robots, "load-", "sabot", operator, rate, velocityRate < 0
                    ? rate : velocityRate, seed, map)) {
                System.out.printf(Locale.ROOT, "[load] %d robots (load-01..load-%02d@%s, password 'sabot') on %s "
                        + "127.0.0.1:%d, %.0f Hz; operator operator@%s password 'sabot' may set; seed %d%n", robots,
                        robots, PrivateXmppServer.DOMAIN, kind.name().toLowerCase(Locale.ROOT), server.port(), rate,
                        PrivateXmppServer.DOMAIN, seed);
                CountDownLatch stop = new CountDownLatch(1);
                Runtime.getRuntime().addShutdownHook(new Thread(stop::countDown));
                long end = seconds > 0 ? System.nanoTime() + TimeUnit.SECONDS.toNanos(seconds) : Long.MAX_VALUE;
                // a status line every 10 s until stopped or the time is up
                while (!stop.await(Math.min(10_000_000_000L, end - System.nanoTime()), TimeUnit.NANOSECONDS)
                        && System.nanoTime() < end) {
                    System.out.printf(Locale.ROOT, "[load] telemetry acknowledged %d, failed %d%n", load
                            .telemetryPublished(), load.telemetryFailed());
                }
            }
        }
    }

    /**
     * {@code --attach PORT}: the robots on a server another process started (the workbench benchmark's, which runs
     * the load in a process of its own: the workbench benchmark's LoadProcess). Standard output then carries the
     * protocol LoadProcess reads: {@value #READY} and the robots' JIDs, comma-separated, once all are online; for each
     * line {@value #COUNTS} read on standard input, {@value #COUNTS} with the publications acknowledged and failed so
     * far. The end of standard input stops the robots and the process.
     */
    private static void attached(PrintStream protocol, int port, ServerTrust trust, int robots, String password,
            EntityBareJid operator, double rate, double velocityRate, double baseRate, long seed) throws Exception {
        Path map = PrivateXmppServer.repositoryRoot().resolve("onboard-bridge/maps/lab.yaml");
        try (FleetLoad load = start(port, trust, robots, "load-", password, operator, rate, velocityRate, baseRate,
                seed, map)) {
            protocol.println(READY + " " + load.jids().stream().map(Object::toString).collect(java.util.stream
                    .Collectors.joining(",")));
            protocol.flush();
            java.io.BufferedReader in = new java.io.BufferedReader(new java.io.InputStreamReader(System.in,
                    java.nio.charset.StandardCharsets.UTF_8));
            for (String line; (line = in.readLine()) != null;) {
                if (line.strip().equals(COUNTS)) {
                    protocol.println(COUNTS + " " + load.telemetryPublished() + " " + load.telemetryFailed());
                    protocol.flush();
                }
            }
        }
    }

    /** @return the accounts of {@code count} robots named {@code prefix01..}, each with {@code password} */
    public static Map<EntityBareJid, String> accounts(int count, String prefix, String password) {
        Map<EntityBareJid, String> accounts = new LinkedHashMap<>();
        for (int i = 0; i < count; i++) {
            accounts.put(org.jxmpp.jid.impl.JidCreate.entityBareFromOrThrowUnchecked(name(prefix, i) + "@"
                    + PrivateXmppServer.DOMAIN), password);
        }
        return accounts;
    }

    private static String name(String prefix, int i) {
        return String.format(Locale.ROOT, "%s%02d", prefix, i + 1);
    }

    /** {@link #attached} protocol: the line that says the robots are online. */
    public static final String READY = "[load] ready";
    /** {@link #attached} protocol: the request for the counts and the start of the answer. */
    public static final String COUNTS = "[load] counts";

    /** @return the server kind named on the command line, or a precise error */
    public static PrivateXmppServer.Kind serverKind(String name) {
        return switch (name) {
            case "prosody" -> PrivateXmppServer.Kind.PROSODY;
            case "ejabberd" -> PrivateXmppServer.Kind.EJABBERD;
            default -> throw new IllegalArgumentException("--server '" + name + "': expected prosody or ejabberd");
        };
    }

    private static String value(String[] args, int i, String option) {
        if (i >= args.length) {
            throw new IllegalArgumentException(option + " needs a value");
        }
        return args[i];
    }

    /** Smack as the benchmarks use it: one parser factory, generous reply timeout (100 logins at once). */
    public static void setUpSmack() {
        SmackXmlParser.setXmlPullParserFactory(SmackXmlParser.getXmlPullParserFactory());
        SmackConfiguration.setDefaultReplyTimeout(20_000);
        if (System.getProperty("sabot.root") == null && System.getenv("SABOT_ROOT") != null) {
            System.setProperty("sabot.root", System.getenv("SABOT_ROOT"));
        }
    }
}
