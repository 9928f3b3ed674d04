package sabot.controlml;

import java.time.Instant;
import java.util.Base64;
import java.util.ArrayList;
import java.util.Collection;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.regex.Pattern;

import sabot.controlml.payload.DirectoryListing;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileEntry;
import sabot.controlml.payload.FileQuery;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MotionLimits;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.Obstacle;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.payload.PidGains;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.RecordBuilder;
import sabot.controlml.payload.RecordReader;
import sabot.controlml.payload.TaskInfo;
import sabot.controlml.payload.TaskList;
import sabot.controlml.payload.Trajectory;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.controlml.payload.VelocityCommand;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.DataRecord;
import sabot.controlml.swe.SweComponent;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;

/**
 * The resources of the protocol (section 4 of {@code docs/CONTROLML.md}): constant, the same in every process. Each
 * resource's payload schema (field names, SWE component types, canonical UCUM units, ranges) is written once, in its
 * codec. Every {@link ResourceRegistry} starts with these; other bundles add their own resources to a connection's
 * registry ({@link ControlMlManager#resources()}), never to this list.
 */
public final class Resources {

    private static final double ANY = Double.POSITIVE_INFINITY;
    private static final double TINY = Double.MIN_VALUE;

    /** {@code cm.position} (get; set re-localises): pose estimate with covariance. */
    public static final Resource<PoseEstimate, NoQuery> POSITION = new Resource<PoseEstimate, NoQuery>(
            "cm.position", new PositionCodec(), null, true, true, "pose estimate (x, y, theta) with covariance")
                    .withRecordStructure(new PoseEstimate(Instant.EPOCH, new Pose2D(0, 0, 0), PoseCovariance.ZERO));
    /** {@code cm.velocity} (set: joystick twist; get: the twist being executed). */
    public static final Resource<VelocityCommand, NoQuery> VELOCITY = new Resource<VelocityCommand, NoQuery>(
            "cm.velocity", new VelocityCodec(), null, true, true, "joystick twist (linear m/s, angular rad/s)")
                    .withRecordStructure(new VelocityCommand(Instant.EPOCH, Twist2D.ZERO));
    /** {@code cm.goal} (get/set): the mission's target pose. */
    public static final Resource<Goal, NoQuery> GOAL = new Resource<Goal, NoQuery>("cm.goal", new GoalCodec(), null,
            true, true, "mission goal pose with tolerances").withRecordStructure(new Goal(new Pose2D(0, 0, 0), 1, 1));
    /** {@code cm.trajectory} (get/set): timed path. */
    public static final Resource<Trajectory, NoQuery> TRAJECTORY = new Resource<>("cm.trajectory",
            new TrajectoryCodec(), null, true, true, "timed trajectory (t, x, y, theta, v, omega)");
    /** {@code cm.map} (get/set): occupancy grid. */
    public static final Resource<GridMap, NoQuery> MAP = new Resource<>("cm.map", new MapCodec(), null, true, true,
            "occupancy grid (at most 64 KiB of payload; larger maps via cm.fs)");
    /** {@code cm.obstacles} (get): detected obstacles. */
    public static final Resource<Obstacles, NoQuery> OBSTACLES = new Resource<>("cm.obstacles",
            new ObstaclesCodec(), null, true, false, "detected obstacles as discs");
    /** {@code cm.pid} (get/set): PID gains per motor. */
    public static final Resource<PidGains, NoQuery> PID = new Resource<>("cm.pid", new PidCodec(), null, true, true,
            "speed-loop PID gains per motor");
    /** {@code cm.limits} (get/set): speed and acceleration limits. */
    public static final Resource<MotionLimits, NoQuery> LIMITS = new Resource<MotionLimits, NoQuery>("cm.limits",
            new LimitsCodec(), null, true, true, "speed and acceleration limits").withRecordStructure(
                    new MotionLimits(1, 1, 1, 1));
    /** {@code cm.mission} (get: state; set: pause/resume/abort/maintenance). */
    public static final Resource<MissionStatus, NoQuery> MISSION = new Resource<>("cm.mission", new MissionCodec(),
            null, true, true, "mission state and maintenance mode");
    /** {@code cm.tasks} (get): loaded tasks. */
    public static final Resource<TaskList, NoQuery> TASKS = new Resource<>("cm.tasks", new TasksCodec(), null, true,
            false, "tasks loaded on the robot");
    /** {@code cm.fs.list} (get with a path): directory listing. */
    public static final Resource<DirectoryListing, FileQuery> FS_LIST = new Resource<>("cm.fs.list",
            new ListingCodec(), new FileQueryCodec(), true, false, "remote FS: list a directory");
    /** {@code cm.fs.read} (get with path, offset, length): a chunk of a file. */
    public static final Resource<FileChunk, FileQuery> FS_READ = new Resource<>("cm.fs.read", new ChunkCodec(),
            new FileQueryCodec(), true, false, "remote FS: read a chunk");
    /** {@code cm.fs.write} (set): write a chunk. */
    public static final Resource<FileChunk, NoQuery> FS_WRITE = new Resource<>("cm.fs.write", new ChunkCodec(), null,
            false, true, "remote FS: write a chunk");
    /** {@code cm.fs.delete} (set with a path): delete a file. */
    public static final Resource<FileQuery, NoQuery> FS_DELETE = new Resource<>("cm.fs.delete",
            new FileQueryCodec(), null, false, true, "remote FS: delete a file");

    private static final Map<String, Resource<?, ?>> BY_NAME = new LinkedHashMap<>();

    static {
        for (Resource<?, ?> r : List.of(POSITION, VELOCITY, GOAL, TRAJECTORY, MAP, OBSTACLES, PID, LIMITS, MISSION,
                TASKS, FS_LIST, FS_READ, FS_WRITE, FS_DELETE)) {
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

    // ------------------------------------------------------------------------------------------------ codecs

    /**
     * cm.position's covariance: the upper triangle of the 3x3 (x, y, theta) matrix as one row of a SWE
     * {@code DataArray} in the text encoding (one {@code <values>} block instead of six {@code Quantity}s).
     */
    static final List<DataArray.Column> COVARIANCE_COLUMNS = List.of(DataArray.Column.quantity("xx", "m2"),
            DataArray.Column.quantity("xy", "m2"), DataArray.Column.quantity("xtheta", "m.rad"), DataArray.Column
                    .quantity("yy", "m2"), DataArray.Column.quantity("ytheta", "m.rad"), DataArray.Column.quantity(
                            "thetatheta", "rad2"));

    private static final class PositionCodec implements PayloadCodec<PoseEstimate> {
        @Override
        public SweComponent encode(PoseEstimate p) {
            PoseCovariance c = p.covariance();
            return new RecordBuilder().time("time", p.time()).quantity("x", "m", p.pose().x()).quantity("y", "m", p
                    .pose().y()).quantity("theta", "rad", p.pose().theta()).add("covariance", new DataArray(
                            "covariance", COVARIANCE_COLUMNS, List.<double[]>of(new double[] { c.xx(), c.xy(), c
                                    .xTheta(), c.yy(), c.yTheta(), c.thetaTheta() }))).build();
        }

        @Override
        public PoseEstimate decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "time", "x", "y", "theta", "covariance");
            List<double[]> rows = r.array("covariance", COVARIANCE_COLUMNS, Integer.MAX_VALUE);
            if (rows.size() != 1) {
                throw new PayloadException(ControlMlCondition.MALFORMED_PAYLOAD, "covariance must have exactly 1 row"
                        + " (the upper triangle xx,xy,xtheta,yy,ytheta,thetatheta), not " + rows.size());
            }
            double[] c = rows.get(0);
            for (int i : new int[] { 0, 3, 5 }) {
                if (c[i] < 0) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "covariance."
                            + COVARIANCE_COLUMNS.get(i).name() + " is a variance and must be >= 0, not " + c[i]);
                }
            }
            return new PoseEstimate(r.time("time"), new Pose2D(r.quantity("x", "m"), r.quantity("y", "m"), r.quantity(
                    "theta", "rad")), new PoseCovariance(c[0], c[1], c[2], c[3], c[4], c[5]));
        }
    }

    private static final class VelocityCodec implements PayloadCodec<VelocityCommand> {
        @Override
        public SweComponent encode(VelocityCommand v) {
            return new RecordBuilder().time("time", v.time()).quantity("linear", "m/s", v.twist().linear()).quantity(
                    "angular", "rad/s", v.twist().angular()).build();
        }

        @Override
        public VelocityCommand decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "time", "linear", "angular");
            // sanity bounds of the protocol; the robot's own limits (cm.limits) clamp further
            return new VelocityCommand(r.time("time"), new Twist2D(r.quantity("linear", "m/s", -10, 10), r.quantity(
                    "angular", "rad/s", -20, 20)));
        }
    }

    private static final class GoalCodec implements PayloadCodec<Goal> {
        @Override
        public SweComponent encode(Goal g) {
            return new RecordBuilder().quantity("x", "m", g.pose().x()).quantity("y", "m", g.pose().y()).quantity(
                    "theta", "rad", g.pose().theta()).quantity("positionTolerance", "m", g.positionTolerance())
                    .quantity("headingTolerance", "rad", g.headingTolerance()).build();
        }

        @Override
        public Goal decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "x", "y", "theta", "positionTolerance", "headingTolerance");
            return new Goal(new Pose2D(r.quantity("x", "m"), r.quantity("y", "m"), r.quantity("theta", "rad")), r
                    .quantity("positionTolerance", "m", TINY, ANY), r.quantity("headingTolerance", "rad", TINY,
                            2 * Math.PI));
        }
    }

    private static final List<DataArray.Column> TRAJECTORY_COLUMNS = List.of(DataArray.Column.quantity("t", "s"),
            DataArray.Column.quantity("x", "m"), DataArray.Column.quantity("y", "m"), DataArray.Column.quantity(
                    "theta", "rad"), DataArray.Column.quantity("v", "m/s"), DataArray.Column.quantity("omega",
                            "rad/s"));

    private static final class TrajectoryCodec implements PayloadCodec<Trajectory> {
        @Override
        public SweComponent encode(Trajectory t) {
            List<double[]> rows = new ArrayList<>(t.points().size());
            for (TrajectoryPoint p : t.points()) {
                rows.add(new double[] { p.t(), p.x(), p.y(), p.theta(), p.v(), p.omega() });
            }
            return new RecordBuilder().time("start", t.start()).add("points", new DataArray("point",
                    TRAJECTORY_COLUMNS, rows)).build();
        }

        @Override
        public Trajectory decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "start", "points");
            List<double[]> rows = r.array("points", TRAJECTORY_COLUMNS, 4096);
            List<TrajectoryPoint> points = new ArrayList<>(rows.size());
            double previous = 0;
            for (double[] row : rows) {
                if (row[0] < previous) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE,
                            "trajectory times must start at >= 0 s and not decrease");
                }
                previous = row[0];
                points.add(new TrajectoryPoint(row[0], row[1], row[2], row[3], row[4], row[5]));
            }
            return new Trajectory(r.time("start"), points);
        }
    }

    private static final List<DataArray.Column> CELL_COLUMNS = List.of(DataArray.Column.count("occupancy"));

    private static final class MapCodec implements PayloadCodec<GridMap> {
        @Override
        public SweComponent encode(GridMap m) {
            byte[] cells = m.cells();
            List<double[]> rows = new ArrayList<>(cells.length);
            for (byte c : cells) {
                rows.add(new double[] { c });
            }
            return new RecordBuilder().quantity("resolution", "m", m.resolution()).count("width", m.width()).count(
                    "height", m.height()).add("origin", new RecordBuilder().quantity("x", "m", m.origin().x())
                            .quantity("y", "m", m.origin().y()).quantity("theta", "rad", m.origin().theta()).build())
                    .add("cells", new DataArray("cell", CELL_COLUMNS, rows)).build();
        }

        @Override
        public GridMap decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "resolution", "width", "height", "origin", "cells");
            RecordReader o = r.record("origin", "x", "y", "theta");
            int width = (int) r.count("width", 1, 4096);
            int height = (int) r.count("height", 1, 4096);
            List<double[]> rows = r.array("cells", CELL_COLUMNS, 1 << 16);
            if (rows.size() != width * height) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, "map of " + width + "x" + height
                        + " needs " + width * height + " cells, has " + rows.size());
            }
            byte[] cells = new byte[rows.size()];
            for (int i = 0; i < cells.length; i++) {
                double v = rows.get(i)[0];
                if (v < -1 || v > 100) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "cell " + i + " = " + v
                            + " is not an occupancy (-1 unknown, 0..100)");
                }
                cells[i] = (byte) v;
            }
            return new GridMap(r.quantity("resolution", "m", TINY, ANY), width, height, new Pose2D(o.quantity("x",
                    "m"), o.quantity("y", "m"), o.quantity("theta", "rad")), cells);
        }
    }

    private static final List<DataArray.Column> OBSTACLE_COLUMNS = List.of(DataArray.Column.quantity("x", "m"),
            DataArray.Column.quantity("y", "m"), DataArray.Column.quantity("radius", "m"));

    private static final class ObstaclesCodec implements PayloadCodec<Obstacles> {
        @Override
        public SweComponent encode(Obstacles o) {
            List<double[]> rows = new ArrayList<>();
            for (Obstacle ob : o.obstacles()) {
                rows.add(new double[] { ob.x(), ob.y(), ob.radius() });
            }
            return new RecordBuilder().time("time", o.time()).add("obstacles", new DataArray("obstacle",
                    OBSTACLE_COLUMNS, rows)).build();
        }

        @Override
        public Obstacles decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "time", "obstacles");
            List<Obstacle> list = new ArrayList<>();
            for (double[] row : r.array("obstacles", OBSTACLE_COLUMNS, 1024)) {
                if (row[2] < 0) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "negative obstacle radius");
                }
                list.add(new Obstacle(row[0], row[1], row[2]));
            }
            return new Obstacles(r.time("time"), list);
        }
    }

    private static final List<DataArray.Column> GAIN_COLUMNS = List.of(DataArray.Column.count("motor"), DataArray
            .Column.quantity("kp", "1"), DataArray.Column.quantity("ki", "1"), DataArray.Column.quantity("kd", "1"));

    private static final class PidCodec implements PayloadCodec<PidGains> {
        @Override
        public SweComponent encode(PidGains g) {
            List<double[]> rows = new ArrayList<>();
            for (MotorGains m : g.motors()) {
                rows.add(new double[] { m.motor(), m.kp(), m.ki(), m.kd() });
            }
            return new RecordBuilder().add("gains", new DataArray("motor", GAIN_COLUMNS, rows)).build();
        }

        @Override
        public PidGains decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "gains");
            List<MotorGains> motors = new ArrayList<>();
            long seen = 0;
            for (double[] row : r.array("gains", GAIN_COLUMNS, 16)) {
                int motor = (int) row[0];
                if (row[0] < 0 || row[0] > 15 || (seen & (1L << motor)) != 0) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "motor indexes must be unique, 0..15");
                }
                seen |= 1L << motor;
                if (row[1] < 0 || row[2] < 0 || row[3] < 0) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "PID gains must be >= 0");
                }
                motors.add(new MotorGains(motor, row[1], row[2], row[3]));
            }
            if (motors.isEmpty()) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, "gains of at least one motor");
            }
            return new PidGains(motors);
        }
    }

    private static final class LimitsCodec implements PayloadCodec<MotionLimits> {
        @Override
        public SweComponent encode(MotionLimits l) {
            return new RecordBuilder().quantity("maxLinearSpeed", "m/s", l.maxLinearSpeed()).quantity(
                    "maxAngularSpeed", "rad/s", l.maxAngularSpeed()).quantity("maxLinearAcceleration", "m/s2", l
                            .maxLinearAcceleration()).quantity("maxAngularAcceleration", "rad/s2", l
                                    .maxAngularAcceleration()).build();
        }

        @Override
        public MotionLimits decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "maxLinearSpeed", "maxAngularSpeed", "maxLinearAcceleration",
                    "maxAngularAcceleration");
            return new MotionLimits(r.quantity("maxLinearSpeed", "m/s", TINY, 10), r.quantity("maxAngularSpeed",
                    "rad/s", TINY, 20), r.quantity("maxLinearAcceleration", "m/s2", TINY, 50), r.quantity(
                            "maxAngularAcceleration", "rad/s2", TINY, 100));
        }
    }

    private static final Set<String> MISSION_CODES;

    static {
        Set<String> codes = new java.util.HashSet<>();
        for (MissionState s : MissionState.values()) {
            codes.add(s.code());
        }
        MISSION_CODES = Set.copyOf(codes);
    }

    private static final class MissionCodec implements PayloadCodec<MissionStatus> {
        @Override
        public SweComponent encode(MissionStatus m) {
            return new RecordBuilder().category("state", m.state().code()).bool("maintenance", m.maintenance())
                    .quantity("progress", "%", m.progress()).text("detail", m.detail()).build();
        }

        @Override
        public MissionStatus decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "state", "maintenance", "progress", "detail");
            return new MissionStatus(MissionState.fromCode(r.category("state", MISSION_CODES)), r.bool("maintenance"),
                    r.quantity("progress", "%", 0, 100), r.text("detail", 256));
        }
    }

    private static final Set<String> TASK_STATES = Set.of("installed", "resolved", "active", "starting", "stopping");

    private static final class TasksCodec implements PayloadCodec<TaskList> {
        @Override
        public SweComponent encode(TaskList t) {
            RecordBuilder b = new RecordBuilder().count("count", t.tasks().size());
            int i = 0;
            for (TaskInfo task : t.tasks()) {
                b.add("task" + i++, new RecordBuilder().text("name", task.name()).text("version", task.version())
                        .category("state", task.state()).build());
            }
            return b.build();
        }

        @Override
        public TaskList decode(SweComponent payload) throws PayloadException {
            String[] names = indexedFields(payload, "task", 256);
            RecordReader r = RecordReader.of(payload, names);
            List<TaskInfo> tasks = new ArrayList<>();
            for (int i = 1; i < names.length; i++) {
                RecordReader t = r.record(names[i], "name", "version", "state");
                tasks.add(new TaskInfo(t.text("name", 128), t.text("version", 64), t.category("state", TASK_STATES)));
            }
            return new TaskList(tasks);
        }
    }

    /** Field names {@code count, <prefix>0 .. <prefix>n-1} of a record whose {@code count} field says n. */
    private static String[] indexedFields(SweComponent payload, String prefix, int max) throws PayloadException {
        long n = 0;
        if (payload instanceof DataRecord r && r.get("count") instanceof sabot.controlml.swe.Count c) {
            n = c.value();
        }
        if (n < 0 || n > max) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, "count must be 0.." + max);
        }
        String[] names = new String[(int) n + 1];
        names[0] = "count";
        for (int i = 0; i < n; i++) {
            names[i + 1] = prefix + i;
        }
        return names;
    }

    // Relative, '/'-separated, no '..', no empty segments except the root "".
    private static final Pattern PATH = Pattern.compile("|[A-Za-z0-9_.+-]+(/[A-Za-z0-9_.+-]+)*");

    static String path(RecordReader r) throws PayloadException {
        String p = r.text("path", 512);
        if (!PATH.matcher(p).matches() || p.equals("..") || p.startsWith("../") || p.contains("/../") || p.endsWith(
                "/..")) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, "path '" + p
                    + "' must be relative, '/'-separated, without '..'");
        }
        return p;
    }

    private static final class FileQueryCodec implements PayloadCodec<FileQuery> {
        @Override
        public SweComponent encode(FileQuery q) {
            return new RecordBuilder().text("path", q.path()).count("offset", q.offset()).count("length", q.length())
                    .build();
        }

        @Override
        public FileQuery decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "path", "offset", "length");
            return new FileQuery(path(r), r.count("offset", 0, Long.MAX_VALUE), r.count("length", 0,
                    FileChunkLimits.MAX_CHUNK));
        }
    }

    /** Chunk size limit: 32 KiB of data is 43,692 characters of base64, well inside one payload. */
    public static final class FileChunkLimits {
        /** Largest chunk, bytes. */
        public static final int MAX_CHUNK = 32 * 1024;

        private FileChunkLimits() {
        }
    }

    private static final class ChunkCodec implements PayloadCodec<FileChunk> {
        @Override
        public SweComponent encode(FileChunk c) {
            return new RecordBuilder().text("path", c.path()).count("offset", c.offset()).text("data", Base64
                    .getEncoder().encodeToString(c.data())).text("sha256", c.sha256()).bool("last", c.last()).build();
        }

        @Override
        public FileChunk decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "path", "offset", "data", "sha256", "last");
            byte[] data;
            try {
                data = Base64.getDecoder().decode(r.text("data", 4 * (FileChunkLimits.MAX_CHUNK / 3 + 1)));
            } catch (IllegalArgumentException e) {
                throw new PayloadException(ControlMlCondition.MALFORMED_PAYLOAD, "data is not base64");
            }
            String sha = r.text("sha256", 64);
            if (!sha.equals(sha256Hex(data))) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, "sha256 does not match the data");
            }
            return new FileChunk(path(r), r.count("offset", 0, Long.MAX_VALUE), data, sha, r.bool("last"));
        }
    }

    /** @return lower-case hex SHA-256 of bytes */
    public static String sha256Hex(byte[] data) {
        try {
            byte[] d = java.security.MessageDigest.getInstance("SHA-256").digest(data);
            return java.util.HexFormat.of().formatHex(d);
        } catch (java.security.NoSuchAlgorithmException e) {
            throw new IllegalStateException("SHA-256 is a required JDK algorithm", e);
        }
    }

    private static final class ListingCodec implements PayloadCodec<DirectoryListing> {
        @Override
        public SweComponent encode(DirectoryListing l) {
            RecordBuilder b = new RecordBuilder().text("path", l.path()).count("count", l.entries().size());
            int i = 0;
            for (FileEntry e : l.entries()) {
                b.add("entry" + i++, new RecordBuilder().text("name", e.name()).count("size", e.size()).bool(
                        "directory", e.directory()).build());
            }
            return b.build();
        }

        @Override
        public DirectoryListing decode(SweComponent payload) throws PayloadException {
            String[] indexed = indexedFields(payload, "entry", 1024);
            String[] names = new String[indexed.length + 1];
            names[0] = "path";
            System.arraycopy(indexed, 0, names, 1, indexed.length);
            RecordReader r = RecordReader.of(payload, names);
            List<FileEntry> entries = new ArrayList<>();
            for (int i = 2; i < names.length; i++) {
                RecordReader e = r.record(names[i], "name", "size", "directory");
                entries.add(new FileEntry(e.text("name", 255), e.count("size", 0, Long.MAX_VALUE), e.bool(
                        "directory")));
            }
            return new DirectoryListing(path(r), entries);
        }
    }
}
