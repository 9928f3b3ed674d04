package sabot.controlml.internal;

import java.time.Clock;
import java.time.Duration;
import java.time.Instant;
import java.util.Map;
import java.util.Objects;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicLong;

import org.jxmpp.jid.Jid;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import org.jivesoftware.smack.util.PacketParserUtils;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;

import sabot.controlml.AccessPolicy;
import sabot.controlml.Carrier;
import sabot.controlml.ControlMl;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlType;
import sabot.controlml.GetHandler;
import sabot.controlml.Outcome;
import sabot.controlml.Request;
import sabot.controlml.Resource;
import sabot.controlml.ResourceRegistry;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.SetHandler;
import sabot.controlml.StaleCommandPolicy;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.swe.SweFormatException;
import sabot.controlml.swe.SweXml;

/**
 * The device side of ControlML without the connection: typed handlers per resource, the access and stale-command
 * policies, the replay cache, and the checks every request passes. {@link sabot.controlml.ControlMlManager} feeds
 * it requests from IQs and messages; tests and the fuzzer feed it elements directly. Thread-safe.
 */
public final class Endpoint {

    private static final Logger LOG = LoggerFactory.getLogger(Endpoint.class);

    private final Clock clock;
    private final ResourceRegistry resources;
    private final Map<String, GetHandler<?, ?>> getHandlers = new ConcurrentHashMap<>();
    private final Map<String, SetHandler<?>> setHandlers = new ConcurrentHashMap<>();
    private final ReplayCache replayCache = new ReplayCache(ReplayCache.CAPACITY);
    private final Object setLock = new Object();
    private volatile AccessPolicy accessPolicy = AccessPolicy.CLOSED;
    private volatile StaleCommandPolicy stalePolicy = StaleCommandPolicy.DEFAULT;
    private volatile ClockOffsets clocks;
    private volatile boolean validateWithSchema = true;
    private volatile boolean textForm = true;
    private final AtomicLong requestsServed = new AtomicLong();
    private final AtomicLong errorsAnswered = new AtomicLong();
    private final AtomicLong duplicatesReplayed = new AtomicLong();

    /**
     * @param clock     the device's clock (request ages are measured with it)
     * @param resources the resources this device knows; a request for any other is {@code unknown-resource}
     */
    public Endpoint(Clock clock, ResourceRegistry resources) {
        this.clock = Objects.requireNonNull(clock);
        this.resources = Objects.requireNonNull(resources);
    }

    /** @return the resources this device knows */
    public ResourceRegistry resources() {
        return resources;
    }

    private void checkRegistered(Resource<?, ?> resource) {
        if (resources.byName(resource.name()) != resource) {
            throw new IllegalArgumentException(resource + " is not in this device's resource registry: register it"
                    + " first (ControlMlManager.resources().register)");
        }
    }

    /** Serves gets of a resource (replaces an earlier handler). */
    public <T, Q> void onGet(Resource<T, Q> resource, GetHandler<T, Q> handler) {
        checkRegistered(resource);
        if (!resource.isGettable()) {
            throw new IllegalArgumentException(resource + " has no get");
        }
        getHandlers.put(resource.name(), Objects.requireNonNull(handler));
    }

    /** Applies sets of a resource (replaces an earlier handler). */
    public <T> void onSet(Resource<T, ?> resource, SetHandler<T> handler) {
        checkRegistered(resource);
        if (!resource.isSettable()) {
            throw new IllegalArgumentException(resource + " has no set");
        }
        setHandlers.put(resource.name(), Objects.requireNonNull(handler));
    }

    /**
     * @return whether a request of this type for this resource has a handler here ({@code false} for a name this
     *         device's registry does not know)
     */
    public boolean serves(ControlMlType type, String res) {
        return res != null && (type == ControlMlType.GET ? getHandlers.containsKey(res) : type == ControlMlType.SET
                && setHandlers.containsKey(res));
    }

    /** Stops serving a resource. */
    public void removeHandlers(Resource<?, ?> resource) {
        getHandlers.remove(resource.name());
        setHandlers.remove(resource.name());
    }

    /** @param policy who may do what; default {@link AccessPolicy#CLOSED} */
    public void setAccessPolicy(AccessPolicy policy) {
        this.accessPolicy = Objects.requireNonNull(policy);
    }

    /** @return the access policy */
    public AccessPolicy accessPolicy() {
        return accessPolicy;
    }

    /** @param policy the stale-command policy; default {@link StaleCommandPolicy#DEFAULT} */
    public void setStaleCommandPolicy(StaleCommandPolicy policy) {
        this.stalePolicy = Objects.requireNonNull(policy);
    }

    /**
     * @param offsets the requesters' clocks, to judge a set's send time ({@code sent}) on this device's clock; null
     *                (the default) takes every requester's clock as this one
     */
    public void setClockOffsets(ClockOffsets offsets) {
        this.clocks = offsets;
    }

    /** @return true when a set handler is registered (this connection serves as a device) */
    public boolean servesSets() {
        return !setHandlers.isEmpty();
    }

    /** @param text answers in the text form where the resource allows it (see ControlMlManager#setTextForm) */
    public void setTextForm(boolean text) {
        this.textForm = text;
    }

    /** @param enabled validate request payloads against controlml.xsd as well; default true */
    public void setSchemaValidation(boolean enabled) {
        this.validateWithSchema = enabled;
    }

    /** @return requests served */
    public long requestsServed() {
        return requestsServed.get();
    }

    /** @return requests answered with an error */
    public long errorsAnswered() {
        return errorsAnswered.get();
    }

    /** @return sets answered from the replay cache */
    public long duplicatesReplayed() {
        return duplicatesReplayed.get();
    }

    /** An answer: an element echoing the request's attributes, or (when they were unreadable) a bare error. */
    public record Answer(ControlMlElement element, ControlMlError bareError) {
        static Answer of(ControlMlElement e) {
            return new Answer(e, null);
        }
    }

    /**
     * Checks and serves one request (see {@link sabot.controlml.ControlMlManager} for the order of checks). Never
     * throws: a failing handler is answered with {@link ControlMlCondition#DEVICE_FAULT}.
     *
     * @param request     the element as received (possibly defective)
     * @param carrierType for an IQ, the control-ml type its IQ type implies; for a message, the element's own type
     * @param from        the requester as stamped by the server
     * @param delayStamp  the XEP-0203 delay stamp, or null
     * @param carrier     what carried the request
     * @return the answer to send
     */
    public Answer serve(ControlMlElement request, ControlMlType carrierType, Jid from, Instant delayStamp,
            Carrier carrier) {
        requestsServed.incrementAndGet();
        Answer answer;
        try {
            answer = serveChecked(request, carrierType, from, delayStamp, carrier);
        } catch (RuntimeException e) {
            LOG.warn("ControlML request {} from {} failed", request, from, e);
            answer = refuse(request, ControlMlError.of(ControlMlCondition.DEVICE_FAULT, "the device failed: " + e));
        }
        if (answer.bareError() != null || answer.element().type() == ControlMlType.ERROR) {
            errorsAnswered.incrementAndGet();
        }
        return answer;
    }

    private Answer refuse(ControlMlElement request, ControlMlError error) {
        if (request.hasValidAttributes()) {
            return Answer.of(ControlMlElement.error(request.id(), request.res(), error));
        }
        return new Answer(null, error);
    }

    private Answer serveChecked(ControlMlElement request, ControlMlType carrierType, Jid from, Instant delayStamp,
            Carrier carrier) {
        // The order of checks is the protocol's (docs/CONTROLML.md section 8): a peer must get the same condition
        // from every conforming device, so a check is not moved for convenience.
        ControlMlError defect = request.defect();
        if (defect != null && (!request.hasValidAttributes() || isAttributeDefect(defect))) {
            return refuse(request, defect);
        }
        Role role = accessPolicy.roleOf(from);
        if (role == null || role == Role.NONE) {
            return refuse(request, ControlMlError.of(ControlMlCondition.ACCESS_DENIED, from.asBareJid()
                    + " has no role on this device"));
        }
        if (request.type() != carrierType) {
            return refuse(request, ControlMlError.of(ControlMlCondition.TYPE_MISMATCH, "control-ml type '" + request
                    .type().attribute() + "' in a " + carrier.name().toLowerCase(java.util.Locale.ROOT)
                    + " carrying a " + carrierType.attribute()));
        }
        if (request.type() == ControlMlType.GET) {
            return serveGet(request, from, delayStamp, carrier, role);
        }
        Role needed = setRoleOf(request.res());
        if (!role.includes(needed)) {
            return refuse(request, ControlMlError.of(ControlMlCondition.SET_NOT_PERMITTED, from.asBareJid()
                    + " is " + role.withArticle() + " on this device; a set of " + request.res() + " needs the "
                    + needed.label() + " role"));
        }
        synchronized (setLock) {
            // The duplicate check and the application are atomic: a retransmitted set is never applied twice. The
            // id names the command: a second set under a remembered id gets the first one's answer whatever it
            // carries (its payload is not even looked at, so a retransmission that arrives damaged is answered too).
            ControlMlElement earlier = replayCache.get(from, request.id());
            if (earlier != null) {
                duplicatesReplayed.incrementAndGet();
                return Answer.of(earlier);
            }
            Answer answer = serveSet(request, from, delayStamp, carrier, role);
            if (isRemembered(answer.element())) {
                replayCache.put(from, request.id(), answer.element());
            }
            return answer;
        }
    }

    /**
     * @return the least role a set of the named resource needs; for a name this device does not know, the operator's
     *         (the least of any set), so that an operator learns the name is unknown and an observer that it may not set
     */
    private Role setRoleOf(String res) {
        Resource<?, ?> resource = resources.byName(res);
        return resource == null ? Role.OPERATOR : resource.setRole();
    }

    /** @return true for a defect of the attributes (checked first), false for one of the content (checked late) */
    private static boolean isAttributeDefect(ControlMlError defect) {
        return defect.cmCondition() == ControlMlCondition.BAD_ATTRIBUTES
                || defect.cmCondition() == ControlMlCondition.BAD_ID;
    }

    /**
     * @return whether the answer to a set is kept for retransmissions: every answer but {@code busy}, which tells
     *         the requester to send the same command again later (it must then be taken as new, not refused again)
     */
    static boolean isRemembered(ControlMlElement answer) {
        return answer != null && !(answer.type() == ControlMlType.ERROR && answer.failure()
                .cmCondition() == ControlMlCondition.BUSY);
    }

    /** The content defect of a request that passed the earlier checks: its payload could not be read. */
    private Answer refuseContentDefect(ControlMlElement request) {
        return refuse(request, request.defect());
    }

    /**
     * The request's send time on this device's clock: the earlier of its {@code sent} (moved by the requester's
     * measured clock offset) and the server's delay stamp; the arrival when it carries neither. The age may be
     * negative: a send time ahead of this clock.
     */
    private Request requestOf(ControlMlElement request, Jid from, Instant delayStamp, Carrier carrier, Role role) {
        Instant now = clock.instant();
        Instant sent = now;
        if (request.sent() != null) {
            ClockOffsets offsets = clocks;
            sent = offsets == null ? request.sent() : request.sent().minus(offsets.offsetOf(from));
        }
        if (delayStamp != null && (request.sent() == null || delayStamp.isBefore(sent))) {
            sent = delayStamp;
        }
        return new Request(from, request.id(), request.res(), carrier, sent, Duration.between(sent, now), role);
    }

    @SuppressWarnings("unchecked")
    private Answer serveGet(ControlMlElement request, Jid from, Instant delayStamp, Carrier carrier, Role role) {
        Resource<Object, Object> resource = (Resource<Object, Object>) resources.byName(request.res());
        if (resource == null) {
            return refuse(request, ControlMlError.of(ControlMlCondition.UNKNOWN_RESOURCE, "no resource "
                    + request.res()));
        }
        GetHandler<Object, Object> handler = (GetHandler<Object, Object>) getHandlers.get(resource.name());
        if (!resource.isGettable() || handler == null) {
            return refuse(request, ControlMlError.of(ControlMlCondition.UNSUPPORTED_OPERATION, "this device serves no get of "
                    + resource.name()));
        }
        if (request.defect() != null) {
            return refuseContentDefect(request);
        }
        Object query = NoQuery.NONE;
        PayloadCodec<Object> queryCodec = resource.queryCodec();
        if (queryCodec == null) {
            if (request.payload() != null) {
                return refuse(request, ControlMlError.of(ControlMlCondition.PAYLOAD_MISMATCH, "a get of "
                        + resource.name() + " carries no payload"));
            }
        } else {
            if (request.payload() == null) {
                return refuse(request, ControlMlError.of(ControlMlCondition.PAYLOAD_MISMATCH, "a get of "
                        + resource.name() + " needs its query payload"));
            }
            String problem = schemaProblem(request);
            if (problem != null) {
                return refuse(request, ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD, problem));
            }
            try {
                query = queryCodec.decode(request.payload());
            } catch (PayloadException e) {
                return refuse(request, e.error());
            }
        }
        Outcome<Object> outcome = handler.get(requestOf(request, from, delayStamp, carrier, role), query);
        return answerFor(request, resource, outcome, true);
    }

    @SuppressWarnings("unchecked")
    private Answer serveSet(ControlMlElement request, Jid from, Instant delayStamp, Carrier carrier, Role role) {
        Resource<Object, Object> resource = (Resource<Object, Object>) resources.byName(request.res());
        if (resource == null) {
            return refuse(request, ControlMlError.of(ControlMlCondition.UNKNOWN_RESOURCE, "no resource "
                    + request.res()));
        }
        SetHandler<Object> handler = (SetHandler<Object>) setHandlers.get(resource.name());
        if (!resource.isSettable() || handler == null) {
            return refuse(request, ControlMlError.of(ControlMlCondition.UNSUPPORTED_OPERATION, "this device serves no set of "
                    + resource.name()));
        }
        if (request.defect() != null) {
            return refuseContentDefect(request);
        }
        if (request.payload() == null) {
            return refuse(request, ControlMlError.of(ControlMlCondition.PAYLOAD_MISMATCH, "a set of "
                    + resource.name() + " needs a payload"));
        }
        String problem = schemaProblem(request);
        if (problem != null) {
            return refuse(request, ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD, problem));
        }
        Object value;
        try {
            value = resource.codec().decode(request.payload());
        } catch (PayloadException e) {
            return refuse(request, e.error());
        }
        if (resource.isMotionCommand() && request.sent() == null) {
            return refuse(request, ControlMlError.of(ControlMlCondition.BAD_ATTRIBUTES, "a set of " + resource
                    .name() + " moves the robot and must carry its send time (sent)"));
        }
        ClockOffsets offsets = clocks;
        if (offsets != null && request.sent() != null) {
            offsets.measure(from); // known from the requester's presence, as a rule; else for its next command
        }
        Request r = requestOf(request, from, delayStamp, carrier, role);
        StaleCommandPolicy policy = stalePolicy;
        if (policy.isStale(r.age())) {
            return refuse(request, ControlMlError.of(ControlMlCondition.STALE_COMMAND, "command sent " + r.sent()
                    + " waited " + r.age().toMillis() + " ms, longer than the device accepts ("
                    + policy.maxAge().toMillis() + " ms)" + offsetNote(offsets, from)));
        }
        if (policy.isStale(r.age().negated())) {
            return refuse(request, ControlMlError.of(ControlMlCondition.STALE_COMMAND, "command sent " + r.sent()
                    + ", " + r.age().negated().toMillis() + " ms ahead of the device's clock: its age cannot be"
                    + " judged (more than the " + policy.maxAge().toMillis() + " ms the device accepts)" + offsetNote(
                            offsets, from)));
        }
        return answerFor(request, resource, handler.set(r, value), false);
    }

    private static String offsetNote(ClockOffsets offsets, Jid from) {
        ClockOffsets.Offset o = offsets == null ? null : offsets.of(from);
        return o == null ? "; your clock is taken as the device's (not measured)" : "; your clock differs by "
                + o.offset().toMillis() + " ms (±" + o.uncertainty().toMillis() + ")";
    }

    private Answer answerFor(ControlMlElement request, Resource<Object, Object> resource, Outcome<Object> outcome,
            boolean valueRequired) {
        if (outcome == null) {
            return refuse(request, ControlMlError.of(ControlMlCondition.DEVICE_FAULT, "the handler gave no outcome"));
        }
        if (outcome instanceof Outcome.Failure<Object> f) {
            return refuse(request, f.error());
        }
        Object value = outcome.orElseThrow();
        if (value == null) {
            if (valueRequired) {
                return refuse(request, ControlMlError.of(ControlMlCondition.DEVICE_FAULT, "the device has no value for "
                        + resource.name()));
            }
            return Answer.of(ControlMlElement.result(request.id(), request.res(), null));
        }
        ControlMlElement result = ControlMlElement.result(request.id(), request.res(), resource.codec().encode(value))
                .withTextForm(textForm);
        int size = payloadSizeOver(result.contentXml(), ControlMl.MAX_PAYLOAD_CHARS);
        if (size > 0) {
            // a device must not send what a conforming reader refuses (section 1)
            return refuse(request, ControlMlError.of(ControlMlCondition.PAYLOAD_TOO_LARGE, "the value of "
                    + resource.name() + " does not fit one payload (more than " + ControlMl.MAX_PAYLOAD_CHARS
                    + "); larger data travels as files (cm.fs.*)"));
        }
        return Answer.of(result);
    }

    /**
     * @param contentXml a payload as written
     * @return 0 when its payload size (section 1) is at most {@code limit}, else a positive number. The written
     *         form differs from the counted one (namespace declarations, empty-element tags), so only a payload
     *         whose written length is more than half the limit is read back with the reader's budget.
     */
    static int payloadSizeOver(String contentXml, int limit) {
        if (contentXml.length() <= limit / 2) {
            return 0;
        }
        try {
            XmlPullParser parser = PacketParserUtils.getParserFor(contentXml);
            SweXml.readPayload(parser, new SweXml.Budget(limit), href -> {
                for (Resource<?, ?> r : Resources.all()) {
                    if (href.equals(r.recordHref())) {
                        return r.recordTemplate();
                    }
                }
                return null;
            });
            return 0;
        } catch (SweFormatException e) {
            return e.problem() == SweFormatException.Problem.TOO_LARGE ? 1 : 0;
        } catch (XmlPullParserException | java.io.IOException e) {
            return 0; // our own writer's output: well-formed
        }
    }


    private String schemaProblem(ControlMlElement request) {
        return validateWithSchema ? SchemaValidator.shared().problemWith(request) : null;
    }
}
