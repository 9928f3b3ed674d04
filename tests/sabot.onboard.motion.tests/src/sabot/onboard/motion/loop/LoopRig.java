package sabot.onboard.motion.loop;

import java.util.ArrayList;
import java.util.List;

import sabot.control.Controllers;
import sabot.control.DflGains;
import sabot.control.MotionLimits;
import sabot.control.TrackingController;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionStatus;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.map.GridGeometry;
import sabot.model.map.OccupancyGrid;
import sabot.model.robot.RobotDescription;
import sabot.model.robot.RobotDescriptions;

/**
 * The real {@link ControlLoop} on {@link FakeBoards} and a {@link ManualClock}, with the motion tasks' default settings
 * (odometry only: no inertial settling), on a 10 m × 10 m map (empty unless the test gives one), the robot at (2, 5)
 * facing +x: a test ticks it period by period.
 */
final class LoopRig implements LoopHost {

    static final RobotDescription ROBOT = RobotDescriptions.defaults();
    static final MotionLimits LIMITS = MotionLimits.of(ROBOT);
    static final double DEADMAN = 0.5;
    static final double PROGRESS_TIME = 8;
    static final double ROBOT_RADIUS = 0.25;
    static final LoopSettings SETTINGS = settingsAt(new Pose2D(2, 5, 0));

    final ManualClock clock = new ManualClock(1_000_000_000L);
    final FakeBoards boards = new FakeBoards(clock, ROBOT);
    final List<MissionStatus> missions = new ArrayList<>();
    final List<PlanRequest> planRequests = new ArrayList<>();
    final ControlLoop loop;
    private final long period = SETTINGS.periodNanos();

    LoopRig() {
        this(emptyMap());
    }

    /** @param map the static map the loop plans on and guards against (10 m × 10 m, 5 cm cells, origin at 0, 0) */
    LoopRig(OccupancyGrid map) {
        this(map, SETTINGS);
    }

    /** As {@link #LoopRig(OccupancyGrid)}, the robot starting at {@code start}. */
    LoopRig(OccupancyGrid map, Pose2D start) {
        this(map, settingsAt(start));
    }

    /** @return the rig's settings, the robot starting at {@code start} */
    static LoopSettings settingsAt(Pose2D start) {
        return new LoopSettings(50, 0, 3, 3, 0.05, 0.1, true, DEADMAN, ROBOT_RADIUS, 10, 0.95, 0.8, 0.1, PROGRESS_TIME,
                15, new LocalizerSettings(start, 0.02, 0.02, false, false, 0, 0.2, 0.02, 0.02, 0.5),
                LoopDefaults.guard());
    }

    private LoopRig(OccupancyGrid map, LoopSettings settings) {
        NavigationPlanner planner = new NavigationPlanner(map, "lpn", 1, ROBOT_RADIUS, 0.55);
        LoopControllers controllers = new LoopControllers() {
            @Override
            public TrackingController tracker(MotionLimits l) {
                return Controllers.dynamicFeedbackLinearization(DflGains.of(2.0, 0.9), l);
            }

            @Override
            public TrackingController stabilizer(MotionLimits l) {
                return Controllers.dflPointStabilization(DflGains.stabilizing(0.5), l);
            }
        };
        Localizer localizer = new Localizer(ROBOT, settings.localizer(), List.of());
        loop = new ControlLoop(this, clock, boards, ROBOT, localizer, planner, controllers, settings, LIMITS);
    }

    /** @return an empty map, 10 m × 10 m with 5 cm cells */
    static OccupancyGrid emptyMap() {
        return OccupancyGrid.of(new GridGeometry(200, 200, 0.05, Pose2D.ORIGIN), new byte[200 * 200]);
    }

    /** @return the empty map with a wall across it whose near face is at x = {@code x} m (two cells thick) */
    static OccupancyGrid wallAt(double x) {
        OccupancyGrid map = emptyMap();
        int column = (int) Math.round(x / 0.05);
        for (int row = 0; row < 200; row++) {
            map.set(column, row, OccupancyGrid.OCCUPIED);
            map.set(column + 1, row, OccupancyGrid.OCCUPIED);
        }
        return map;
    }

    /** Runs one period at the clock's time, then advances the clock by a period. */
    ControlLoop.Snapshot tick() {
        long now = clock.nanoTime();
        ControlLoop.Snapshot s = loop.tick(now, now);
        clock.advance(period);
        return s;
    }

    /**
     * Drives by joystick for {@code seconds}, the twist sent again every 0.1 s as a joystick does.
     *
     * @return the last period's snapshot
     */
    ControlLoop.Snapshot drive(double v, double w, double seconds) {
        ControlLoop.Snapshot s = null;
        for (double t = 0; t < seconds - 1e-9; t += 0.1) {
            joystick(v, w);
            s = run(0.1);
        }
        return s;
    }

    /** Ticks for {@code seconds}. @return the last period's snapshot */
    ControlLoop.Snapshot run(double seconds) {
        ControlLoop.Snapshot s = null;
        for (long n = Math.round(seconds * 1e9 / period); n > 0; n--) {
            s = tick();
        }
        return s;
    }

    /** A joystick twist received now. */
    void joystick(double v, double w) {
        loop.teleop(new Twist2D(v, w), clock.nanoTime(), clock.now());
    }

    /** A new goal, planned as the motion task plans it. */
    void navigateTo(double x, double y, double theta) {
        Goal g = new Goal(new Pose2D(x, y, theta), 0.05, 0.1);
        ControlLoop.Plan plan = loop.planPath(loop.snapshot().pose().pose(), g, List.of());
        loop.startMission(g, plan);
    }

    /** Answers the plan requests so far, as the planner's thread and the command queue do. */
    void answerPlanRequests() {
        List<PlanRequest> pending = new ArrayList<>(planRequests);
        planRequests.clear();
        for (PlanRequest r : pending) {
            loop.replanned(r, loop.planPath(r.from(), r.via(), r.goal(), r.obstacles()));
        }
    }

    @Override
    public void missionChanged(MissionStatus status) {
        missions.add(status);
    }

    @Override
    public void planRequested(PlanRequest request) {
        planRequests.add(request);
    }

    @Override
    public void applyPendingCommands() {
        // the tests give their commands between periods
    }
}
