package sabot.controlml;

import java.time.Clock;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.Date;
import java.util.Iterator;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.WeakHashMap;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.atomic.AtomicLong;

import org.jivesoftware.smack.Manager;
import org.jivesoftware.smack.SmackException.NoResponseException;
import org.jivesoftware.smack.SmackException.NotConnectedException;
import org.jivesoftware.smack.XMPPException.XMPPErrorException;
import org.jivesoftware.smack.StanzaCollector;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.filter.StanzaFilter;
import org.jivesoftware.smack.iqrequest.AbstractIqRequestHandler;
import org.jivesoftware.smack.iqrequest.IQRequestHandler.Mode;
import org.jivesoftware.smack.packet.ErrorIQ;
import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.IqData;
import org.jivesoftware.smack.packet.StanzaBuilder;
import org.jivesoftware.smack.packet.Message;
import org.jivesoftware.smack.packet.MessageBuilder;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.packet.Stanza;
import org.jivesoftware.smack.packet.StandardExtensionElement;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.util.Async;
import org.jivesoftware.smackx.delay.DelayInformationManager;
import org.jivesoftware.smackx.disco.ServiceDiscoveryManager;
import org.jivesoftware.smackx.time.EntityTimeManager;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;
import org.osgi.annotation.versioning.ConsumerType;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.internal.ClockOffsets;
import sabot.controlml.internal.Endpoint;
import sabot.controlml.internal.SchemaValidator;
import sabot.controlml.payload.AccessRole;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.provider.ControlMlProviders;
import sabot.controlml.swe.SweComponent;

/**
 * ControlML on one XMPP connection, in Smack's manager style ({@link #getInstanceFor(XMPPConnection)}).
 * <p>
 * <b>Requester</b> (workbench): {@link #get}, {@link #set} send a request in an {@code <iq/>} and wait for the answer
 * up to {@link #setRequestTimeout request timeout}; {@link #sendCommandMessage} queues a set for an offline device
 * in a {@code <message/>}. Every call returns an {@link Outcome}: no ControlML exception reaches the caller.
 * <p>
 * <b>Endpoint</b> (robot): {@link #onGet} and {@link #onSet} register typed handlers per resource. Every request is
 * checked in this order before a handler runs: readable element (else {@code bad-request}, {@code not-acceptable}
 * for an oversized payload), {@link AccessPolicy} ({@code forbidden}), carrier/type agreement, duplicate id from the
 * same requester (answered again from the replay cache, never re-applied), known resource and operation
 * ({@code item-not-found} / {@code service-unavailable}), payload schema, units and values ({@code bad-request} /
 * {@code not-acceptable}), XSD validation when enabled, and for sets the {@link StaleCommandPolicy}. A refused
 * request leaves the device's state unchanged, and no bad request breaks the connection.
 * <p>
 * Telemetry (PEP publications) has its own manager, {@link TelemetryManager}.
 */
public final class ControlMlManager extends Manager {

    private static final Logger LOG = LoggerFactory.getLogger(ControlMlManager.class);
    private static final Map<XMPPConnection, ControlMlManager> INSTANCES = new WeakHashMap<>();
    private static final int SENT_IDS_REMEMBERED = 16_384;

    static {
        ControlMlProviders.register();
    }

    private final Clock clock;
    private final RequestIdGenerator ids;
    private final Endpoint endpoint;
    private final ClockOffsets clocks;
    private final Map<RequestId, PendingMessage<?>> pendingMessages = new ConcurrentHashMap<>();
    /** Stored commands that arrived before their resource's handler ({@link #hold}). */
    private final List<Message> held = new ArrayList<>();
    /** The most stored commands held at once. */
    static final int HELD_MAX = 256;
    private final Map<String, Boolean> sentStanzaIds = new LinkedHashMap<>(1024, 0.75f, false) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<String, Boolean> eldest) {
            return size() > SENT_IDS_REMEMBERED;
        }
    };

    private volatile Duration requestTimeout = Duration.ofSeconds(ControlMl.DEFAULT_REQUEST_TIMEOUT_S);
    private volatile boolean validateResultsWithSchema = false;
    private volatile boolean textForm = true;

    private final AtomicLong unsolicitedDropped = new AtomicLong();
    private final List<UnsolicitedAnswerListener> unsolicitedListeners = new CopyOnWriteArrayList<>();

    private record PendingMessage<T>(Resource<T, ?> resource, CompletableFuture<Outcome<T>> future) {
    }

    /** @return the manager of a connection, created on first use */
    public static synchronized ControlMlManager getInstanceFor(XMPPConnection connection) {
        return INSTANCES.computeIfAbsent(connection, c -> new ControlMlManager(c, Clock.systemUTC()));
    }

    private ControlMlManager(XMPPConnection connection, Clock clock) {
        super(connection);
        this.clock = clock;
        this.ids = new RequestIdGenerator(clock);
        this.endpoint = new Endpoint(clock, new ResourceRegistry());
        this.clocks = new ClockOffsets(clock, this::entityTimeOf, r -> Async.go(r, "ControlML clock of a requester"));
        endpoint.setClockOffsets(clocks);
        // every device tells a requester its own role (section 9): the endpoint has judged it before any handler
        onGet(Resources.ROLE, (request, none) -> Outcome.success(new AccessRole(request.role())));
        EntityTimeManager.getInstanceFor(connection).enable(); // so that the devices it commands can measure its clock
        // A device learns each requester's clock when it comes online, before its first command (section 5).
        connection.addAsyncStanzaListener(this::onPresence, stanza -> stanza instanceof Presence && endpoint
                .servesSets());
        ServiceDiscoveryManager.getInstanceFor(connection).addFeature(ControlMl.FEATURE);
        connection.registerIQRequestHandler(new RequestHandler(IQ.Type.get));
        connection.registerIQRequestHandler(new RequestHandler(IQ.Type.set));
        connection.addSyncStanzaListener(this::onMessage, CONTROL_ML_MESSAGE);
        // The filter runs on Smack's reader thread and lets through only answers this client never asked for, so
        // ordinary answers cost no listener dispatch (a thread hand-off per answer would show in the round trip).
        connection.addAsyncStanzaListener(this::onIqAnswer, stanza -> stanza instanceof ControlMlIQ iq && !iq
                .isRequestIQ() && !wasSent(iq.getStanzaId()));
    }

    private static final StanzaFilter CONTROL_ML_MESSAGE = stanza -> stanza instanceof Message && stanza.getExtension(
            ControlMlElement.QNAME) != null;


    // ---------------------------------------------------------------------------------------------- settings

    /**
     * @return the resources this connection serves and reads: section 4's, and those other bundles
     *         {@link ResourceRegistry#register register} (e.g. a robot's {@code cm.pid.step}); a request for any other
     *         is answered {@code unknown-resource}
     */
    public ResourceRegistry resources() {
        return endpoint.resources();
    }

    /** @param policy who may get and set on this device; the default is {@link AccessPolicy#CLOSED} */
    public void setAccessPolicy(AccessPolicy policy) {
        endpoint.setAccessPolicy(policy);
    }

    /** @return the access policy in force */
    public AccessPolicy accessPolicy() {
        return endpoint.accessPolicy();
    }

    /** @param policy what to do with sets that waited at the server; default {@link StaleCommandPolicy#DEFAULT} */
    public void setStaleCommandPolicy(StaleCommandPolicy policy) {
        endpoint.setStaleCommandPolicy(policy);
    }

    /**
     * @param timeout how long {@link #get}/{@link #set} (and {@link TelemetryManager#follow}) wait for an answer;
     *                default 10 s
     */
    public void setRequestTimeout(Duration timeout) {
        if (timeout.isNegative() || timeout.isZero()) {
            throw new IllegalArgumentException("timeout must be positive");
        }
        this.requestTimeout = timeout;
    }

    /**
     * @param requests validate incoming requests' payloads against {@code controlml.xsd} (with the OGC SWE Common
     *                 2.0 schema) in addition to the schema checks of the codecs; default true
     * @param results  validate answers received by this requester the same way; default false
     */
    public void setSchemaValidation(boolean requests, boolean results) {
        endpoint.setSchemaValidation(requests);
        this.validateResultsWithSchema = results;
    }

    /**
     * @param text true (default): values of resources with a record structure ({@link Resource#recordTemplate()})
     *             are sent in the text form, a SWE {@code DataStream} of one record referring to the structure
     *             (about a third of the XML form's size and a fifth of its elements, which servers pay for per
     *             element); false: always the XML form. Applies to requests, answers and the telemetry of this
     *             connection's {@link TelemetryManager}; both forms are always read.
     */
    public void setTextForm(boolean text) {
        this.textForm = text;
        endpoint.setTextForm(text);
    }

    /** Called for every ControlML answer that matched no request of this client (after it was logged and dropped). */
    @FunctionalInterface
    @ConsumerType
    public interface UnsolicitedAnswerListener {
        /**
         * @param from    the sender
         * @param element the dropped element
         */
        void dropped(Jid from, ControlMlElement element);
    }

    /** @param listener told about every unsolicited answer dropped (diagnostics, tests) */
    public void addUnsolicitedAnswerListener(UnsolicitedAnswerListener listener) {
        unsolicitedListeners.add(Objects.requireNonNull(listener));
    }

    private void dropUnsolicited(Jid from, ControlMlElement element) {
        unsolicitedDropped.incrementAndGet();
        LOG.warn("dropped unsolicited ControlML answer {} from {}", element, from);
        for (UnsolicitedAnswerListener l : unsolicitedListeners) {
            l.dropped(from, element);
        }
    }

    /** @return the telemetry manager of this connection ({@link TelemetryManager#getInstanceFor}) */
    public TelemetryManager telemetry() {
        return TelemetryManager.getInstanceFor(connection());
    }

    /** @return a snapshot of this connection's request counters (telemetry's: {@link TelemetryManager#statistics}) */
    public ControlMlStatistics statistics() {
        return new ControlMlStatistics(endpoint.requestsServed(), endpoint.errorsAnswered(), endpoint
                .duplicatesReplayed(), unsolicitedDropped.get());
    }

    /** @return a fresh id of this requester (telemetry items take theirs from here too, section 6) */
    RequestId nextId() {
        return ids.next();
    }

    /** @return whether values are written in the text form where their resource allows it */
    boolean isTextForm() {
        return textForm;
    }

    /** @return how long a request waits for its answer */
    Duration requestTimeout() {
        return requestTimeout;
    }

    // ---------------------------------------------------------------------------------------------- requester

    /**
     * Gets a resource that takes no query.
     *
     * @param device the device's full JID (IQs go to a resource, RFC 6120 section 8.5.2)
     * @return the value, or why not
     */
    public <T> Outcome<T> get(Jid device, Resource<T, NoQuery> resource) {
        return get(device, resource, NoQuery.NONE);
    }

    /**
     * Gets a resource with a query (e.g. {@code cm.fs.read}).
     *
     * @return the value, or why not
     */
    public <T, Q> Outcome<T> get(Jid device, Resource<T, Q> resource, Q query) {
        SweComponent payload = null;
        if (resource.queryCodec() != null) {
            payload = resource.queryCodec().encode(Objects.requireNonNull(query, "query"));
        }
        return exchange(device, resource, ControlMlType.GET, payload);
    }

    /**
     * Sets a resource and waits for the acknowledgement.
     *
     * @return a success (whose value is the device's read-back, or null) or why not
     */
    public <T> Outcome<T> set(Jid device, Resource<T, ?> resource, T value) {
        return exchange(device, resource, ControlMlType.SET, resource.codec().encode(Objects.requireNonNull(value,
                "value")));
    }

    private <T> Outcome<T> exchange(Jid device, Resource<T, ?> resource, ControlMlType type, SweComponent payload) {
        ControlMlElement request = ControlMlElement.request(type, ids.next(), resource.name(), payload)
                .withTextForm(textForm);
        Outcome<ControlMlElement> answer = exchange(device, request);
        if (answer instanceof Outcome.Failure<ControlMlElement> f) {
            return Outcome.failure(f.error());
        }
        return decodeAnswer(resource, type, answer.orElseThrow());
    }

    /**
     * Sends a request element as is (a set without a send time gets one: now) and waits for the answer element: the
     * low-level form of {@link #get} and {@link #set}, for tools and tests.
     *
     * @return the answer element (a result; errors arrive as a failure), or why there is none
     */
    public Outcome<ControlMlElement> exchange(Jid device, ControlMlElement request) {
        ControlMlIQ iq = new ControlMlIQ(stamped(request));
        iq.setTo(device);
        String stanzaId = iq.setStanzaId();
        synchronized (sentStanzaIds) {
            sentStanzaIds.put(stanzaId, Boolean.TRUE);
        }
        XMPPConnection connection = connection();
        StanzaCollector collector;
        try {
            collector = connection.createStanzaCollectorAndSend(iq);
        } catch (NotConnectedException e) {
            return Outcome.failure(ControlMlCondition.NOT_CONNECTED, "not connected: " + e.getMessage());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return Outcome.failure(ControlMlCondition.NOT_CONNECTED, "interrupted while sending");
        }
        IQ answer;
        try {
            answer = collector.nextResult(requestTimeout.toMillis());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return Outcome.failure(ControlMlCondition.TIMEOUT, "interrupted while waiting for " + device);
        } finally {
            collector.cancel();
        }
        if (answer == null) {
            return Outcome.failure(ControlMlCondition.TIMEOUT, "no answer from " + device + " within "
                    + requestTimeout.toMillis() + " ms");
        }
        return interpret(device, request, answer);
    }

    /** An answer IQ to {@code request} as the requester sees it: the result element, or why there is none. */
    private static Outcome<ControlMlElement> interpret(Jid device, ControlMlElement request, IQ answer) {
        if (answer.getType() == IQ.Type.error) {
            if (answer instanceof ControlMlIQ cmError && cmError.element().failure() != null) {
                // the control-ml element's failure is complete (condition, reason, text) and in our own namespace
                return Outcome.failure(cmError.element().failure());
            }
            StanzaError error = answer.getError();
            if (error == null) {
                return Outcome.failure(ControlMlCondition.UNSPECIFIED, "error answer without <error/>");
            }
            return Outcome.failure(ControlMlError.fromStanzaError(error));
        }
        if (!(answer instanceof ControlMlIQ cm)) {
            return Outcome.failure(ControlMlCondition.MALFORMED_PAYLOAD, "answer without control-ml from " + device);
        }
        ControlMlElement element = cm.element();
        if (element.defect() != null) {
            return Outcome.failure(element.defect());
        }
        if (element.type() != ControlMlType.RESULT || !Objects.equals(element.id(), request.id())) {
            return Outcome.failure(ControlMlCondition.MALFORMED_PAYLOAD, "answer is not a result for id "
                    + request.id());
        }
        return Outcome.success(element);
    }

    /**
     * Sets a resource without waiting: the answer completes the future (on one of Smack's threads; hand long work
     * off), with a timeout after the {@link #setRequestTimeout request timeout}. For requests a client sends many of
     * and need not wait for, e.g. a workbench's telemetry leases ({@link TelemetryWatcher}).
     *
     * @return the future outcome, as {@link #set} would return it
     */
    public <T> CompletableFuture<Outcome<T>> setAsync(Jid device, Resource<T, ?> resource, T value) {
        ControlMlElement request = stamped(ControlMlElement.request(ControlMlType.SET, ids.next(), resource.name(),
                resource.codec().encode(Objects.requireNonNull(value, "value"))).withTextForm(textForm));
        ControlMlIQ iq = new ControlMlIQ(request);
        iq.setTo(device);
        String stanzaId = iq.setStanzaId();
        synchronized (sentStanzaIds) {
            sentStanzaIds.put(stanzaId, Boolean.TRUE);
        }
        CompletableFuture<Outcome<T>> future = new CompletableFuture<>();
        long timeout = requestTimeout.toMillis();
        try {
            connection().sendIqRequestAsync(iq, timeout).onSuccess(answer -> future.complete(answered(resource,
                    device, request, answer))).onError(e -> {
                        if (e instanceof XMPPErrorException x && x.getStanza() instanceof IQ answer) {
                            future.complete(answered(resource, device, request, answer));
                        } else if (e instanceof NoResponseException) {
                            future.complete(Outcome.failure(ControlMlCondition.TIMEOUT, "no answer from " + device
                                    + " within " + timeout + " ms"));
                        } else {
                            future.complete(Outcome.failure(ControlMlCondition.NOT_CONNECTED, "not sent: " + e));
                        }
                    });
        } catch (RuntimeException e) {
            future.complete(Outcome.failure(ControlMlCondition.NOT_CONNECTED, "not connected: " + e.getMessage()));
        }
        return future;
    }

    private <T> Outcome<T> answered(Resource<T, ?> resource, Jid device, ControlMlElement request, IQ answer) {
        Outcome<ControlMlElement> element = interpret(device, request, answer);
        if (element instanceof Outcome.Failure<ControlMlElement> f) {
            return Outcome.failure(f.error());
        }
        return decodeAnswer(resource, ControlMlType.SET, element.orElseThrow());
    }

    private <T> Outcome<T> decodeAnswer(Resource<T, ?> resource, ControlMlType type, ControlMlElement answer) {
        if (answer.payload() == null) {
            if (type == ControlMlType.GET) {
                return Outcome.failure(ControlMlCondition.PAYLOAD_MISMATCH, "result of a get without payload");
            }
            return Outcome.done();
        }
        if (validateResultsWithSchema) {
            String problem = SchemaValidator.shared().problemWith(answer);
            if (problem != null) {
                return Outcome.failure(ControlMlCondition.MALFORMED_PAYLOAD, problem);
            }
        }
        try {
            return Outcome.success(answer.value(resource));
        } catch (PayloadException e) {
            return Outcome.failure(e.error());
        }
    }

    /**
     * Queues a set for a device that may be offline: a {@code <message type='normal'/>} to its bare JID with a
     * XEP-0334 store hint (so the server keeps it offline and archives it) and a plain-text fallback body. The server
     * stamps it with a XEP-0203 delay when it holds it; the device applies its {@link StaleCommandPolicy} and answers
     * with a message.
     *
     * @param device the device's bare JID
     * @return the pending command; its outcome completes when the answer message arrives
     */
    public <T> PendingCommand<T> sendCommandMessage(EntityBareJid device, Resource<T, ?> resource, T value) {
        RequestId id = ids.next();
        ControlMlElement element = ControlMlElement.request(ControlMlType.SET, id, resource.name(), resource.codec()
                .encode(Objects.requireNonNull(value))).withTextForm(textForm);
        CompletableFuture<Outcome<T>> future = new CompletableFuture<>();
        pendingMessages.put(id, new PendingMessage<>(resource, future));
        element = stamped(element);
        Message message = messageTo(device, element, "ControlML command " + resource.name() + " " + id
                + " (needs a ControlML endpoint)");
        try {
            connection().sendStanza(message);
        } catch (NotConnectedException e) {
            pendingMessages.remove(id);
            future.complete(Outcome.failure(ControlMlCondition.NOT_CONNECTED, "not connected"));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            pendingMessages.remove(id);
            future.complete(Outcome.failure(ControlMlCondition.NOT_CONNECTED, "interrupted while sending"));
        }
        return new PendingCommand<>(id, future);
    }

    /** @return the request; a set without a send time carries now as its send time (section 1's {@code sent}) */
    private ControlMlElement stamped(ControlMlElement request) {
        return request.type() == ControlMlType.SET && request.sent() == null ? request.withSent(clock.instant())
                : request;
    }

    private Instant entityTimeOf(Jid requester) throws Exception {
        Date time = EntityTimeManager.getInstanceFor(connection()).getTime(requester).getTime();
        return time == null ? null : time.toInstant();
    }

    private void onPresence(Stanza stanza) {
        Jid from = stanza.getFrom();
        XMPPConnection c = connection();
        if (from == null || !from.hasResource() || from.equals(c.getUser())) {
            return;
        }
        if (((Presence) stanza).isAvailable()) {
            if (!endpoint.accessPolicy().roleOf(from).includes(Role.OPERATOR)) {
                return; // only those who may command: not every contact or room occupant
            }
            clocks.measure(from);
        } else {
            clocks.forget(from);
        }
    }

    /**
     * @param requester a requester's full JID
     * @return its clock minus this device's as measured with XEP-0202 (section 5), or null when not measured
     */
    public Duration clockOffsetOf(Jid requester) {
        ClockOffsets.Offset o = clocks.of(requester);
        return o == null ? null : o.offset();
    }

    private Message messageTo(Jid to, ControlMlElement element, String body) {
        MessageBuilder b = connection().getStanzaFactory().buildMessageStanza().to(to).ofType(Message.Type.normal)
                .setBody(body).addExtension(element).addExtension(StandardExtensionElement.builder("store",
                        "urn:xmpp:hints").build());
        return b.build();
    }

    // ---------------------------------------------------------------------------------------------- endpoint

    /**
     * Serves gets of a resource on this device (replaces an earlier handler).
     *
     * @throws IllegalArgumentException when the resource is not in {@link #resources()} (register a resource of
     *                                  another bundle first) or has no get
     */
    public <T, Q> void onGet(Resource<T, Q> resource, GetHandler<T, Q> handler) {
        endpoint.onGet(resource, handler);
        releaseHeld(resource);
    }

    /**
     * Applies sets of a resource on this device (replaces an earlier handler).
     *
     * @throws IllegalArgumentException when the resource is not in {@link #resources()} or has no set
     */
    public <T> void onSet(Resource<T, ?> resource, SetHandler<T> handler) {
        endpoint.onSet(resource, handler);
        releaseHeld(resource);
    }

    /** Stops serving a resource (gets and sets). */
    public void removeHandlers(Resource<?, ?> resource) {
        endpoint.removeHandlers(resource);
    }

    private final class RequestHandler extends AbstractIqRequestHandler {
        RequestHandler(IQ.Type type) {
            super(ControlMl.ELEMENT, ControlMl.NAMESPACE, type, Mode.sync);
        }

        @Override
        public IQ handleIQRequest(IQ iq) {
            ControlMlElement request = ((ControlMlIQ) iq).element();
            ControlMlType carrierType = iq.getType() == IQ.Type.get ? ControlMlType.GET : ControlMlType.SET;
            Endpoint.Answer answer = endpoint.serve(request, carrierType, iq.getFrom(), delayOf(iq), Carrier.IQ);
            if (answer.element() != null) {
                // written here, while the payload the handler made is in this core's cache, not by the writer thread
                answer.element().contentXml();
                return new ControlMlIQ(answer.element());
            }
            // Nothing to echo: the error alone (IQ.createErrorResponse would copy the request's child, i.e. a
            // control-ml holding only the attributes that could be read, which is not valid ControlML).
            return bareErrorResponse(iq, answer.bareError());
        }
    }

    /** @return an {@code <iq type='error'/>} answering {@code request} that carries only the {@code <error/>} */
    static IQ bareErrorResponse(IQ request, ControlMlError error) {
        IqData data = StanzaBuilder.buildIqData(request.getStanzaId()).ofType(IQ.Type.error).to(request.getFrom())
                .from(request.getTo());
        return ErrorIQ.builder(error.toStanzaError(), data).build();
    }

    private static Instant delayOf(Stanza stanza) {
        Date stamp = DelayInformationManager.getDelayTimestamp(stanza);
        return stamp == null ? null : stamp.toInstant();
    }

    // ---------------------------------------------------------------------------------------------- messages

    private void onMessage(Stanza stanza) {
        Message message = (Message) stanza;
        if (message.getType() == Message.Type.error) {
            ControlMlElement element = message.getExtension(ControlMlElement.class);
            PendingMessage<?> pending = element == null || element.id() == null ? null : pendingMessages.remove(
                    element.id());
            if (pending != null) {
                StanzaError error = message.getError();
                pending.future().complete(Outcome.failure(error != null ? ControlMlError.fromStanzaError(error)
                        : ControlMlError.of(ControlMlCondition.UNSPECIFIED, "message bounced")));
            }
            return;
        }
        ControlMlElement element = message.getExtension(ControlMlElement.class);
        Jid from = message.getFrom();
        if (element == null || from == null) {
            return;
        }
        if (element.type() != null && element.type().isRequest()) {
            if (hold(message, element)) {
                return;
            }
            Endpoint.Answer answer = endpoint.serve(element, element.type(), from, delayOf(message), Carrier.MESSAGE);
            Message reply;
            if (answer.element() != null) {
                reply = messageTo(from, answer.element(), "ControlML answer " + answer.element().res() + " "
                        + answer.element().id());
            } else {
                // unreadable attributes: nothing to correlate with but the message itself, so bounce it (RFC 6120 8.3)
                reply = StanzaBuilder.buildMessage(message.getStanzaId()).to(from)
                        .ofType(Message.Type.error).setError(answer.bareError().toStanzaError()).build();
            }
            try {
                connection().sendStanza(reply);
            } catch (NotConnectedException e) {
                LOG.info("answer to {} not sent: not connected", from);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            return;
        }
        PendingMessage<?> pending = element.id() == null ? null : pendingMessages.remove(element.id());
        if (pending == null) {
            dropUnsolicited(from, element);
            return;
        }
        completeFromMessage(pending, element);
    }

    /**
     * A stored command (section 5) can arrive at the login, before the device's code has registered the handler of
     * its resource (a robot's session logs in while its other tasks still start): a request for a resource of the
     * registry that has no handler yet is held, and served once its handler is registered (judged then, by its age,
     * with the stale-command policy), at most {@value #HELD_MAX}; beyond them, or for a name the registry does not
     * know, it is answered at once. A device that never serves the resource never answers it, as if offline.
     *
     * @return whether the message was held
     */
    private boolean hold(Message message, ControlMlElement element) {
        if (!element.hasValidAttributes() || endpoint.resources().byName(element.res()) == null || endpoint.serves(
                element.type(), element.res())) {
            return false;
        }
        synchronized (held) {
            if (held.size() >= HELD_MAX) {
                return false;
            }
            held.add(message);
        }
        LOG.info("stored command {} {} from {} held until this device serves {}", element.res(), element.id(),
                message.getFrom(), element.res());
        // registered meanwhile (between the check and the hold): released now
        if (endpoint.serves(element.type(), element.res())) {
            releaseHeld(endpoint.resources().byName(element.res()));
        }
        return true;
    }

    /** Serves the held messages that a handler of {@code resource} now serves (the registering thread). */
    private void releaseHeld(Resource<?, ?> resource) {
        List<Message> now = new ArrayList<>();
        synchronized (held) {
            for (Iterator<Message> i = held.iterator(); i.hasNext();) {
                Message m = i.next();
                ControlMlElement e = m.getExtension(ControlMlElement.class);
                if (resource.name().equals(e.res()) && endpoint.serves(e.type(), e.res())) {
                    now.add(m);
                    i.remove();
                }
            }
        }
        now.forEach(this::onMessage);
    }

    private <T> void completeFromMessage(PendingMessage<T> pending, ControlMlElement element) {
        if (element.defect() != null) {
            pending.future().complete(Outcome.failure(element.defect()));
        } else if (element.type() == ControlMlType.ERROR) {
            pending.future().complete(Outcome.failure(element.failure()));
        } else {
            pending.future().complete(decodeAnswer(pending.resource(), ControlMlType.SET, element));
        }
    }

    private boolean wasSent(String stanzaId) {
        synchronized (sentStanzaIds) {
            return stanzaId != null && sentStanzaIds.containsKey(stanzaId);
        }
    }

    private void onIqAnswer(Stanza stanza) {
        dropUnsolicited(stanza.getFrom(), ((ControlMlIQ) stanza).element());
    }
}
