package sabot.controlml;

import java.time.Instant;
import java.util.Collection;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

import sabot.controlml.payload.AccessRole;
import sabot.controlml.payload.BatteryPayload;
import sabot.controlml.payload.DirectoryListing;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileQuery;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.LimitsPayload;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PassageStatus;
import sabot.controlml.payload.PidGains;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TaskList;
import sabot.controlml.payload.TelemetryRates;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.VelocityCommand;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.BatteryState;

/**
 * The resources of the protocol (section 4 of {@code docs/CONTROLML.md}): constant, the same in every process. Each
 * resource's payload schema (field names, SWE component types, canonical UCUM units, ranges) is written once, in the
 * {@code CODEC} beside its value's record (e.g. {@link PoseEstimate#CODEC}). Every {@link ResourceRegistry} starts
 * with these; other bundles add their own resources to a connection's registry ({@link ControlMlManager#resources()}),
 * never to this list.
 */
public final class Resources {

    /** {@code cm.position} (get; set re-localises): pose estimate with covariance. */
    public static final Resource<PoseEstimate, NoQuery> POSITION = new Resource<PoseEstimate, NoQuery>(
            "cm.position", PoseEstimate.CODEC, null, true, true, "pose estimate (x, y, theta) with covariance")
                    .withRecordStructure(new PoseEstimate(Instant.EPOCH, new Pose2D(0, 0, 0), PoseCovariance.ZERO))
                    .setBy(Role.OPERATOR);
    /** {@code cm.velocity} (set: joystick twist; get: the twist being executed). */
    public static final Resource<VelocityCommand, NoQuery> VELOCITY = new Resource<VelocityCommand, NoQuery>(
            "cm.velocity", VelocityCommand.CODEC, null, true, true, "joystick twist (linear m/s, angular rad/s)")
                    .withRecordStructure(new VelocityCommand(Instant.EPOCH, Twist2D.ZERO)).movingTheRobot()
                    .setBy(Role.OPERATOR);
    /** {@code cm.goal} (get/set): the mission's target pose. */
    public static final Resource<Goal, NoQuery> GOAL = new Resource<Goal, NoQuery>("cm.goal", Goal.CODEC, null,
            true, true, "mission goal pose with tolerances").withRecordStructure(new Goal(new Pose2D(0, 0, 0), 1, 1))
                    .movingTheRobot().setBy(Role.OPERATOR);
    /** {@code cm.trajectory} (get/set): timed path. */
    public static final Resource<TrajectoryPayload, NoQuery> TRAJECTORY = new Resource<TrajectoryPayload, NoQuery>(
            "cm.trajectory", TrajectoryPayload.CODEC, null, true, true, "timed trajectory (t, x, y, theta, v, omega)")
                    .movingTheRobot().setBy(Role.OPERATOR);
    /** {@code cm.map} (get/set): occupancy grid. */
    public static final Resource<GridMap, NoQuery> MAP = new Resource<>("cm.map", GridMap.CODEC, null, true, true,
            "occupancy grid (at most 64 KiB of payload; larger maps via cm.fs)");
    /** {@code cm.obstacles} (get): detected obstacles. */
    public static final Resource<Obstacles, NoQuery> OBSTACLES = new Resource<>("cm.obstacles",
            Obstacles.CODEC, null, true, false, "detected obstacles as discs");
    /** {@code cm.battery} (get): the battery as the power board last measured it; telemetry too. */
    public static final Resource<BatteryState, NoQuery> BATTERY = new Resource<>("cm.battery", BatteryPayload.CODEC,
            null, true, false, "battery: state of charge, voltage, current, capacity, dock and charge flags");
    /**
     * {@code cm.passage} (get): the robot's claim on a narrow passage of its map (docs/PASSAGES.md); telemetry too,
     * which the other robots follow to take turns.
     */
    public static final Resource<PassageStatus, NoQuery> PASSAGE = new Resource<>("cm.passage", PassageStatus.CODEC,
            null, true, false, "claim on a narrow passage of the map: passage, state, since");
    /** {@code cm.pid} (get/set): PID gains per motor. */
    public static final Resource<PidGains, NoQuery> PID = new Resource<>("cm.pid", PidGains.CODEC, null, true, true,
            "speed-loop PID gains per motor");
    /** {@code cm.limits} (get/set): speed and acceleration limits. */
    public static final Resource<LimitsPayload, NoQuery> LIMITS = new Resource<LimitsPayload, NoQuery>("cm.limits",
            LimitsPayload.CODEC, null, true, true, "speed and acceleration limits").withRecordStructure(
                    new LimitsPayload(1, 1, 1, 1));
    /** {@code cm.mission} (get: state; set: pause/resume/abort/maintenance). */
    public static final Resource<MissionStatus, NoQuery> MISSION = new Resource<MissionStatus, NoQuery>("cm.mission",
            MissionStatus.CODEC, null, true, true, "mission state and maintenance mode").movingTheRobot()
                    .setBy(Role.OPERATOR); // a maintenance switch needs the maintainer: the device judges it
    /** {@code cm.tasks} (get): loaded tasks. */
    public static final Resource<TaskList, NoQuery> TASKS = new Resource<>("cm.tasks", TaskList.CODEC, null, true,
            false, "tasks loaded on the robot");
    /** {@code cm.role} (get): the requester's own role on the device; every device answers it. */
    public static final Resource<AccessRole, NoQuery> ROLE = new Resource<>("cm.role", AccessRole.CODEC, null, true,
            false, "the requester's role on this device");
    /**
     * {@code cm.telemetry} (get: the rate of each telemetry resource now; set: a watcher's lease of faster rates,
     * section 6). Observers may set it: a lease asks for telemetry and changes nothing on the robot.
     */
    public static final Resource<TelemetryRates, NoQuery> TELEMETRY = new Resource<TelemetryRates, NoQuery>(
            "cm.telemetry", TelemetryRates.CODEC, null, true, true, "telemetry rates; a set leases faster ones for a "
                    + "while").setByObservers();
    /** {@code cm.fs.list} (get with a path): directory listing. */
    public static final Resource<DirectoryListing, FileQuery> FS_LIST = new Resource<>("cm.fs.list",
            DirectoryListing.CODEC, FileQuery.CODEC, true, false, "remote FS: list a directory");
    /** {@code cm.fs.read} (get with path, offset, length): a chunk of a file. */
    public static final Resource<FileChunk, FileQuery> FS_READ = new Resource<>("cm.fs.read", FileChunk.CODEC,
            FileQuery.CODEC, true, false, "remote FS: read a chunk");
    /** {@code cm.fs.write} (set): write a chunk. */
    public static final Resource<FileChunk, NoQuery> FS_WRITE = new Resource<>("cm.fs.write", FileChunk.CODEC, null,
            false, true, "remote FS: write a chunk");
    /** {@code cm.fs.delete} (set with a path): delete a file. */
    public static final Resource<FileQuery, NoQuery> FS_DELETE = new Resource<>("cm.fs.delete",
            FileQuery.CODEC, null, false, true, "remote FS: delete a file");

    private static final Map<String, Resource<?, ?>> BY_NAME = new LinkedHashMap<>();

    static {
        for (Resource<?, ?> r : List.of(POSITION, VELOCITY, GOAL, TRAJECTORY, MAP, OBSTACLES, BATTERY, PASSAGE, PID, LIMITS,
                MISSION,
                TASKS, ROLE, TELEMETRY, FS_LIST, FS_READ, FS_WRITE, FS_DELETE)) {
            BY_NAME.put(r.name(), r);
        }
    }

    private Resources() {
    }

    /**
     * @return the section 4 resource of a {@code res} value, or null when it is none of them (a connection's own
     *         resources are in its {@link ControlMlManager#resources() registry})
     */
    public static Resource<?, ?> byName(String name) {
        return BY_NAME.get(name);
    }

    /** @return section 4's resources, in its order */
    public static Collection<Resource<?, ?>> all() {
        return BY_NAME.values();
    }
}
