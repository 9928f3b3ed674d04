package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Clock;
import java.time.Instant;
import java.time.ZoneOffset;
import java.util.ArrayList;
import java.util.List;

import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.Carrier;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlType;
import sabot.controlml.Outcome;
import sabot.controlml.RequestId;
import sabot.controlml.Resource;
import sabot.controlml.ResourceRegistry;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.internal.Endpoint;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.payload.RecordBuilder;
import sabot.controlml.payload.RecordReader;
import sabot.controlml.swe.SweComponent;

/**
 * The open resource registry (docs/CONTROLML.md, "Resources of other bundles"): a resource another bundle registers
 * is served and checked with its own codec, an unregistered one is still {@code unknown-resource}, a name is
 * registered once, and registries of two connections are independent. Through the endpoint, without a server; the
 * same resource over the wire is {@code ControlMlOnServerTest#aRegisteredResourceOfAnotherBundleTravels}.
 */
class ResourceRegistryTest {

    /** A resource of "another bundle": a counter with a bounded value. */
    record Counter(long value) {
        static final PayloadCodec<Counter> CODEC = new PayloadCodec<>() {
            @Override
            public SweComponent encode(Counter c) {
                return new RecordBuilder().count("value", c.value()).build();
            }

            @Override
            public Counter decode(SweComponent payload) throws PayloadException {
                return new Counter(RecordReader.of(payload, "value").count("value", 0, 100));
            }
        };
    }

    static final Resource<Counter, sabot.controlml.payload.NoQuery> COUNTER = Resource.builder("cm.test.counter", Counter.CODEC).gettable()
            .settable().description("a test counter, 0..100").build();

    private Jid operator;
    private ResourceRegistry registry;
    private Endpoint endpoint;
    private final List<Long> applied = new ArrayList<>();

    @BeforeEach
    void setUp() throws Exception {
        operator = JidCreate.from("operator@sabot.local/wb");
        registry = new ResourceRegistry();
        endpoint = new Endpoint(Clock.fixed(Instant.parse("2026-11-21T12:00:00Z"), ZoneOffset.UTC), registry);
        endpoint.setAccessPolicy(j -> Role.MAINTAINER);
    }

    private static String setCounter(int id, String value) {
        return "<control-ml xmlns='urn:sabot:controlml:1' type='set' id='20261121:" + id + "' res='cm.test.counter'>"
                + "<DataRecord xmlns='http://www.opengis.net/swe/2.0'><field name='value'><Count><value>" + value
                + "</value></Count></field></DataRecord></control-ml>";
    }

    private ControlMlError errorOf(String xml, ControlMlType carrier) throws Exception {
        Endpoint.Answer a = endpoint.serve(Xml.element(xml), carrier, operator, null, Carrier.IQ);
        return a.element().type() == ControlMlType.ERROR ? a.element().failure() : null;
    }

    private void serveCounter() {
        endpoint.onSet(COUNTER, (r, c) -> {
            applied.add(c.value());
            return Outcome.done();
        });
        endpoint.onGet(COUNTER, (r, none) -> Outcome.success(new Counter(applied.isEmpty() ? 0 : applied.get(applied
                .size() - 1))));
    }

    @Test
    void aResourceInNoRegistryIsStillUnknown() throws Exception {
        ControlMlError e = errorOf(setCounter(1, "5"), ControlMlType.SET);
        assertEquals(ControlMlCondition.UNKNOWN_RESOURCE, e.cmCondition());
        assertEquals("item-not-found", e.condition().toString());
    }

    @Test
    void aRegisteredResourceIsServedAndCheckedWithItsOwnCodec() throws Exception {
        registry.register(COUNTER);
        serveCounter();
        assertNull(errorOf(setCounter(1, "42"), ControlMlType.SET));
        assertEquals(List.of(42L), applied);
        ControlMlError out = errorOf(setCounter(2, "101"), ControlMlType.SET);
        assertEquals(ControlMlCondition.INVALID_VALUE, out.cmCondition(), out.toString());
        assertEquals(List.of(42L), applied, "a refused value is not applied");
        Endpoint.Answer got = endpoint.serve(ControlMlElement.request(ControlMlType.GET, RequestId.parse(
                "20261121:3"), "cm.test.counter", null), ControlMlType.GET, operator, null, Carrier.IQ);
        assertEquals(new Counter(42), Xml.element(Xml.xml(got.element())).value(COUNTER));
    }

    @Test
    void handlersOfAnUnregisteredResourceAreRefused() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> endpoint.onGet(COUNTER, (r,
                none) -> Outcome.success(new Counter(1))));
        assertTrue(e.getMessage().contains("cm.test.counter is not in this device's resource registry"), e
                .getMessage());
    }

    @Test
    void aNameIsRegisteredOnce() {
        registry.register(COUNTER);
        Resource<Counter, ?> again = Resource.builder("cm.test.counter", Counter.CODEC).gettable().description(
                "another counter").build();
        IllegalArgumentException clash = assertThrows(IllegalArgumentException.class, () -> registry.register(again));
        assertEquals("resource cm.test.counter is already registered (a test counter, 0..100); one name, one resource",
                clash.getMessage());
        Resource<Counter, ?> pid = Resource.builder("cm.pid", Counter.CODEC).settable().build();
        IllegalArgumentException protocol = assertThrows(IllegalArgumentException.class, () -> registry.register(
                pid));
        assertEquals("resource cm.pid is already registered (a ControlML resource of section 4); one name, one resource",
                protocol.getMessage());
        assertSame(Resources.PID, registry.byName("cm.pid"), "the protocol's resource is untouched");
        assertSame(COUNTER, registry.byName("cm.test.counter"));
    }

    @Test
    void closingTheRegistrationRemovesTheResource() throws Exception {
        ResourceRegistry.Registration r = registry.register(COUNTER);
        serveCounter();
        r.close();
        r.close();
        assertEquals(ControlMlCondition.UNKNOWN_RESOURCE, errorOf(setCounter(1, "5"), ControlMlType.SET)
                .cmCondition());
        assertTrue(applied.isEmpty());
        registry.register(COUNTER); // the name is free again
        assertSame(COUNTER, registry.byName("cm.test.counter"));
    }

    @Test
    void registriesOfTwoConnectionsAreIndependent() {
        ResourceRegistry other = new ResourceRegistry();
        registry.register(COUNTER);
        assertNull(other.byName("cm.test.counter"));
        assertEquals(Resources.all().size(), other.all().size());
        assertEquals(Resources.all().size() + 1, registry.all().size());
    }

    @Test
    void namesOutsideTheSyntaxAndResourcesWithoutOperationsAreRefused() {
        IllegalArgumentException name = assertThrows(IllegalArgumentException.class, () -> Resource.builder(
                "pid.step", Counter.CODEC));
        assertTrue(name.getMessage().startsWith("'pid.step' is not a resource name"), name.getMessage());
        IllegalStateException ops = assertThrows(IllegalStateException.class, () -> Resource.builder("cm.x",
                Counter.CODEC).build());
        assertEquals("cm.x allows neither get nor set", ops.getMessage());
    }
}
