package sabot.workbench.views;

import java.time.Instant;
import java.util.ArrayList;
import java.util.Hashtable;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.TreeMap;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;

import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.framework.ServiceRegistration;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Resource;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.Obstacle;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.ConnectionStatus;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetListener;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;

/**
 * A fleet the test drives by hand, published as a second {@link FleetState} service next to the ControlML plug-in's
 * (the views observe every fleet service; ranked above it, so that the views ask it for the map): bursts of telemetry for many robots at the pace the test chooses, without a
 * server in between. It follows the service's contract (a new listener first gets the present state; notifications in
 * order) and calls its listeners on the caller's thread. Commands are refused, except missions of several targets,
 * which are taken and kept ({@link #missions}) for the test to read; the map is an empty 12 x 9 m room.
 */
final class DrivenFleet implements FleetState, AutoCloseable {

    static final String DOMAIN = "driven.test";

    private final Map<String, RobotState> robots = new TreeMap<>();
    private final List<FleetListener> listeners = new CopyOnWriteArrayList<>();
    /** The missions the views sent ({@link #startMission}), in order; any thread. */
    final List<SentMission> missions = new CopyOnWriteArrayList<>();
    /** When set, missions are refused with this text ({@code invalid-value}) and not kept; any thread. */
    volatile String refuseMissions;
    private final ServiceRegistration<FleetState> registration;

    /** A mission of several targets as a view sent it. */
    record SentMission(String robot, List<MissionTarget> targets, boolean queue) {
    }

    /** Registers the fleet with the workbench bundle's context; {@link #close()} unregisters it. */
    DrivenFleet() {
        BundleContext context = FrameworkUtil.getBundle(FleetView.class).getBundleContext();
        registration = context.registerService(FleetState.class, this, new Hashtable<>(Map.of("service.ranking",
                100)));
    }

    /** @return the bare JID of robot {@code i} ({@code driven-007@driven.test}) */
    static String jid(int i) {
        return String.format("driven-%03d@%s", i, DOMAIN);
    }

    /** Adds or changes a robot, as the ControlML plug-in does on a presence or telemetry item. */
    void put(RobotState r) {
        robots.put(r.jid(), r);
        listeners.forEach(l -> l.robotChanged(r));
    }

    /** Removes a robot, as the ControlML plug-in does when it leaves the roster. */
    void remove(String jid) {
        robots.remove(jid);
        listeners.forEach(l -> l.robotRemoved(jid));
    }

    /** @return robot {@code jid} as last put; fails when there is none */
    RobotState get(String jid) {
        RobotState r = robots.get(jid);
        if (r == null) {
            throw new AssertionError("no driven robot " + jid);
        }
        return r;
    }

    /**
     * A robot live at a pose, with what the workspace draws for a robot on a mission: a trail of
     * {@link RobotState#TRAIL_POINTS} points (loops around its pose, within 0.45 m), a planned path, its goal, three
     * sonar obstacles and a covariance ellipse.
     */
    static RobotState busy(int i, double x, double y, double theta, Instant at) {
        RobotState r = RobotState.unknown(jid(i), String.format("driven-%03d", i)).withPresence(Availability.BUSY,
                "");
        // the trail: a lap of a 0.6 m circle, then the pose (spacing above TRAIL_SPACING_M keeps every point)
        for (int k = 0; k < RobotState.TRAIL_POINTS; k++) {
            double a = 2 * Math.PI * k / 30.0;
            double rad = 0.3 + 0.15 * k / RobotState.TRAIL_POINTS;
            r = r.withPose(new PoseEstimate(at, new Pose2D(x + rad * Math.cos(a), y + rad * Math.sin(a), a),
                    PoseCovariance.ZERO), at, receipt(at));
        }
        List<TrajectoryPoint> path = new ArrayList<>();
        for (int k = 0; k <= 20; k++) {
            path.add(new TrajectoryPoint(k * 0.5, x + 0.1 * k, y + 0.05 * k, theta, 0.2, 0));
        }
        Goal goal = new Goal(new Pose2D(x + 2, y + 1, theta), 0.1, 0.1);
        return r.withPlan(new TrajectoryPayload(at, path), goal).withMission(new MissionStatus(MissionState.RUNNING,
                false, 40, ""), at).withObstacles(new Obstacles(at, List.of(new Obstacle(x + 0.5, y, 0.1), new Obstacle(
                        x, y + 0.5, 0.1), new Obstacle(x - 0.5, y, 0.1))), at).withPose(pose(x, y, theta, at), at, receipt(at));
    }

    /**
     * @return a monotonic receipt time for a pose stamped {@code at} that arrived at once (no lag): the stamp's
     *         nanoseconds since the epoch, so that the driven robots' lags are zero whatever the test's timing
     */
    static long receipt(Instant at) {
        return at.getEpochSecond() * 1_000_000_000L + at.getNano();
    }

    /** @return a pose estimate with a covariance whose 95 % ellipse is a few centimetres */
    static PoseEstimate pose(double x, double y, double theta, Instant at) {
        return new PoseEstimate(at, new Pose2D(x, y, theta), new PoseCovariance(4e-4, 1e-4, 0, 2e-4, 0, 1e-3));
    }

    @Override
    public ConnectionStatus connection() {
        return new ConnectionStatus(ConnectionStatus.State.ONLINE, "operator@" + DOMAIN, "driven by the test",
                Instant.EPOCH);
    }

    @Override
    public List<RobotState> robots() {
        return List.copyOf(robots.values());
    }

    @Override
    public Optional<RobotState> robot(String jid) {
        return Optional.ofNullable(robots.get(jid));
    }

    @Override
    public void addListener(FleetListener listener) {
        if (!listeners.contains(listener)) {
            listeners.add(listener);
            robots.values().forEach(listener::robotChanged);
        }
    }

    @Override
    public void removeListener(FleetListener listener) {
        listeners.remove(listener);
    }

    @Override
    public void reconnect() {
        // nothing to connect to
    }

    private static <T> CompletableFuture<T> refused() {
        return CompletableFuture.failedFuture(new FleetCommandException(ControlMlCondition.UNSUPPORTED_OPERATION,
                "a driven test fleet takes no commands"));
    }

    @Override
    public CompletableFuture<Void> goTo(String robot, Goal goal) {
        return refused();
    }

    /** {@inheritDoc} Taken as it is, into {@link #missions}; refused while {@link #refuseMissions} is set. */
    @Override
    public CompletableFuture<Void> startMission(String robot, List<MissionTarget> targets, boolean queue) {
        String refusal = refuseMissions;
        if (refusal != null) {
            return CompletableFuture.failedFuture(new FleetCommandException(ControlMlCondition.INVALID_VALUE,
                    refusal));
        }
        missions.add(new SentMission(robot, List.copyOf(targets), queue));
        return CompletableFuture.completedFuture(null);
    }

    @Override
    public CompletableFuture<Void> stop(String robot) {
        return refused();
    }

    @Override
    public CompletableFuture<Void> drive(String robot, Twist2D twist) {
        return refused();
    }

    @Override
    public CompletableFuture<GridMap> map(String robot) {
        int w = 240;
        int h = 180;
        byte[] cells = new byte[w * h];
        for (int row = 0; row < h; row++) {
            for (int col = 0; col < w; col++) {
                boolean wall = row < 2 || row >= h - 2 || col < 2 || col >= w - 2 || (col == 120 && row % 60 > 20);
                cells[row * w + col] = (byte) (wall ? 100 : 0);
            }
        }
        return CompletableFuture.completedFuture(new GridMap(0.05, w, h, new Pose2D(0, 0, 0), cells));
    }

    @Override
    public <T> CompletableFuture<T> get(String robot, Resource<T, NoQuery> resource) {
        return refused();
    }

    @Override
    public <T, Q> CompletableFuture<T> get(String robot, Resource<T, Q> resource, Q query) {
        return refused();
    }

    @Override
    public <T> CompletableFuture<T> set(String robot, Resource<T, ?> resource, T value) {
        return refused();
    }

    @Override
    public void close() {
        registration.unregister();
    }
}
