package sabot.onboard.controlml.internal.endpoint;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.LinkedBlockingQueue;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.LimitsPayload;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.Obstacle;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PidGains;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.controlml.payload.VelocityCommand;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.BatteryState;
import sabot.onboard.robot.CommandRefused;
import sabot.onboard.robot.MotionListener;
import sabot.onboard.robot.RobotMotion;

/**
 * A recorded, in-memory robot for the endpoint's tests. It stands in for the control loop (the lead's
 * {@code sabot.task.navigation}), which the end-to-end tests with {@code sabot-sim} exercise: here nothing moves, but
 * every command is checked and applied to a state the test can compare, the way {@link RobotMotion}'s contract says,
 * and every command that reaches it is recorded (refused ones too), so a test can prove a request never got here.
 * <p>
 * The world: a 2 m x 2 m map at 0.1 m with an occupied 0.3 m block at (1.0..1.3, 1.0..1.3); physical limits 1 m/s,
 * 3 rad/s, 1 m/s², 4 rad/s²; two motors (0, 1); mission commands as in {@code docs/CONTROLML.md} "The onboard
 * endpoint". Listeners are told on a notifier thread of their own, in order.
 */
final class RecordedRobot implements RobotMotion {

    /** Everything a command may change; equal snapshots mean nothing changed. */
    record State(PoseEstimate pose, Twist2D twist, Optional<Goal> goal, TrajectoryPayload trajectory, GridMap map,
            LimitsPayload limits, PidGains gains, MissionStatus mission, boolean boardAnswering) {
    }

    static final Instant T0 = Instant.parse("2026-11-21T10:00:00Z");
    static final PoseCovariance INITIAL_COVARIANCE = PoseCovariance.diagonal(0.01, 0.01, 0.001);
    static final LimitsPayload PHYSICAL = new LimitsPayload(1.0, 3.0, 1.0, 4.0);
    static final GridMap LAB = labMap();

    private PoseEstimate pose = new PoseEstimate(T0, new Pose2D(0.5, 0.5, 0), INITIAL_COVARIANCE);
    private Twist2D twist = Twist2D.ZERO;
    private Optional<Goal> goal = Optional.empty();
    private TrajectoryPayload trajectory = new TrajectoryPayload(T0, List.of());
    private GridMap map = LAB;
    private LimitsPayload limits = new LimitsPayload(0.5, 1.5, 0.5, 2.0);
    private PidGains gains = new PidGains(List.of(new MotorGains(0, 1.2, 0.3, 0.01), new MotorGains(1, 1.2, 0.3,
            0.01)));
    private MissionStatus mission = new MissionStatus(MissionState.IDLE, false, 0, "");
    private Obstacles obstacles = new Obstacles(T0, List.of(new Obstacle(1.15, 1.15, 0.2)));
    private boolean boardAnswering = true;

    private final List<String> calls = new ArrayList<>();
    private long telemetryReads;
    private final List<MotionListener> listeners = new CopyOnWriteArrayList<>();
    private final ExecutorService notifier = Executors.newSingleThreadExecutor(r -> {
        Thread t = new Thread(r, "recorded-robot-notifier");
        t.setDaemon(true);
        return t;
    });
    /** "added" and "removed" as listeners come and go: the endpoint's activation and deactivation. */
    final BlockingQueue<String> listenerEvents = new LinkedBlockingQueue<>();

    private static GridMap labMap() {
        byte[] cells = new byte[20 * 20];
        for (int y = 10; y < 13; y++) {
            for (int x = 10; x < 13; x++) {
                cells[y * 20 + x] = 100;
            }
        }
        return new GridMap(0.1, 20, 20, new Pose2D(0, 0, 0), cells);
    }

    // ---------------------------------------------------------------------------------------------- test side

    /** @return the state now */
    synchronized State state() {
        return new State(pose, twist, goal, trajectory, map, limits, gains, mission, boardAnswering);
    }

    /** @return the commands that reached the robot, refused ones included, e.g. {@code navigateTo Goal[...]} */
    synchronized List<String> calls() {
        return List.copyOf(calls);
    }

    /** @return how many times pose, velocity, mission or obstacles were read (what telemetry publishes) */
    synchronized long telemetryReads() {
        return telemetryReads;
    }

    /** The motor board stops (false) or starts (true) answering. */
    synchronized void boardAnswering(boolean answering) {
        boardAnswering = answering;
    }

    /** The mission progresses without changing state (a progress band). */
    synchronized void progress(double percent) {
        changeMission(new MissionStatus(mission.state(), mission.maintenance(), percent, mission.detail()));
    }

    /** The running mission reaches its goal. */
    synchronized void arrive() {
        twist = Twist2D.ZERO;
        changeMission(new MissionStatus(MissionState.DONE, mission.maintenance(), 100, "arrived"));
    }

    /** The mission fails (a fault): the robot brakes. */
    synchronized void fail(String reason) {
        twist = Twist2D.ZERO;
        changeMission(new MissionStatus(MissionState.FAILED, mission.maintenance(), mission.progress(), reason));
    }

    // ---------------------------------------------------------------------------------------------- reads

    @Override
    public synchronized PoseEstimate pose() {
        telemetryReads++;
        return pose;
    }

    @Override
    public synchronized VelocityCommand velocity() {
        telemetryReads++;
        return new VelocityCommand(T0, twist);
    }

    @Override
    public synchronized Optional<Goal> goal() {
        return goal;
    }

    @Override
    public synchronized TrajectoryPayload trajectory() {
        return trajectory;
    }

    @Override
    public synchronized Obstacles obstacles() {
        telemetryReads++;
        return obstacles;
    }

    @Override
    public synchronized GridMap map() {
        return map;
    }

    @Override
    public synchronized LimitsPayload limits() {
        return limits;
    }

    @Override
    public synchronized MissionStatus mission() {
        telemetryReads++;
        return mission;
    }

    @Override
    public synchronized PidGains gains() throws CommandRefused {
        requireBoard();
        return gains;
    }

    /** The power board's reading: 42 % of 10 Ah at 25.3 V, 0.61 A away from a dock. */
    static final BatteryState BATTERY = new BatteryState(T0, 0.42, 25.3, 0.61, 10.0, false, false, false);
    private String batteryFault = "";

    /** Makes the power board's reads fail with that text (empty: they succeed again). */
    synchronized void batteryFault(String why) {
        batteryFault = why;
    }

    @Override
    public synchronized BatteryState battery() throws CommandRefused {
        telemetryReads++;
        if (!batteryFault.isEmpty()) {
            throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, batteryFault);
        }
        return BATTERY;
    }

    // ---------------------------------------------------------------------------------------------- commands

    @Override
    public synchronized void relocalise(Pose2D newPose) throws CommandRefused {
        calls.add("relocalise " + newPose);
        if (mission.state() == MissionState.RUNNING || !twist.equals(Twist2D.ZERO)) {
            throw new CommandRefused(ControlMlCondition.INVALID_STATE, "cannot re-localise while moving");
        }
        requireOnMap(newPose.x(), newPose.y(), "pose");
        pose = new PoseEstimate(pose.time(), newPose, INITIAL_COVARIANCE);
    }

    @Override
    public synchronized void teleop(Twist2D command, java.time.Instant sent, java.time.Duration age)
            throws CommandRefused {
        calls.add("teleop " + command);
        requireNoMaintenance();
        if (mission.state().isActive()) {
            throw new CommandRefused(ControlMlCondition.INVALID_STATE, "a mission is " + mission.state().code()
                    + ": abort it before driving by joystick");
        }
        twist = new Twist2D(clamp(command.linear(), limits.maxLinearSpeed()), clamp(command.angular(), limits
                .maxAngularSpeed()));
    }

    @Override
    public synchronized void navigateTo(Goal target) throws CommandRefused {
        calls.add("navigateTo " + target);
        requireNoMaintenance();
        requireBoard();
        double x = target.pose().x();
        double y = target.pose().y();
        requireOnMap(x, y, "goal");
        if (map.cells()[cellIndex(x, y)] >= 50) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, String.format("goal (%.2f, %.2f) is inside an"
                    + " obstacle", x, y));
        }
        goal = Optional.of(target);
        trajectory = new TrajectoryPayload(T0, List.of(
                new TrajectoryPoint(0, pose.pose().x(), pose.pose().y(), 0, 0, 0),
                new TrajectoryPoint(5, x, y, target.pose().theta(), 0, 0)));
        changeMission(new MissionStatus(MissionState.RUNNING, false, 0, String.format("to (%.2f, %.2f)", x, y)));
    }

    /** Records the mission; starts it (its targets pending, the first active) or counts it as queued. */
    @Override
    public synchronized void startMission(List<MissionTarget> targets, boolean queue) throws CommandRefused {
        calls.add((queue ? "queueMission " : "startMission ") + targets.size() + " targets");
        requireNoMaintenance();
        requireBoard();
        for (MissionTarget t : targets) {
            requireOnMap(t.goal().pose().x(), t.goal().pose().y(), "target");
        }
        if (queue && mission.state().isActive()) {
            changeMission(new MissionStatus(mission.state(), false, mission.progress(), mission.detail(), mission
                    .targets(), mission.current(), mission.queued() + 1));
            return;
        }
        List<MissionTarget> started = new ArrayList<>();
        for (MissionTarget t : targets) {
            started.add(t.in(started.isEmpty() ? MissionTarget.State.ACTIVE : MissionTarget.State.PENDING));
        }
        goal = Optional.of(targets.get(0).goal());
        changeMission(new MissionStatus(MissionState.RUNNING, false, 0, "target 1 of " + targets.size(), started, 0,
                mission.queued()));
    }

    @Override
    public synchronized void follow(TrajectoryPayload imposed) throws CommandRefused {
        calls.add("follow " + imposed.points().size() + " points");
        requireNoMaintenance();
        requireBoard();
        if (imposed.points().isEmpty()) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "an empty trajectory leads nowhere");
        }
        trajectory = imposed;
        changeMission(new MissionStatus(MissionState.RUNNING, false, 0, "following a trajectory"));
    }

    @Override
    public synchronized void replaceMap(GridMap newMap) throws CommandRefused {
        calls.add("replaceMap " + newMap);
        if (mission.state().isActive()) {
            throw new CommandRefused(ControlMlCondition.INVALID_STATE, "the map is in use by a " + mission.state()
                    .code() + " mission");
        }
        map = newMap;
    }

    @Override
    public synchronized void setLimits(LimitsPayload newLimits) throws CommandRefused {
        calls.add("setLimits " + newLimits);
        if (newLimits.maxLinearSpeed() > PHYSICAL.maxLinearSpeed() || newLimits.maxAngularSpeed() > PHYSICAL
                .maxAngularSpeed() || newLimits.maxLinearAcceleration() > PHYSICAL.maxLinearAcceleration()
                || newLimits.maxAngularAcceleration() > PHYSICAL.maxAngularAcceleration()) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "limits above the robot's physical ones "
                    + PHYSICAL);
        }
        limits = newLimits;
    }

    @Override
    public synchronized PidGains setGains(PidGains newGains) throws CommandRefused {
        calls.add("setGains " + newGains);
        requireBoard();
        List<MotorGains> merged = new ArrayList<>(gains.motors());
        for (MotorGains m : newGains.motors()) {
            if (m.motor() > 1) {
                throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "motor " + m.motor()
                        + ": the robot has motors 0 and 1");
            }
        }
        for (MotorGains m : newGains.motors()) {
            merged.set(m.motor(), m);
        }
        gains = new PidGains(merged);
        return gains;
    }

    @Override
    public synchronized void command(MissionStatus command) throws CommandRefused {
        calls.add("command " + command.state().code() + (command.maintenance() ? " maintenance" : ""));
        if (command.maintenance() != mission.maintenance()) {
            if (command.maintenance()) {
                twist = Twist2D.ZERO;
                MissionState state = mission.state().isActive() ? MissionState.ABORTED : mission.state();
                changeMission(new MissionStatus(state, true, mission.progress(), "maintenance"));
            } else {
                changeMission(new MissionStatus(mission.state(), false, mission.progress(), "maintenance over"));
            }
            return;
        }
        MissionState from = mission.state();
        MissionState to = command.state();
        boolean fits = switch (to) {
            case PAUSED -> from == MissionState.RUNNING;
            case RUNNING -> from == MissionState.PAUSED;
            case ABORTED -> from.isActive();
            default -> false;
        };
        if (!fits) {
            throw new CommandRefused(ControlMlCondition.INVALID_STATE, "cannot go from " + from.code() + " to "
                    + to.code());
        }
        if (to != MissionState.RUNNING) {
            twist = Twist2D.ZERO;
        }
        String detail = switch (to) {
            case PAUSED -> "paused by an operator";
            case ABORTED -> "aborted by an operator";
            default -> "resumed";
        };
        changeMission(new MissionStatus(to, false, mission.progress(), detail));
    }

    @Override
    public synchronized void stop(String reason, boolean fault) {
        calls.add("stop " + reason);
        twist = Twist2D.ZERO;
        changeMission(new MissionStatus(fault ? MissionState.FAILED : MissionState.ABORTED, mission.maintenance(),
                mission.progress(), reason));
    }

    @Override
    public void addListener(MotionListener listener) {
        listeners.add(listener);
        listenerEvents.add("added");
    }

    @Override
    public void removeListener(MotionListener listener) {
        listeners.remove(listener);
        listenerEvents.add("removed");
    }

    // ---------------------------------------------------------------------------------------------- helpers

    private void changeMission(MissionStatus status) {
        mission = status;
        for (MotionListener l : listeners) {
            notifier.execute(() -> l.missionChanged(status));
        }
    }

    private void requireNoMaintenance() throws CommandRefused {
        if (mission.maintenance()) {
            throw new CommandRefused(ControlMlCondition.MAINTENANCE_LOCK, "the robot is in maintenance");
        }
    }

    private void requireBoard() throws CommandRefused {
        if (!boardAnswering) {
            throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, "the motor board does not answer");
        }
    }

    private void requireOnMap(double x, double y, String what) throws CommandRefused {
        double width = map.width() * map.resolution();
        double height = map.height() * map.resolution();
        double ox = map.origin().x();
        double oy = map.origin().y();
        if (x < ox || y < oy || x >= ox + width || y >= oy + height) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, String.format("%s (%.2f, %.2f) is off the map",
                    what, x, y));
        }
    }

    private int cellIndex(double x, double y) {
        int col = (int) ((x - map.origin().x()) / map.resolution());
        int row = (int) ((y - map.origin().y()) / map.resolution());
        return row * map.width() + col;
    }

    private static double clamp(double value, double limit) {
        return Math.max(-limit, Math.min(limit, value));
    }
}
