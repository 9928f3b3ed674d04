package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.payload.RecordBuilder;
import sabot.controlml.swe.DataRecord;
import sabot.controlml.swe.SweComponent;
import sabot.model.geometry.Pose2D;

/** {@code cm.mission}'s record with targets (section 4): both forms travel, and bad records are refused. */
class MissionRecordTest {

    private static final MissionStatus WITH_TARGETS = new MissionStatus(MissionState.RUNNING, false, 37.5,
            "target 2 of 3", List.of(new MissionTarget(new Goal(new Pose2D(1, 2, 0), 0.1, 0.2),
                    MissionTarget.Action.PASS, 0, MissionTarget.State.REACHED), new MissionTarget(new Goal(
                            new Pose2D(3, 2, 1.5), 0.05, 0.1), MissionTarget.Action.WAIT, 4.5,
                            MissionTarget.State.ACTIVE), new MissionTarget(new Goal(new Pose2D(0.5, 0.5, 3), 0.05,
                                    0.1), MissionTarget.Action.DOCK, 0, MissionTarget.State.PENDING)), 1, 2);

    @Test
    void aMissionWithTargetsTravelsAndOneWithoutKeepsItsFourFields() throws PayloadException {
        assertEquals(WITH_TARGETS, MissionStatus.CODEC.decode(MissionStatus.CODEC.encode(WITH_TARGETS)));
        MissionStatus plain = new MissionStatus(MissionState.PAUSED, false, 10, "paused");
        SweComponent encoded = MissionStatus.CODEC.encode(plain);
        assertEquals(4, ((DataRecord) encoded).fields().size(), "no target fields without targets or a queue");
        assertEquals(plain, MissionStatus.CODEC.decode(encoded));
        MissionStatus queueOnly = new MissionStatus(MissionState.RUNNING, false, 0, "to (1, 1)", List.of(), 0, 3);
        assertEquals(queueOnly, MissionStatus.CODEC.decode(MissionStatus.CODEC.encode(queueOnly)));
    }

    private static SweComponent target(String action, double wait, String state) {
        return new RecordBuilder().quantity("x", "m", 1).quantity("y", "m", 1).quantity("theta", "rad", 0).quantity(
                "positionTolerance", "m", 0.1).quantity("headingTolerance", "rad", 0.2).category("action", action)
                .quantity("wait", "s", wait).category("state", state).build();
    }

    private static RecordBuilder head(long current, long count) {
        return new RecordBuilder().category("state", "running").bool("maintenance", false).quantity("progress", "%", 0)
                .text("detail", "").count("current", current).count("queued", 0).count("count", count);
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "a wait target without a wait  | wait    | 0    | pending | 0 | invalid-value",
        "a stop target with a wait     | stop    | 2    | pending | 0 | invalid-value",
        "a wait over an hour           | wait    | 3601 | pending | 0 | invalid-value",
        "an unknown action             | fly     | 0    | pending | 0 | invalid-value",
        "an unknown target state       | stop    | 0    | lost    | 0 | invalid-value",
        "current past the targets      | stop    | 0    | pending | 2 | invalid-value",
    })
    void badTargetsAreRefused(String why, String action, double wait, String state, long current, String condition) {
        SweComponent bad = head(current, 1).add("target0", target(action, wait, state)).build();
        PayloadException e = assertThrows(PayloadException.class, () -> MissionStatus.CODEC.decode(bad), why);
        assertEquals(ControlMlCondition.fromElement(condition), e.error().cmCondition(), why + ": " + e.getMessage());
    }

    @Test
    void theLongestMissionFitsOnePayload() throws Exception {
        List<MissionTarget> targets = new java.util.ArrayList<>();
        for (int i = 0; i < MissionStatus.MAX_TARGETS; i++) {
            targets.add(new MissionTarget(new Goal(new Pose2D(-10.123456789012345 - i, -7.987654321098765,
                    -3.1415926535897931), 0.30000000000000004, 6.2831853071795862), MissionTarget.Action.WAIT,
                    3599.1234567890123, MissionTarget.State.PENDING));
        }
        MissionStatus longest = new MissionStatus(MissionState.RUNNING, false, 99.123456789012345, "é".repeat(
                MissionStatus.DETAIL_MAX), targets, MissionStatus.MAX_TARGETS, MissionStatus.MAX_QUEUED);
        String xml = sabot.controlml.ControlMlElement.result(new sabot.controlml.RequestId(java.time.LocalDate.of(2026,
                11, 29), 4294967295L), "cm.mission", MissionStatus.CODEC.encode(longest)).withTextForm(false)
                .contentXml();
        int size = ConformanceTest.payloadSize(xml);
        System.out.printf("[figure] the longest cm.mission (%d targets): %d of %d code points%n",
                MissionStatus.MAX_TARGETS, size, sabot.controlml.ControlMl.MAX_PAYLOAD_CHARS);
        assertTrue(size <= sabot.controlml.ControlMl.MAX_PAYLOAD_CHARS, size + " code points");
    }

    @Test
    void aCountThatDoesNotMatchTheTargetsOrMissingFieldsAreMalformed() {
        SweComponent short1 = head(0, 2).add("target0", target("stop", 0, "pending")).build();
        assertEquals(ControlMlCondition.MALFORMED_PAYLOAD, assertThrows(PayloadException.class,
                () -> MissionStatus.CODEC.decode(short1)).error().cmCondition());
        SweComponent noQueue = new RecordBuilder().category("state", "running").bool("maintenance", false).quantity(
                "progress", "%", 0).text("detail", "").count("current", 0).count("count", 1).add("target0", target(
                        "stop", 0, "pending")).build();
        PayloadException e = assertThrows(PayloadException.class, () -> MissionStatus.CODEC.decode(noQueue));
        assertEquals(ControlMlCondition.MALFORMED_PAYLOAD, e.error().cmCondition());
        assertTrue(e.getMessage().contains("queued"), e.getMessage());
        RecordBuilder many = head(0, MissionStatus.MAX_TARGETS + 1);
        for (int i = 0; i <= MissionStatus.MAX_TARGETS; i++) {
            many.add("target" + i, target("stop", 0, "pending"));
        }
        SweComponent tooMany = many.build();
        assertEquals(ControlMlCondition.INVALID_VALUE, assertThrows(PayloadException.class,
                () -> MissionStatus.CODEC.decode(tooMany)).error().cmCondition());
    }
}
