package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Clock;
import java.time.Duration;
import java.time.Instant;
import java.time.LocalDate;
import java.time.ZoneOffset;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.atomic.AtomicInteger;

import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.Carrier;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlIQ;
import sabot.controlml.ControlMlType;
import sabot.controlml.Outcome;
import sabot.controlml.Request;
import sabot.controlml.RequestId;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.internal.ClockOffsets;
import sabot.controlml.internal.Endpoint;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.LimitsPayload;

/**
 * A set's send time ({@code sent}, docs/CONTROLML.md sections 1 and 5): written and read, required on the sets that
 * move a robot, and judged on the device's clock through the requester's measured clock offset.
 */
class SendTimeTest {

    private static final Instant NOW = Instant.parse("2026-11-21T12:00:00Z");
    private static final LocalDate DAY = LocalDate.of(2026, 11, 21);
    private static final Duration HOUR = Duration.ofHours(1);
    private static final Goal GOAL = (Goal) Samples.VALUES.get(Resources.GOAL);
    private static final LimitsPayload LIMITS = (LimitsPayload) Samples.VALUES.get(Resources.LIMITS);

    private final AtomicInteger ids = new AtomicInteger();
    private final List<Request> requests = new ArrayList<>();
    private Jid operator;
    private RecordingDevice device;
    private Endpoint endpoint;

    @BeforeEach
    void setUp() throws Exception {
        operator = JidCreate.from("operator@sabot.local/wb");
        device = new RecordingDevice();
        endpoint = RecordingDevice.endpoint(Clock.fixed(NOW, ZoneOffset.UTC), device);
        endpoint.setAccessPolicy(j -> Role.MAINTAINER);
        endpoint.onSet(Resources.GOAL, (request, goal) -> {
            requests.add(request);
            return Outcome.done();
        });
    }

    private ControlMlElement goal(Instant sent) {
        ControlMlElement e = ControlMlElement.request(ControlMlType.SET, new RequestId(DAY, ids.incrementAndGet()),
                "cm.goal", Resources.GOAL.codec().encode(GOAL));
        return sent == null ? e : e.withSent(sent);
    }

    private ControlMlError serve(ControlMlElement request, Instant delayStamp) throws Exception {
        // through the wire form, as a device receives it
        ControlMlElement received = Xml.element(Xml.xml(request));
        Endpoint.Answer a = endpoint.serve(received, ControlMlType.SET, operator, delayStamp, Carrier.IQ);
        return a.element() == null ? a.bareError() : a.element().failure();
    }

    @Test
    void theSendTimeTravelsToTheNanosecondInTheElementAndInTheIq() throws Exception {
        Instant sent = Instant.parse("2026-11-28T10:15:30.123456789Z");
        ControlMlElement e = goal(sent);
        assertEquals(sent, Xml.element(Xml.xml(e)).sent());
        assertTrue(Xml.xml(e).contains(" sent='2026-11-28T10:15:30.123456789Z'"), Xml.xml(e));
        ControlMlIQ iq = new ControlMlIQ(e);
        assertEquals(sent, ((ControlMlIQ) Xml.stanza("<iq xmlns='jabber:client' type='set' id='i1' from="
                + "'operator@sabot.local/wb' to='robot@sabot.local/onboard'>" + Xml.xml(e) + "</iq>")).element()
                        .sent());
        assertTrue(Xml.xml(iq).contains("sent='2026-11-28T10:15:30.123456789Z'"), Xml.xml(iq));
        assertNull(Xml.element(Xml.xml(goal(null))).sent());
    }

    @Test
    void aSendTimeOnAnythingButASetOrNotInUtcIsABadAttribute() throws Exception {
        String get = "<control-ml xmlns='urn:sabot:controlml:1' type='get' id='20261121:1' res='cm.goal' "
                + "sent='2026-11-21T12:00:00Z'/>";
        assertEquals(ControlMlCondition.BAD_ATTRIBUTES, Xml.element(get).defect().cmCondition());
        for (String bad : List.of("2026-11-21T13:00:00+01:00", "2026-11-21T12:00:00", "2026-11-21", "yesterday",
                "2026-11-21T12:00:00.1234567890Z", "")) {
            ControlMlElement e = Xml.element(Xml.xml(goal(NOW)).replace("2026-11-21T12:00:00Z", bad));
            assertEquals(ControlMlCondition.BAD_ATTRIBUTES, e.defect().cmCondition(), bad);
            assertTrue(e.defect().text().contains("sent must be an ISO 8601 UTC time stamp"), e.defect().text());
        }
    }

    @Test
    void aSetThatMovesTheRobotWithoutItsSendTimeIsRefusedAndOtherSetsAreApplied() throws Exception {
        ControlMlError e = serve(goal(null), null);
        assertEquals(ControlMlCondition.BAD_ATTRIBUTES, e.cmCondition());
        assertEquals("a set of cm.goal moves the robot and must carry its send time (sent)", e.text());
        assertTrue(requests.isEmpty());
        for (var r : List.of(Resources.VELOCITY, Resources.TRAJECTORY, Resources.MISSION)) {
            assertTrue(r.isMotionCommand(), r.name());
        }
        ControlMlElement limits = ControlMlElement.request(ControlMlType.SET, new RequestId(DAY, 900), "cm.limits",
                Resources.LIMITS.codec().encode(LIMITS));
        assertNull(serve(limits, null), "a set that does not move the robot needs no send time");
        assertEquals(List.of("cm.limits 20261121:900"), device.applied);
    }

    @Test
    void theAgeIsTheDevicesNowMinusTheSendTimeAndTheLimitRefusesOlderAndFurtherAhead() throws Exception {
        assertNull(serve(goal(NOW.minusSeconds(2)), null));
        assertEquals(Duration.ofSeconds(2), requests.get(0).age());
        ControlMlError old = serve(goal(NOW.minusMillis(5001)), null);
        assertEquals(ControlMlCondition.STALE_COMMAND, old.cmCondition());
        assertTrue(old.text().contains("waited 5001 ms, longer than the device accepts (5000 ms)"), old.text());
        ControlMlError ahead = serve(goal(NOW.plusSeconds(6)), null);
        assertEquals(ControlMlCondition.STALE_COMMAND, ahead.cmCondition());
        assertTrue(ahead.text().contains("6000 ms ahead of the device's clock"), ahead.text());
        assertTrue(ahead.text().contains("your clock is taken as the device's (not measured)"), ahead.text());
        assertEquals(1, requests.size());
    }

    @Test
    void theServersDelayStampCountsWhenItIsEarlier() throws Exception {
        // held offline: the delay stamp is earlier than a send time that a requester wrote late
        ControlMlError e = serve(goal(NOW.minusSeconds(1)), NOW.minusSeconds(60));
        assertEquals(ControlMlCondition.STALE_COMMAND, e.cmCondition());
        assertNull(serve(goal(NOW.minusSeconds(1)), NOW));
        assertEquals(Duration.ofSeconds(1), requests.get(0).age());
    }

    @Test
    void aRequesterAnHourAheadIsJudgedOnItsOwnClockOnceMeasured() throws Exception {
        AtomicInteger queries = new AtomicInteger();
        List<Runnable> background = new ArrayList<>(); // the measurements, run when the test says they are done
        ClockOffsets offsets = new ClockOffsets(Clock.fixed(NOW, ZoneOffset.UTC), who -> {
            queries.incrementAndGet();
            return who.equals(operator) ? NOW.plus(HOUR) : null;
        }, background::add);
        endpoint.setClockOffsets(offsets);
        offsets.measure(operator); // its presence came
        runAll(background);
        assertEquals(HOUR, offsets.offsetOf(operator));

        assertNull(serve(goal(NOW.plus(HOUR).minusSeconds(2)), null), "sent 2 s ago on the requester's clock");
        assertEquals(Duration.ofSeconds(2), requests.get(0).age());
        assertEquals(NOW.minusSeconds(2), requests.get(0).sent());
        ControlMlError old = serve(goal(NOW.plus(HOUR).minusSeconds(10)), null);
        assertEquals(ControlMlCondition.STALE_COMMAND, old.cmCondition());
        assertTrue(old.text().contains("your clock differs by 3600000 ms"), old.text());
        assertEquals(1, queries.get(), "measured once per presence");

        offsets.forget(operator); // offline: the next session may run on another clock
        ControlMlError unmeasured = serve(goal(NOW.plus(HOUR)), null);
        assertEquals(ControlMlCondition.STALE_COMMAND, unmeasured.cmCondition(), "an hour ahead, unmeasured");
        assertTrue(unmeasured.text().contains("not measured"), unmeasured.text());
        runAll(background); // the set from an unmeasured clock asked for its time
        assertEquals(2, queries.get());
        assertNull(serve(goal(NOW.plus(HOUR)), null), "now measured");
    }

    private static void runAll(List<Runnable> tasks) {
        List<Runnable> now = new ArrayList<>(tasks);
        tasks.clear();
        now.forEach(Runnable::run);
    }

    @Test
    void aRequesterThatDoesNotTellItsTimeIsTakenAsSynchronised() throws Exception {
        ClockOffsets offsets = new ClockOffsets(Clock.fixed(NOW, ZoneOffset.UTC), who -> {
            throw new IllegalStateException("feature-not-implemented");
        }, Runnable::run);
        endpoint.setClockOffsets(offsets);
        offsets.measure(operator);
        assertNull(offsets.of(operator));
        assertNull(serve(goal(NOW.minusSeconds(1)), null));
        assertEquals(ControlMlCondition.STALE_COMMAND, serve(goal(NOW.minusSeconds(6)), null).cmCondition());
    }
}
