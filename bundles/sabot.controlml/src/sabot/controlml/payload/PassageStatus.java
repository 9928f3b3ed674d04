package sabot.controlml.payload;

import java.time.Instant;
import java.util.Locale;
import java.util.Objects;
import java.util.Optional;
import java.util.Set;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.SweComponent;
import sabot.model.map.MapServerFormat;
import sabot.model.robot.PassageClaim;

/**
 * {@code cm.passage}: the robot's claim on a narrow passage of its map (docs/PASSAGES.md), which the other robots
 * follow to take turns: the passage's id on the map ({@code sabot_passages}, from 1; 0 for no claim), the state
 * ({@code none}, {@code waiting}, {@code passing}) and when the robot asked for it.
 *
 * @param time  when the status was read; never null
 * @param claim the claim, empty for none; never null
 */
public record PassageStatus(Instant time, Optional<PassageClaim> claim) {

    public PassageStatus {
        Objects.requireNonNull(time, "time");
        Objects.requireNonNull(claim, "claim");
    }

    static final Set<String> STATES = Set.of("none", "waiting", "passing");

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, ranges. */
    public static final PayloadCodec<PassageStatus> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(PassageStatus p) {
            PassageClaim c = p.claim().orElse(null);
            return new RecordBuilder().time("time", p.time()).count("passage", c == null ? 0 : c.passage()).category(
                    "state", c == null ? "none" : c.state().name().toLowerCase(Locale.ROOT)).time("since", c == null
                            ? p.time() : c.since()).build();
        }

        @Override
        public PassageStatus decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "time", "passage", "state", "since");
            Instant time = r.time("time");
            int passage = (int) r.count("passage", 0, MapServerFormat.MAX_PASSAGES);
            String state = r.category("state", STATES);
            Instant since = r.time("since");
            if (state.equals("none") != (passage == 0)) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, "passage " + passage + " with state '"
                        + state + "': a claim names its passage (1.." + MapServerFormat.MAX_PASSAGES
                        + ") and is waiting or passing; no claim is passage 0, state none");
            }
            if (passage == 0) {
                return new PassageStatus(time, Optional.empty());
            }
            return new PassageStatus(time, Optional.of(new PassageClaim(passage, PassageClaim.State.valueOf(state
                    .toUpperCase(Locale.ROOT)), since)));
        }
    };
}
