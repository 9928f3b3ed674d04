package sabot.controlml.tests;

import java.time.Instant;
import java.util.List;
import java.util.Map;
import java.util.Optional;

import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.AccessRole;
import sabot.controlml.payload.DirectoryListing;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileEntry;
import sabot.controlml.payload.FileQuery;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.LimitsPayload;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.Obstacle;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PassageStatus;
import sabot.controlml.payload.PidGains;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TaskInfo;
import sabot.controlml.payload.TaskList;
import sabot.controlml.payload.TelemetryRates;
import sabot.controlml.payload.TelemetryRates.StreamRate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.controlml.payload.VelocityCommand;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.BatteryState;
import sabot.model.robot.PassageClaim;

/** One realistic value per resource, for round trips. */
final class Samples {

    static final Instant T = Instant.parse("2026-11-21T10:15:30.123456Z");

    static final PoseEstimate POSE = new PoseEstimate(T, new Pose2D(1.25, -3.5, 0.7853981633974483),
            new PoseCovariance(0.01, 0.001, -0.0002, 0.02, 0.0003, 0.0004));

    static final byte[] DATA = "hello remote fs\n".getBytes(java.nio.charset.StandardCharsets.UTF_8);

    static final Map<Resource<?, ?>, Object> VALUES = Map.ofEntries(
            Map.entry(Resources.POSITION, POSE),
            Map.entry(Resources.VELOCITY, new VelocityCommand(T, new Twist2D(0.3, -0.5))),
            Map.entry(Resources.GOAL, new Goal(new Pose2D(4, 2.5, Math.PI / 2), 0.05, 0.1)),
            Map.entry(Resources.TRAJECTORY, new TrajectoryPayload(T, List.of(new TrajectoryPoint(0, 0, 0, 0, 0, 0),
                    new TrajectoryPoint(0.5, 0.1, 0.01, 0.05, 0.2, 0.1), new TrajectoryPoint(1.0, 0.2, 0.03, 0.1, 0.2,
                            0.0)))),
            Map.entry(Resources.MAP, new GridMap(0.05, 3, 2, new Pose2D(-1, -2, 0), new byte[] { 0, 100, -1, 50, 0,
                    0 })),
            Map.entry(Resources.OBSTACLES, new Obstacles(T, List.of(new Obstacle(1, 1, 0.2), new Obstacle(-2, 0.5,
                    0.35)))),
            Map.entry(Resources.BATTERY, new BatteryState(T, 0.25, 25.125, -4.5, 10, true, true, false)),
            Map.entry(Resources.PASSAGE, new PassageStatus(T, Optional.of(new PassageClaim(2,
                    PassageClaim.State.WAITING, T.minusMillis(1500))))),
            Map.entry(Resources.PID, new PidGains(List.of(new MotorGains(0, 1.2, 0.05, 0.01), new MotorGains(1, 1.1,
                    0.04, 0.0)))),
            Map.entry(Resources.LIMITS, new LimitsPayload(0.5, 2.0, 0.5, 3.0)),
            Map.entry(Resources.MISSION, new MissionStatus(MissionState.RUNNING, false, 42.5, "to dock <B> & back",
                    List.of(new MissionTarget(new Goal(new Pose2D(1, 2, 0), 0.1, 0.2), MissionTarget.Action.WAIT, 5,
                            MissionTarget.State.REACHED), new MissionTarget(new Goal(new Pose2D(0, 0, 3.1), 0.05,
                                    0.1), MissionTarget.Action.DOCK, 0, MissionTarget.State.ACTIVE)), 1, 1)),
            Map.entry(Resources.TASKS, new TaskList(List.of(new TaskInfo("localizer", "sabot.onboard.motion",
                    "0.1.0", "active"), new TaskInfo("remotefs", "sabot.onboard.remotefs", "0.1.0", "resolved")))),
            Map.entry(Resources.ROLE, new AccessRole(Role.OPERATOR)),
            Map.entry(Resources.TELEMETRY, new TelemetryRates(30, List.of(new StreamRate("cm.position", 10),
                    new StreamRate("cm.mission", 0.5)))),
            Map.entry(Resources.FS_LIST, new DirectoryListing("maps", List.of(new FileEntry("lab.pgm", 10240, false),
                    new FileEntry("old", 0, true)))),
            Map.entry(Resources.FS_READ, new FileChunk("maps/lab.yaml", 0, DATA, FileChunk.sha256Hex(DATA), true)),
            Map.entry(Resources.FS_WRITE, new FileChunk("logs/run.txt", 16, DATA, FileChunk.sha256Hex(DATA), false)),
            Map.entry(Resources.FS_DELETE, new FileQuery("logs/run.txt", 0, 0)));

    static final FileQuery QUERY = new FileQuery("maps/lab.yaml", 0, 4096);

    private Samples() {
    }
}
