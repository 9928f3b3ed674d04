package sabot.controlml.payload;

import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.Set;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.SweComponent;
import sabot.model.geometry.Pose2D;

/**
 * {@code cm.mission}: the mission state (get), or a command (set: pause, resume, abort, maintenance, or a new mission of
 * several targets to start now or to queue).
 *
 * @param state       the state; never null
 * @param maintenance whether the robot is in maintenance mode
 * @param progress    percent of the mission done, 0..100
 * @param detail      a short explanation for operators; never null. Made sendable: control characters (line ends of
 *                    an exception's message) become spaces, runs of spaces one, and more than {@link #DETAIL_MAX}
 *                    characters end in "…" (a robot must not make a status its own endpoint would refuse to send)
 * @param targets     the mission's targets in order, at most {@value #MAX_TARGETS}; empty for a mission to one
 *                    {@code cm.goal}, an imposed trajectory, or none
 * @param current     the index of the target the robot is on its way to (or waits on), 0..{@code targets.size()};
 *                    {@code targets.size()} once all are reached; 0 without targets
 * @param queued      missions waiting in the robot's queue after this one, 0..{@value #MAX_QUEUED}
 * @throws IllegalArgumentException if {@code progress} is outside 0..100 (the schema's range, for the same reason),
 *                                  or the targets, {@code current} or {@code queued} are outside theirs
 */
public record MissionStatus(MissionState state, boolean maintenance, double progress, String detail,
        List<MissionTarget> targets, int current, int queued) {

    /** Longest {@code detail}, characters (the schema's). */
    public static final int DETAIL_MAX = 256;
    /**
     * Most targets in one mission: a status with this many, every number at its longest (17 digits) and the longest
     * detail, still fits one payload ({@code ControlMl.MAX_PAYLOAD_CHARS}; MissionRecordTest measures it).
     */
    public static final int MAX_TARGETS = 64;
    /** Most missions waiting in a robot's queue. */
    public static final int MAX_QUEUED = 16;

    public MissionStatus {
        Objects.requireNonNull(state, "state");
        detail = sendable(Objects.requireNonNull(detail, "detail"));
        targets = List.copyOf(targets);
        if (!(progress >= 0 && progress <= 100)) {
            throw new IllegalArgumentException("mission progress " + progress + " % is outside [0, 100]");
        }
        if (targets.size() > MAX_TARGETS) {
            throw new IllegalArgumentException("at most " + MAX_TARGETS + " targets, were " + targets.size());
        }
        if (current < 0 || current > targets.size()) {
            throw new IllegalArgumentException("current target " + current + " is outside 0.." + targets.size());
        }
        if (queued < 0 || queued > MAX_QUEUED) {
            throw new IllegalArgumentException("queued missions " + queued + " outside 0.." + MAX_QUEUED);
        }
    }

    /** A mission without targets (one goal, an imposed trajectory, or none) and an empty queue. */
    public MissionStatus(MissionState state, boolean maintenance, double progress, String detail) {
        this(state, maintenance, progress, detail, List.of(), 0, 0);
    }

    /** @return this status with another state, progress and detail (targets and queue kept) */
    public MissionStatus with(MissionState s, double p, String d) {
        return new MissionStatus(s, maintenance, p, d, targets, current, queued);
    }

    /** @return true when this record carries the targets' fields (a mission of targets, or a queue) */
    public boolean hasTargetFields() {
        return !targets.isEmpty() || queued > 0;
    }

    private static String sendable(String text) {
        if (text.length() <= DETAIL_MAX && text.chars().noneMatch(Character::isISOControl)) {
            return text;
        }
        String line = text.replaceAll("\\p{Cntrl}", " ").replaceAll(" {2,}", " ").strip();
        return line.length() <= DETAIL_MAX ? line : line.substring(0, DETAIL_MAX - 1) + "…";
    }

    private static final Set<String> MISSION_CODES = codes(MissionState.values());
    private static final Set<String> ACTION_CODES = codes(MissionTarget.Action.values());
    private static final Set<String> TARGET_STATE_CODES = codes(MissionTarget.State.values());

    private static Set<String> codes(Enum<?>[] values) {
        Set<String> codes = new java.util.HashSet<>();
        for (Enum<?> v : values) {
            codes.add(v.name().toLowerCase(java.util.Locale.ROOT));
        }
        return Set.copyOf(codes);
    }

    private static final String[] FIELDS = { "state", "maintenance", "progress", "detail" };
    private static final String[] TARGET_FIELDS = { "x", "y", "theta", "positionTolerance", "headingTolerance",
            "action", "wait", "state" };

    /**
     * The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. The
     * four fields always; {@code current}, {@code queued}, {@code count} and {@code target0…} all together or none.
     */
    public static final PayloadCodec<MissionStatus> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(MissionStatus m) {
            RecordBuilder b = new RecordBuilder().category("state", m.state().code()).bool("maintenance", m
                    .maintenance()).quantity("progress", "%", m.progress()).text("detail", m.detail());
            if (m.hasTargetFields()) {
                b.count("current", m.current()).count("queued", m.queued()).count("count", m.targets().size());
                int i = 0;
                for (MissionTarget t : m.targets()) {
                    Pose2D p = t.goal().pose();
                    b.add("target" + i++, new RecordBuilder().quantity("x", "m", p.x()).quantity("y", "m", p.y())
                            .quantity("theta", "rad", p.theta()).quantity("positionTolerance", "m", t.goal()
                                    .positionTolerance()).quantity("headingTolerance", "rad", t.goal()
                                            .headingTolerance()).category("action", t.action().code()).quantity(
                                                    "wait", "s", t.dwell()).category("state", t.state().code())
                            .build());
                }
            }
            return b.build();
        }

        @Override
        public MissionStatus decode(SweComponent payload) throws PayloadException {
            boolean withTargets = payload instanceof sabot.controlml.swe.DataRecord r && r.get("count") != null;
            String[] names = FIELDS;
            if (withTargets) {
                String[] indexed = RecordReader.indexedFields(payload, "target", MAX_TARGETS);
                names = new String[FIELDS.length + 2 + indexed.length];
                System.arraycopy(FIELDS, 0, names, 0, FIELDS.length);
                names[FIELDS.length] = "current";
                names[FIELDS.length + 1] = "queued";
                System.arraycopy(indexed, 0, names, FIELDS.length + 2, indexed.length);
            }
            RecordReader r = RecordReader.of(payload, names);
            MissionState state = MissionState.fromCode(r.category("state", MISSION_CODES));
            boolean maintenance = r.bool("maintenance");
            double progress = r.quantity("progress", "%", 0, 100);
            String detail = r.text("detail", DETAIL_MAX);
            if (!withTargets) {
                return new MissionStatus(state, maintenance, progress, detail);
            }
            List<MissionTarget> targets = new ArrayList<>();
            for (int i = FIELDS.length + 3; i < names.length; i++) {
                targets.add(target(r.record(names[i], TARGET_FIELDS), names[i]));
            }
            int current = (int) r.count("current", 0, targets.size());
            int queued = (int) r.count("queued", 0, MAX_QUEUED);
            return new MissionStatus(state, maintenance, progress, detail, targets, current, queued);
        }

        private MissionTarget target(RecordReader t, String name) throws PayloadException {
            Pose2D pose = new Pose2D(t.quantity("x", "m"), t.quantity("y", "m"), t.quantity("theta", "rad"));
            Goal goal = new Goal(pose, t.quantity("positionTolerance", "m", RecordReader.POSITIVE,
                    RecordReader.UNBOUNDED), t.quantity("headingTolerance", "rad", RecordReader.POSITIVE, 2 * Math.PI));
            String actionCode = t.category("action", ACTION_CODES);
            MissionTarget.Action action = MissionTarget.Action.valueOf(actionCode.toUpperCase(java.util.Locale.ROOT));
            double wait = t.quantity("wait", "s", 0, MissionTarget.MAX_WAIT_S);
            if ((action == MissionTarget.Action.WAIT) != (wait > 0)) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, name + ".wait must be above 0 s for "
                        + "the action wait and 0 for any other (action " + actionCode + ", wait " + wait + " s)");
            }
            MissionTarget.State s = MissionTarget.State.valueOf(t.category("state", TARGET_STATE_CODES).toUpperCase(
                    java.util.Locale.ROOT));
            return new MissionTarget(goal, action, wait, s);
        }
    };
}
