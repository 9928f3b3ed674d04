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
 * @param detail      a short explanation for operators; never null. Made sendable: control characters (line ends of
 *                    an exception's message) become spaces, runs of spaces one, and more than {@link #DETAIL_MAX}
 *                    characters end in "…" (a robot must not make a status its own endpoint would refuse to send)
 * @throws IllegalArgumentException if {@code progress} is outside 0..100 (the schema's range, for the same reason)
 */
public record MissionStatus(MissionState state, boolean maintenance, double progress, String detail) {

    /** Longest {@code detail}, characters (the schema's). */
    public static final int DETAIL_MAX = 256;

    public MissionStatus {
        Objects.requireNonNull(state, "state");
        detail = sendable(Objects.requireNonNull(detail, "detail"));
        if (!(progress >= 0 && progress <= 100)) {
            throw new IllegalArgumentException("mission progress " + progress + " % is outside [0, 100]");
        }
    }

    private static String sendable(String text) {
        if (text.length() <= DETAIL_MAX && text.chars().noneMatch(Character::isISOControl)) {
            return text;
        }
        String line = text.replaceAll("\\p{Cntrl}", " ").replaceAll(" {2,}", " ").strip();
        return line.length() <= DETAIL_MAX ? line : line.substring(0, DETAIL_MAX - 1) + "…";
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
                    r.quantity("progress", "%", 0, 100), r.text("detail", DETAIL_MAX));
        }
    };
}
