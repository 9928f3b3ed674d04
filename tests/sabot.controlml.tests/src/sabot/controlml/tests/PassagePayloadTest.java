package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.time.Instant;
import java.util.Optional;

import org.junit.jupiter.api.Test;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.payload.PassageStatus;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.payload.RecordBuilder;
import sabot.model.robot.PassageClaim;

/** {@code cm.passage}'s payload (docs/CONTROLML.md section 4, docs/PASSAGES.md): a claim, none, and what it refuses. */
class PassagePayloadTest {

    private static final Instant T = Instant.parse("2026-12-01T10:00:00Z");

    @Test
    void aClaimAndNoClaimTravel() throws PayloadException {
        PassageStatus passing = new PassageStatus(T, Optional.of(new PassageClaim(1, PassageClaim.State.PASSING, T
                .minusSeconds(3))));
        assertEquals(passing, PassageStatus.CODEC.decode(PassageStatus.CODEC.encode(passing)));
        PassageStatus none = new PassageStatus(T, Optional.empty());
        assertEquals(none, PassageStatus.CODEC.decode(PassageStatus.CODEC.encode(none)));
    }

    @Test
    void aClaimWithoutItsPassageOrAPassageWithoutAClaimIsAnInvalidValue() {
        for (Object[] bad : new Object[][] { { 0L, "waiting" }, { 3L, "none" } }) {
            PayloadException e = assertThrows(PayloadException.class, () -> PassageStatus.CODEC.decode(
                    new RecordBuilder().time("time", T).count("passage", (Long) bad[0]).category("state",
                            (String) bad[1]).time("since", T).build()));
            assertEquals(ControlMlCondition.INVALID_VALUE, e.error().cmCondition());
            assertEquals("passage " + bad[0] + " with state '" + bad[1] + "': a claim names its passage (1..64) and "
                    + "is waiting or passing; no claim is passage 0, state none", e.getMessage());
        }
        PayloadException range = assertThrows(PayloadException.class, () -> PassageStatus.CODEC.decode(
                new RecordBuilder().time("time", T).count("passage", 65).category("state", "passing").time("since",
                        T).build()));
        assertEquals(ControlMlCondition.INVALID_VALUE, range.error().cmCondition());
    }
}
