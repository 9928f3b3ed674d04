package sabot.controlml.payload;

import java.util.Objects;
import java.util.Set;

import sabot.controlml.swe.SweComponent;

/**
 * {@code cm.mission}: the mission state (get), or a requested transition (set: pause, resume, abort, maintenance).
 *
 * @param state       the state; never null
 * @param maintenance whether the robot is in maintenance mode
 * @param progress    percent of the path done, 0..100
 * @param detail      a short explanation for operators; never null
 * @throws IllegalArgumentException if {@code progress} is outside 0..100 (the schema's range: a robot must not make a
 *                                  status that its own endpoint would refuse to send)
 */
public record MissionStatus(MissionState state, boolean maintenance, double progress, String detail) {
    public MissionStatus {
        Objects.requireNonNull(state, "state");
        Objects.requireNonNull(detail, "detail");
        if (!(progress >= 0 && progress <= 100)) {
            throw new IllegalArgumentException("mission progress " + progress + " % is outside [0, 100]");
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

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<MissionStatus> CODEC = new PayloadCodec<>() {
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
    };
}
