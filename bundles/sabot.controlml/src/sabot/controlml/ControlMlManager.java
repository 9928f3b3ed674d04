package sabot.controlml;

import java.time.Clock;
import java.time.Duration;
import java.time.Instant;
import java.util.Date;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Objects;
import java.util.WeakHashMap;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.ScheduledThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Supplier;

import org.jivesoftware.smack.Manager;
import org.jivesoftware.smack.SmackException.NotConnectedException;
import org.jivesoftware.smack.StanzaCollector;
import org.jivesoftware.smack.StanzaListener;
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
import org.jivesoftware.smack.packet.Stanza;
import org.jivesoftware.smack.packet.StandardExtensionElement;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smackx.delay.DelayInformationManager;
import org.jivesoftware.smackx.disco.ServiceDiscoveryManager;
import org.jivesoftware.smackx.pep.PepManager;
import org.jivesoftware.smackx.pubsub.NodeExtension;
import org.jivesoftware.smackx.pubsub.PayloadItem;
import org.jivesoftware.smackx.pubsub.PublishItem;
import org.jivesoftware.smackx.pubsub.SubscribeExtension;
import org.jivesoftware.smackx.pubsub.UnsubscribeExtension;
import org.jivesoftware.smackx.pubsub.packet.PubSub;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.internal.Endpoint;
import sabot.controlml.internal.SchemaValidator;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.PayloadCodec;
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
 * <b>Telemetry</b>: {@link #publishTelemetry} publishes a resource's value to the device's PEP node at a fixed rate;
 * {@link #addTelemetryListener} receives it (register before login so that the {@code +notify} feature is in the
 * client's entity caps).
 */
public final class ControlMlManager extends Manager {

    private static final Logger LOG = LoggerFactory.getLogger(ControlMlManager.class);
    private static final Map<XMPPConnection, ControlMlManager> INSTANCES = new WeakHashMap<>();
    private static final int SENT_IDS_REMEMBERED = 16_384;

    static {
        ControlMlProviders.register();
    }

    private final RequestIdGenerator ids;
    private final Endpoint endpoint;
    private final Map<RequestId, PendingMessage<?>> pendingMessages = new ConcurrentHashMap<>();
    private final Map<String, Boolean> sentStanzaIds = new LinkedHashMap<>(1024, 0.75f, false) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<String, Boolean> eldest) {
            return size() > SENT_IDS_REMEMBERED;
        }
    };

    private volatile Duration requestTimeout = Duration.ofSeconds(10);
    private volatile boolean validateResultsWithSchema = false;
    private volatile boolean textForm = true;

    private final AtomicLong unsolicitedDropped = new AtomicLong();
    private final AtomicLong telemetryPublished = new AtomicLong();
    private final AtomicLong telemetryFailed = new AtomicLong();
    private final AtomicLong telemetryReceived = new AtomicLong();
    private final AtomicLong telemetryRejected = new AtomicLong();

    private final java.util.List<UnsolicitedAnswerListener> unsolicitedListeners =
            new java.util.concurrent.CopyOnWriteArrayList<>();
    private final java.util.Set<String> publishWithoutOptions = ConcurrentHashMap.newKeySet();
    private ScheduledExecutorService scheduler;
    private final AtomicInteger activePublications = new AtomicInteger();

    private record PendingMessage<T>(Resource<T, ?> resource, CompletableFuture<Outcome<T>> future) {
    }

    /** @return the manager of a connection, created on first use */
    public static synchronized ControlMlManager getInstanceFor(XMPPConnection connection) {
        return INSTANCES.computeIfAbsent(connection, c -> new ControlMlManager(c, Clock.systemUTC()));
    }

    private ControlMlManager(XMPPConnection connection, Clock clock) {
        super(connection);
        this.ids = new RequestIdGenerator(clock);
        this.endpoint = new Endpoint(clock, new ResourceRegistry());
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

    /** @param timeout how long {@link #get}/{@link #set} wait for an answer; default 10 s */
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
     *             element); false: always the XML form. Applies to requests, answers and telemetry this manager
     *             writes; both forms are always read.
     */
    public void setTextForm(boolean text) {
        this.textForm = text;
        endpoint.setTextForm(text);
    }

    /** Called for every ControlML answer that matched no request of this client (after it was logged and dropped). */
    @FunctionalInterface
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

    /** @return a snapshot of this connection's counters */
    public ControlMlStatistics statistics() {
        return new ControlMlStatistics(endpoint.requestsServed(), endpoint.errorsAnswered(), endpoint
                .duplicatesReplayed(),
                unsolicitedDropped.get(), telemetryPublished.get(), telemetryFailed.get(), telemetryReceived.get(),
                telemetryRejected.get());
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
     * Sends a request element as is and waits for the answer element: the low-level form of {@link #get} and
     * {@link #set}, for tools and tests.
     *
     * @return the answer element (a result; errors arrive as a failure), or why there is none
     */
    public Outcome<ControlMlElement> exchange(Jid device, ControlMlElement request) {
        ControlMlIQ iq = new ControlMlIQ(request);
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
    }

    /**
     * Applies sets of a resource on this device (replaces an earlier handler).
     *
     * @throws IllegalArgumentException when the resource is not in {@link #resources()} or has no set
     */
    public <T> void onSet(Resource<T, ?> resource, SetHandler<T> handler) {
        endpoint.onSet(resource, handler);
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
            Endpoint.Answer answer = endpoint.serve(element, element.type(), from, delayOf(message), Carrier.MESSAGE);
            Message reply;
            if (answer.element() != null) {
                reply = messageTo(from, answer.element(), "ControlML answer " + answer.element().res() + " "
                        + answer.element().id());
            } else {
                // unreadable attributes: nothing to correlate with but the message itself, so bounce it (RFC 6120 8.3)
                reply = org.jivesoftware.smack.packet.StanzaBuilder.buildMessage(message.getStanzaId()).to(from)
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

    // ---------------------------------------------------------------------------------------------- telemetry

    /**
     * Publishes a resource's value to this device's PEP node {@link ControlMl#telemetryNode} at a fixed rate. Each
     * publication is sent without waiting for the server's acknowledgement (counted in {@link #statistics()}); a
     * null from {@code source} skips that tick.
     *
     * @param rateHz publications per second, &gt; 0 and at most 1000
     * @return the running publication
     */
    public <T> TelemetryPublication publishTelemetry(Resource<T, ?> resource, Supplier<? extends T> source,
            double rateHz) {
        if (!(rateHz > 0 && rateHz <= 1000)) {
            throw new IllegalArgumentException("rate must be in (0, 1000] Hz, was " + rateHz);
        }
        long period = Math.round(1e9 / rateHz);
        ScheduledFuture<?> task;
        synchronized (this) {
            if (scheduler == null) {
                ScheduledThreadPoolExecutor s = new ScheduledThreadPoolExecutor(1, r -> {
                    Thread t = new Thread(r, "controlml-telemetry-" + connection().getXMPPServiceDomain());
                    t.setDaemon(true);
                    return t;
                });
                s.setRemoveOnCancelPolicy(true);
                scheduler = s;
            }
            activePublications.incrementAndGet();
            task = scheduler.scheduleAtFixedRate(() -> {
                T value = source.get();
                if (value != null) {
                    publishTelemetryNow(resource, value);
                }
            }, 0, period, TimeUnit.NANOSECONDS);
        }
        return new TelemetryPublication() {
            private boolean stopped;

            @Override
            public String resource() {
                return resource.name();
            }

            @Override
            public long periodNanos() {
                return period;
            }

            @Override
            public void stop() {
                synchronized (ControlMlManager.this) {
                    if (stopped) {
                        return;
                    }
                    stopped = true;
                    task.cancel(false);
                    if (activePublications.decrementAndGet() == 0 && scheduler != null) {
                        scheduler.shutdown();
                        scheduler = null;
                    }
                }
            }
        };
    }

    /**
     * XEP-0060 publish-options of telemetry nodes: items are not persisted (a pose is stale 100 ms later, and
     * Prosody would otherwise write every item to its storage: measured, 1,000 publications/s saturated it) and at
     * most one is kept. The server creates the node with these options on first publication.
     */
    private static final StandardExtensionElement TELEMETRY_PUBLISH_OPTIONS = StandardExtensionElement.builder(
            "publish-options", "http://jabber.org/protocol/pubsub").addElement(StandardExtensionElement.builder("x",
                    "jabber:x:data").addAttribute("type", "submit").addElement(formField("FORM_TYPE",
                            "http://jabber.org/protocol/pubsub#publish-options", true)).addElement(formField(
                                    "pubsub#persist_items", "false", false)).addElement(formField("pubsub#max_items",
                                            "1", false)).build()).build();

    private static StandardExtensionElement formField(String var, String value, boolean hidden) {
        StandardExtensionElement.Builder b = StandardExtensionElement.builder("field", "jabber:x:data").addAttribute(
                "var", var);
        if (hidden) {
            b.addAttribute("type", "hidden");
        }
        return b.addElement("value", value).build();
    }

    /** Publishes one value to the resource's PEP node now, without waiting for the server's acknowledgement. */
    public <T> void publishTelemetryNow(Resource<T, ?> resource, T value) {
        ControlMlElement element = ControlMlElement.result(ids.next(), resource.name(), resource.codec().encode(
                value)).withTextForm(textForm);
        String node = ControlMl.telemetryNode(resource.name());
        // The options are needed only until the server has created the node with them: checking them costs the
        // server a data-form comparison on every publication.
        sendPublication(node, element, !publishWithoutOptions.contains(node));
    }

    private void sendPublication(String node, ControlMlElement element, boolean withOptions) {
        PubSub publish = PubSub.createPubsubPacket(null, IQ.Type.set, new PublishItem<>(node, new PayloadItem<>(
                "current", element)));
        if (withOptions) {
            publish.addExtension(TELEMETRY_PUBLISH_OPTIONS);
        }
        try {
            connection().sendIqRequestAsync(publish).onSuccess(r -> {
                telemetryPublished.incrementAndGet();
                if (withOptions) {
                    publishWithoutOptions.add(node); // the node exists with the options now
                }
            }).onError(
                    e -> {
                        if (withOptions && e instanceof org.jivesoftware.smack.XMPPException.XMPPErrorException x) {
                            // e.g. ejabberd 23.01 refuses these publish-options on an auto-created PEP node:
                            // publish with the server's defaults from now on, this item included
                            if (publishWithoutOptions.add(node)) {
                                LOG.info("server refused telemetry publish-options on {} ({}); publishing with its defaults",
                                        node, x.getStanzaError().getCondition());
                            }
                            sendPublication(node, element, false);
                            return;
                        }
                        telemetryFailed.incrementAndGet();
                        LOG.debug("telemetry publication failed", e);
                    });
        } catch (RuntimeException e) {
            telemetryFailed.incrementAndGet();
        }
    }

    /**
     * Subscribes this client explicitly (XEP-0060 {@code subscribe}) to a device's telemetry node of a resource, so
     * that its publications arrive at {@link #addTelemetryListener listeners} even where the server does not honour
     * the {@code +notify} of the entity capabilities (ejabberd 23.01 now and then never does for a contact, while it
     * always delivers to explicit subscribers). Servers keep one subscription per JID, so calling again does no harm.
     * The node exists once the device has published the resource: before that the answer is {@code item-not-found};
     * call again when the device comes online or publishes.
     *
     * @param device the device's bare JID (the owner of the PEP node)
     * @return done, or why not ({@code item-not-found}, {@code forbidden} without a presence subscription, timeout,
     *         not connected)
     */
    public Outcome<Void> followTelemetry(EntityBareJid device, Resource<?, ?> resource) {
        return pubsubRequest(device, new SubscribeExtension(connection().getUser(), ControlMl.telemetryNode(resource
                .name())));
    }

    /** Ends a subscription made by {@link #followTelemetry}; same answers. */
    public Outcome<Void> unfollowTelemetry(EntityBareJid device, Resource<?, ?> resource) {
        return pubsubRequest(device, new UnsubscribeExtension(connection().getUser().toString(), ControlMl
                .telemetryNode(resource.name())));
    }

    private Outcome<Void> pubsubRequest(EntityBareJid device, NodeExtension request) {
        // a plain request to the owner's PEP service: Smack's PubSubManager.getLeafNode() asks disco#info first, and
        // ejabberd answers it for an auto-created PEP node without the identity Smack insists on
        PubSub iq = PubSub.createPubsubPacket(device, IQ.Type.set, request);
        IQ answer;
        try (StanzaCollector collector = connection().createStanzaCollectorAndSend(iq)) {
            answer = collector.nextResult(requestTimeout.toMillis());
        } catch (NotConnectedException e) {
            return Outcome.failure(ControlMlCondition.NOT_CONNECTED, "not connected: " + e.getMessage());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return Outcome.failure(ControlMlCondition.TIMEOUT, "interrupted while waiting for " + device);
        }
        if (answer == null) {
            return Outcome.failure(ControlMlCondition.TIMEOUT, "no answer from the PEP service of " + device
                    + " within " + requestTimeout.toMillis() + " ms");
        }
        if (answer.getType() == IQ.Type.error) {
            return Outcome.failure(ControlMlError.fromStanzaError(answer.getError()));
        }
        return Outcome.done();
    }

    /**
     * Section 6's deduplication: a telemetry item is taken only when its id is greater than the last one taken from
     * the same publisher for the same resource (a publisher's ids increase, RequestIdGenerator).
     */
    private static boolean isNewer(Map<EntityBareJid, RequestId> lastAccepted, EntityBareJid from, RequestId id) {
        boolean[] newer = { false };
        lastAccepted.compute(from, (k, last) -> {
            newer[0] = last == null || id.compareTo(last) > 0;
            return newer[0] ? id : last;
        });
        return newer[0];
    }

    /**
     * Receives a resource's telemetry from the devices this client is subscribed to. Call before login, so that the
     * {@code <node>+notify} feature is in the entity capabilities the server sees with the first presence; for
     * delivery that does not depend on it, also {@link #followTelemetry} each device.
     */
    public <T> void addTelemetryListener(Resource<T, ?> resource, TelemetryListener<T> listener) {
        Map<EntityBareJid, RequestId> lastAccepted = new ConcurrentHashMap<>();
        PepManager.getInstanceFor(connection()).addPepEventListener(ControlMl.telemetryNode(resource.name()),
                ControlMlElement.class, (from, element, itemId, message) -> {
                    if (element.defect() != null || element.payload() == null || !resource.name().equals(element
                            .res())) {
                        telemetryRejected.incrementAndGet();
                        LOG.debug("rejected telemetry {} from {}", element, from);
                        return;
                    }
                    if (!isNewer(lastAccepted, from, element.id())) {
                        // the same item again (e.g. Prosody 0.12 delivers it for +notify and for the explicit
                        // subscription) or an older one overtaken: section 6's rule, by the publication's id
                        LOG.trace("duplicate telemetry {} from {}", element, from);
                        return;
                    }
                    T value;
                    try {
                        value = element.value(resource);
                    } catch (PayloadException e) {
                        telemetryRejected.incrementAndGet();
                        LOG.debug("rejected telemetry from {}: {}", from, e.getMessage());
                        return;
                    }
                    telemetryReceived.incrementAndGet();
                    listener.onTelemetry(from, value);
                });
    }
}
