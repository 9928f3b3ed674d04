package sabot.motion.sim;

import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

import sabot.control.DifferentialDrive;
import sabot.control.MotionLimits;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.map.GridGeometry;
import sabot.model.map.OccupancyGrid;
import sabot.model.robot.RobotDescription;
import sabot.onboard.motion.loop.ControlLoop;
import sabot.onboard.motion.loop.LocalizerSettings;
import sabot.onboard.motion.loop.Localizer;
import sabot.onboard.motion.loop.LoopDefaults;
import sabot.onboard.motion.loop.LoopHost;
import sabot.onboard.motion.loop.LoopSettings;
import sabot.onboard.motion.loop.ManualClock;
import sabot.onboard.motion.loop.NavigationPlanner;

/**
 * The robot's own control loop ({@link ControlLoop}: the one the {@code motion} task runs, with its planner, trajectory
 * fit, turn in place, DFL tracker, point stabilizer, velocity smoother and EKF localizer) closed over the simulated
 * robot: its boards are {@link SimulatedBoards}, its clock advances one period per tick, and it is given a goal as the
 * robot gets one over ControlML. What this run measures is what the robot does; {@link Simulation} studies the control
 * laws and the estimators one by one on a given trajectory.
 */
public final class OnboardLoop {

    /** Half the side of the empty map the planner plans on, centred on the start, m. */
    static final double MAP_HALF_SIDE = 10;
    /** Cell size of that map, m. */
    static final double MAP_RESOLUTION = 0.05;

    /** The reference mission's start: the origin, facing away from the goal (so the robot first turns in place). */
    public static final Pose2D REFERENCE_START = new Pose2D(0, 0, Math.PI);
    /** The reference mission's goal: 3.6 m away, heading across the way there, 5 cm and 0.1 rad of tolerance. */
    public static final Goal REFERENCE_GOAL = new Goal(new Pose2D(3, 2, Math.PI / 2), 0.05, 0.1);
    /** The reference mission's slip: 1 % noise per wheel and period, 0.2 % left/right asymmetry. */
    public static final double REFERENCE_SLIP_NOISE = 0.01;
    public static final double REFERENCE_SLIP_BIAS = 0.002;
    /** s the reference mission may take before the run gives up on it. */
    public static final double REFERENCE_TIMEOUT = 60;

    private OnboardLoop() {
    }

    /** @return the reference mission (the figures docs/MOTION.md gives for the robot's loop) on the default robot */
    public static Run referenceMission(RobotDescription robot, long seed) {
        return toGoal(robot, REFERENCE_START, REFERENCE_GOAL, REFERENCE_SLIP_NOISE, REFERENCE_SLIP_BIAS, seed,
                REFERENCE_TIMEOUT);
    }

    /**
     * The settings of the robot as shipped ({@link LoopDefaults}: the defaults of the motion, localizer, planner,
     * tracker and teleop tasks), the localizer at {@code start} without landmarks; no status log lines.
     */
    public static LoopSettings settings(Pose2D start) {
        return LoopDefaults.settings(start).withStatusPeriod(0);
    }

    /**
     * One mission on the simulated robot.
     *
     * @param goal            the mission's goal
     * @param mission         the mission's status when the run ended
     * @param truth           where the robot stands at the end
     * @param estimate        where the loop believes it stands at the end
     * @param duration        s from the mission's start to its end (or to the timeout)
     * @param limitViolations periods whose wheel set-points broke a speed, wheel-speed or acceleration limit
     * @param nanCommands     periods whose wheel set-points were not finite
     * @param maxYawRate      largest |ω| written, rad/s
     * @param trace           one row per period, the goal as the reference; t from the mission's start
     */
    public record Run(Goal goal, MissionStatus mission, Pose2D truth, Pose2D estimate, double duration,
            int limitViolations, int nanCommands, double maxYawRate, Trace trace) {

        /** @return distance between the true end and the goal, m */
        public double finalError() {
            return Math.hypot(truth.x() - goal.pose().x(), truth.y() - goal.pose().y());
        }

        /** @return |true end heading &minus; goal heading|, rad */
        public double finalHeadingError() {
            return Math.abs(Pose2D.normalizeAngle(truth.theta() - goal.pose().theta()));
        }

        /** @return distance between the estimate and the truth at the end, m */
        public double estimateError() {
            return Math.hypot(truth.x() - estimate.x(), truth.y() - estimate.y());
        }

        /** @return one JSON object, keys as documented in docs/MOTION.md */
        public String toJson(long seed, double slipNoise, double slipBias) {
            return String.format(Locale.ROOT,
                    "{\"scenario\":\"goal\",\"loop\":\"onboard\",\"seed\":%d,\"slip_noise\":%s,\"slip_bias\":%s,"
                            + "\"mission\":\"%s\",\"time_s\":%s,\"final_m\":%s,\"final_heading_rad\":%s,"
                            + "\"estimate_error_m\":%s,\"limit_violations\":%d,\"nan_commands\":%d,"
                            + "\"max_yaw_rate_radps\":%s}",
                    seed, num(slipNoise), num(slipBias), mission.state().name().toLowerCase(Locale.ROOT), num(duration),
                    num(finalError()), num(finalHeadingError()), num(estimateError()), limitViolations, nanCommands,
                    num(maxYawRate));
        }

        private static String num(double v) {
            return Double.isFinite(v) ? String.format(Locale.ROOT, "%.6g", v) : "null";
        }
    }

    /**
     * Boots the loop with the robot standing at {@code start} (it stays still while the inertial biases are learnt),
     * then gives it {@code goal}, planned from the loop's estimate as the motion task plans a goal, and ticks it until
     * the mission is done or failed, or {@code timeout} s have passed since it started.
     *
     * @param slipNoise standard deviation of each wheel's travel per period (see {@link SimulatedRobot})
     * @param slipBias  left/right travel asymmetry
     * @param seed      seed of the slip and of the inertial sensors
     */
    public static Run toGoal(RobotDescription robot, Pose2D start, Goal goal, double slipNoise, double slipBias,
            long seed, double timeout) {
        LoopSettings settings = settings(start);
        MotionLimits limits = MotionLimits.of(robot);
        DifferentialDrive drive = DifferentialDrive.of(robot);
        SimulatedBoards boards = new SimulatedBoards(new SimulatedRobot(robot, start, slipNoise, slipBias, seed * 31 + 1),
                new SimulatedImu(MemsFigures.bmi088(), seed * 31 + 2));
        SimulatedRobot truth = boards.truth();
        ManualClock clock = new ManualClock(0);
        Host host = new Host();
        int cells = (int) Math.round(2 * MAP_HALF_SIDE / MAP_RESOLUTION);
        NavigationPlanner planner = new NavigationPlanner(OccupancyGrid.of(new GridGeometry(cells, cells,
                MAP_RESOLUTION, new Pose2D(start.x() - MAP_HALF_SIDE, start.y() - MAP_HALF_SIDE, 0)),
                new byte[cells * cells]), LoopDefaults.PLANNER_ALGORITHM, LoopDefaults.PLANNER_THREADS,
                LoopDefaults.ROBOT_RADIUS, LoopDefaults.INFLATION_RADIUS);
        Localizer localizer = new Localizer(robot, settings.localizer(), List.of());
        ControlLoop loop = new ControlLoop(host, clock, boards, robot, localizer, planner, LoopDefaults.controllers(),
                settings, limits);
        host.loop = loop;
        long period = settings.periodNanos();
        double dt = period * 1e-9;
        Trace trace = new Trace();
        Twist2D previous = Twist2D.ZERO;
        int violations = 0;
        int nans = 0;
        double maxYaw = 0;
        long settlePeriods = Math.round(settings.localizer().imuSettleTime() / dt);
        long lastPeriod = settlePeriods + Math.round(timeout / dt);
        ControlLoop.Snapshot s = null;
        long k = 0;
        for (; k <= lastPeriod; k++) {
            double t = (k - settlePeriods) * dt;
            if (k == settlePeriods) {
                loop.startMission(goal, loop.planPath(loop.snapshot().pose().pose(), goal, List.of()));
            }
            long now = clock.nanoTime();
            s = loop.tick(now, now);
            host.answerPlanRequests();
            Twist2D written = drive.toTwist(boards.setPoints());
            if (!written.isFinite()) {
                nans++;
            } else {
                if (Simulation.violates(written, previous, limits, k == 0 ? Double.NaN : dt)) {
                    violations++;
                }
                maxYaw = Math.max(maxYaw, Math.abs(written.angular()));
                previous = written;
            }
            Pose2D p = truth.pose();
            Pose2D e = s.pose().pose();
            Pose2D g = goal.pose();
            trace.add(s.mode().name(), 0, t, g.x(), g.y(), g.theta(), p.x(), p.y(), p.theta(), e.x(), e.y(),
                    e.theta(), written.linear(), written.angular(), Math.hypot(p.x() - g.x(), p.y() - g.y()),
                    Math.hypot(p.x() - e.x(), p.y() - e.y()));
            MissionState state = s.mission().state();
            if (k >= settlePeriods && (state == MissionState.DONE || state == MissionState.FAILED)) {
                break;
            }
            boards.drive(dt);
            clock.advance(period);
        }
        return new Run(goal, s.mission(), truth.pose(), s.pose().pose(), (Math.min(k, lastPeriod) - settlePeriods) * dt,
                violations, nans, maxYaw, trace);
    }

    /**
     * What the motion task does for the loop, done between two periods: plan requests are answered before the next
     * period (the robot's planner thread answers within a few periods), and no other thread queues commands.
     */
    private static final class Host implements LoopHost {

        private ControlLoop loop;
        private final List<PlanRequest> pending = new ArrayList<>();

        void answerPlanRequests() {
            List<PlanRequest> requests = new ArrayList<>(pending);
            pending.clear();
            for (PlanRequest r : requests) {
                loop.replanned(r, loop.planPath(r.from(), r.goal(), r.obstacles()));
            }
        }

        @Override
        public void missionChanged(MissionStatus status) {
            // the run reads the mission from the loop's snapshot
        }

        @Override
        public void planRequested(PlanRequest request) {
            pending.add(request);
        }

        @Override
        public void applyPendingCommands() {
            // no joystick in the simulation
        }
    }
}
