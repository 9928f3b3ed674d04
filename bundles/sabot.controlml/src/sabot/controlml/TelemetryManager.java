package sabot.controlml;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.WeakHashMap;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.ScheduledThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.BiConsumer;
import java.util.function.Supplier;

import org.jivesoftware.smack.Manager;
import org.jivesoftware.smack.SmackException.NotConnectedException;
import org.jivesoftware.smack.StanzaCollector;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException.XMPPErrorException;
import org.jivesoftware.smack.filter.AndFilter;
import org.jivesoftware.smack.filter.MessageTypeFilter;
import org.jivesoftware.smack.filter.StanzaFilter;
import org.jivesoftware.smack.filter.jidtype.FromJidTypeFilter;
import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.NamedElement;
import org.jivesoftware.smack.packet.StandardExtensionElement;
import org.jivesoftware.smack.packet.Stanza;
import org.jivesoftware.smackx.disco.ServiceDiscoveryManager;
import org.jivesoftware.smackx.pubsub.EventElement;
import org.jivesoftware.smackx.pubsub.ItemsExtension;
import org.jivesoftware.smackx.pubsub.NodeExtension;
import org.jivesoftware.smackx.pubsub.PayloadItem;
import org.jivesoftware.smackx.pubsub.PublishItem;
import org.jivesoftware.smackx.pubsub.SubscribeExtension;
import org.jivesoftware.smackx.pubsub.UnsubscribeExtension;
import org.jivesoftware.smackx.pubsub.filter.EventItemsExtensionFilter;
import org.jivesoftware.smackx.pubsub.packet.PubSub;
import org.jxmpp.jid.EntityBareJid;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.payload.PayloadException;

/**
 * ControlML telemetry on one XMPP connection (section 6 of {@code docs/CONTROLML.md}), in Smack's manager style
 * ({@link #getInstanceFor(XMPPConnection)}), beside {@link ControlMlManager} as Smack's {@code PepManager} is beside
 * its IQ managers.
 * <p>
 * A device {@link #publish publishes} a resource's value to its PEP node {@link ControlMl#telemetryNode} at a fixed
 * rate; a client {@link #addListener listens} to the resource (register before login so that the {@code +notify}
 * feature is in the client's entity caps) and {@link #follow follows} each device for delivery that does not depend on
 * it. Items are written in the form {@link ControlMlManager#setTextForm} chooses, with ids of the connection's
 * {@link ControlMlManager}; pubsub requests wait up to its {@link ControlMlManager#setRequestTimeout request timeout}.
 */
public final class TelemetryManager extends Manager {

    private static final Logger LOG = LoggerFactory.getLogger(TelemetryManager.class);
    private static final Map<XMPPConnection, TelemetryManager> INSTANCES = new WeakHashMap<>();
    /** Suffix of the disco feature that asks for a PEP node's notifications (XEP-0163 section 4). */
    private static final String PLUS_NOTIFY = "+notify";
    /** PEP item events from a bare JID: PepManager's filter. */
    private static final StanzaFilter PEP_EVENTS = new AndFilter(MessageTypeFilter.NORMAL_OR_HEADLINE,
            FromJidTypeFilter.ENTITY_BARE_JID, EventItemsExtensionFilter.INSTANCE);

    private final ControlMlManager controlMl;
    private final Set<String> publishWithoutOptions = ConcurrentHashMap.newKeySet();
    /**
     * By node whose first publication (the one with the options) awaits the server's answer: the values published
     * meanwhile, in order. They are sent once the answer has come, after that first value again when the server
     * refused the options: sent at once, a later value would reach the server before the refused first one's second
     * sending, and subscribers would drop the older id as a copy (the node going back in time on the way).
     */
    private final Map<String, List<ControlMlElement>> heldBack = new HashMap<>();
    private final AtomicInteger activePublications = new AtomicInteger();
    private ScheduledExecutorService scheduler;
    /** What {@link #addListener} registered, by PEP node: each item of the node from a device goes to each of them. */
    private final Map<String, List<BiConsumer<EntityBareJid, ControlMlElement>>> itemHandlers =
            new ConcurrentHashMap<>();

    private final AtomicLong published = new AtomicLong();
    private final AtomicLong failed = new AtomicLong();
    private final AtomicLong received = new AtomicLong();
    private final AtomicLong rejected = new AtomicLong();

    /** @return the telemetry manager of a connection, created on first use (with its {@link ControlMlManager}) */
    public static synchronized TelemetryManager getInstanceFor(XMPPConnection connection) {
        return INSTANCES.computeIfAbsent(connection, TelemetryManager::new);
    }

    private TelemetryManager(XMPPConnection connection) {
        super(connection);
        this.controlMl = ControlMlManager.getInstanceFor(connection); // registers the providers, issues the ids
        // what PepManager does, without its dispatch: PepManager hands each event to a pooled thread per sender
        // (AsyncButOrdered), so 100 robots kept some 80 threads waking one another on every burst of items
        // (docs/WORKBENCH.md, "What limits it"); a synchronous listener gets them in arrival order on the
        // connection's one listener thread
        connection.addSyncStanzaListener(this::onPepEvent, PEP_EVENTS);
    }

    /** @return a snapshot of this connection's telemetry counters */
    public TelemetryStatistics statistics() {
        return new TelemetryStatistics(published.get(), failed.get(), received.get(), rejected.get());
    }


    /**
     * Publishes a resource's value to this device's PEP node {@link ControlMl#telemetryNode} at a rate, which
     * {@link TelemetryPublication#setRate} changes (a device serving leases, {@link TelemetryLeases}, does). Each
     * publication is sent without waiting for the server's acknowledgement (counted in {@link #statistics()}); a
     * null from {@code source} skips that tick.
     *
     * @param rateHz publications per second, 0 (none until the rate is changed) to 1000
     * @return the running publication
     */
    public <T> TelemetryPublication publish(Resource<T, ?> resource, Supplier<? extends T> source,
            double rateHz) {
        checkRate(rateHz);
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
            Publication<T> p = new Publication<>(resource, source, scheduler);
            p.setRate(rateHz);
            return p;
        }
    }

    /**
     * Serves {@code cm.telemetry} on this device: resources {@link TelemetryLeases#offer offered} there are published at
     * a base rate, and faster while a watcher leases them (section 6, "Leases").
     *
     * @param maxLeaseSeconds the longest lease granted, in (0, 3600]
     * @return the leases; close them to stop their publications and the {@code cm.telemetry} handlers
     */
    public TelemetryLeases serveLeases(double maxLeaseSeconds) {
        return new TelemetryLeases(controlMl, this, connection(), maxLeaseSeconds);
    }

    /**
     * Leases devices' telemetry at the rates this client looks at (section 6, "Leases"): one watcher per client.
     *
     * @param leaseSeconds the lease asked for, in (0, 3600]; renewed at half of what each device grants
     * @return the watcher; close it to end its leases
     */
    public TelemetryWatcher watcher(double leaseSeconds) {
        return new TelemetryWatcher(controlMl, leaseSeconds, connection().getXMPPServiceDomain().toString());
    }

    private static void checkRate(double rateHz) {
        if (!(rateHz >= 0 && rateHz <= 1000)) {
            throw new IllegalArgumentException("rate must be in [0, 1000] Hz, was " + rateHz);
        }
    }

    /** One resource's periodic publication on the manager's scheduler; its rate can change while it runs. */
    private final class Publication<T> implements TelemetryPublication {
        private final Resource<T, ?> resource;
        private final Supplier<? extends T> source;
        private final ScheduledExecutorService on;
        // guarded by TelemetryManager.this
        private ScheduledFuture<?> task;
        private double rate;
        private long period;
        private boolean stopped;
        /** System.nanoTime() of the last tick; a rate change keeps the next one a new period after it. */
        private volatile long lastTick = System.nanoTime() - TimeUnit.DAYS.toNanos(1);

        Publication(Resource<T, ?> resource, Supplier<? extends T> source, ScheduledExecutorService on) {
            this.resource = resource;
            this.source = source;
            this.on = on;
        }

        private void tick() {
            lastTick = System.nanoTime();
            T value = source.get();
            if (value != null) {
                publishNow(resource, value);
            }
        }

        @Override
        public String resource() {
            return resource.name();
        }

        @Override
        public long periodNanos() {
            synchronized (TelemetryManager.this) {
                return period;
            }
        }

        @Override
        public double rate() {
            synchronized (TelemetryManager.this) {
                return rate;
            }
        }

        @Override
        public void setRate(double rateHz) {
            checkRate(rateHz);
            synchronized (TelemetryManager.this) {
                if (stopped || (rateHz == rate && task != null)) {
                    return;
                }
                if (task != null) {
                    task.cancel(false);
                    task = null;
                }
                rate = rateHz;
                period = rateHz == 0 ? 0 : Math.round(1e9 / rateHz);
                if (period > 0) {
                    long delay = Math.max(0, lastTick + period - System.nanoTime());
                    task = on.scheduleAtFixedRate(this::tick, delay, period, TimeUnit.NANOSECONDS);
                }
            }
        }

        @Override
        public void stop() {
            synchronized (TelemetryManager.this) {
                if (stopped) {
                    return;
                }
                stopped = true;
                if (task != null) {
                    task.cancel(false);
                }
                if (activePublications.decrementAndGet() == 0 && scheduler != null) {
                    scheduler.shutdown();
                    scheduler = null;
                }
            }
        }
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

    /**
     * Publishes one value to the resource's PEP node now, without waiting for the server's acknowledgement. The node's
     * first publication carries the publish-options; values published before the server has answered it follow it
     * once it has, in order.
     */
    public <T> void publishNow(Resource<T, ?> resource, T value) {
        String node = ControlMl.telemetryNode(resource.name());
        // The options are needed only until the server has created the node with them: checking them costs the
        // server a data-form comparison on every publication.
        if (publishWithoutOptions.contains(node)) {
            sendPublication(node, element(resource, value), false);
            return;
        }
        synchronized (heldBack) {
            ControlMlElement element = element(resource, value); // its id after those of the values held back
            if (publishWithoutOptions.contains(node)) {
                sendPublication(node, element, false);
            } else if (heldBack.containsKey(node)) {
                heldBack.get(node).add(element);
            } else {
                heldBack.put(node, new ArrayList<>());
                sendPublication(node, element, true);
            }
        }
    }

    private <T> ControlMlElement element(Resource<T, ?> resource, T value) {
        return ControlMlElement.result(controlMl.nextId(), resource.name(), resource.codec().encode(value))
                .withTextForm(controlMl.isTextForm());
    }

    /**
     * The node's first publication was answered: taken with the options ({@code refusedFirst} null), or refused for
     * them ({@code refusedFirst}, sent again without). Then the values held back, and from now on every value at once.
     */
    private void firstPublicationAnswered(String node, ControlMlElement refusedFirst) {
        synchronized (heldBack) {
            if (refusedFirst != null) {
                sendPublication(node, refusedFirst, false);
            }
            for (ControlMlElement e : heldBack.getOrDefault(node, List.of())) {
                sendPublication(node, e, false);
            }
            heldBack.remove(node);
            publishWithoutOptions.add(node);
        }
    }

    /** The node's first publication failed without an answer on its options: the next value held back tries them. */
    private void firstPublicationFailed(String node) {
        synchronized (heldBack) {
            List<ControlMlElement> held = heldBack.remove(node);
            if (held != null && !held.isEmpty()) {
                heldBack.put(node, held);
                sendPublication(node, held.remove(0), true);
            }
        }
    }

    private void sendPublication(String node, ControlMlElement element, boolean withOptions) {
        PubSub publish = PubSub.createPubsubPacket(null, IQ.Type.set, new PublishItem<>(node, new PayloadItem<>(
                "current", element)));
        if (withOptions) {
            publish.addExtension(TELEMETRY_PUBLISH_OPTIONS);
        }
        try {
            connection().sendIqRequestAsync(publish).onSuccess(r -> {
                published.incrementAndGet();
                if (withOptions) {
                    firstPublicationAnswered(node, null); // the node exists with the options now
                }
            }).onError(
                    e -> {
                        if (withOptions && e instanceof XMPPErrorException x) {
                            // e.g. ejabberd 23.01 refuses these publish-options on an auto-created PEP node
                            // (resource-constraint): publish with the server's defaults from now on, this item first
                            LOG.info("server refused telemetry publish-options on {} ({}); publishing with its"
                                    + " defaults", node, x.getStanzaError().getCondition());
                            firstPublicationAnswered(node, element);
                            return;
                        }
                        failed.incrementAndGet();
                        LOG.debug("telemetry publication failed", e);
                        if (withOptions) {
                            firstPublicationFailed(node);
                        }
                    });
        } catch (RuntimeException e) {
            failed.incrementAndGet();
            if (withOptions) {
                firstPublicationFailed(node);
            }
        }
    }

    /**
     * Subscribes this client explicitly (XEP-0060 {@code subscribe}) to a device's telemetry node of a resource, so
     * that its publications arrive at {@link #addListener listeners} even where the server does not honour
     * the {@code +notify} of the entity capabilities (ejabberd 23.01 now and then never does for a contact, Prosody
     * 0.12 more rarely, while both always deliver to explicit subscribers). Servers keep one subscription per JID, so
     * calling again does no harm. The node exists once the device has published the resource: before that the answer
     * is {@code item-not-found}; call again when the device comes online or publishes.
     *
     * @param device the device's bare JID (the owner of the PEP node)
     * @return done, or why not ({@code item-not-found}, {@code forbidden} without a presence subscription, timeout,
     *         not connected)
     */
    public Outcome<Void> follow(EntityBareJid device, Resource<?, ?> resource) {
        return pubsubRequest(device, new SubscribeExtension(connection().getUser(), ControlMl.telemetryNode(resource
                .name())));
    }

    /** Ends a subscription made by {@link #follow}; same answers. */
    public Outcome<Void> unfollow(EntityBareJid device, Resource<?, ?> resource) {
        return pubsubRequest(device, new UnsubscribeExtension(connection().getUser().toString(), ControlMl
                .telemetryNode(resource.name())));
    }

    private Outcome<Void> pubsubRequest(EntityBareJid device, NodeExtension request) {
        // a plain request to the owner's PEP service: Smack's PubSubManager.getLeafNode() asks disco#info first, and
        // ejabberd answers it for an auto-created PEP node without the identity Smack insists on
        PubSub iq = PubSub.createPubsubPacket(device, IQ.Type.set, request);
        IQ answer;
        try (StanzaCollector collector = connection().createStanzaCollectorAndSend(iq)) {
            answer = collector.nextResult(controlMl.requestTimeout().toMillis());
        } catch (NotConnectedException e) {
            return Outcome.failure(ControlMlCondition.NOT_CONNECTED, "not connected: " + e.getMessage());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return Outcome.failure(ControlMlCondition.TIMEOUT, "interrupted while waiting for " + device);
        }
        if (answer == null) {
            return Outcome.failure(ControlMlCondition.TIMEOUT, "no answer from the PEP service of " + device
                    + " within " + controlMl.requestTimeout().toMillis() + " ms");
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
     * delivery that does not depend on it, also {@link #follow} each device. Listeners are called in arrival order on
     * the connection's listener thread (a Smack synchronous stanza listener), one item after another: hand long work
     * off.
     */
    public <T> void addListener(Resource<T, ?> resource, TelemetryListener<T> listener) {
        String node = ControlMl.telemetryNode(resource.name());
        Map<EntityBareJid, RequestId> lastAccepted = new ConcurrentHashMap<>();
        itemHandlers.computeIfAbsent(node, n -> new CopyOnWriteArrayList<>()).add((from, element) -> accept(resource,
                listener, lastAccepted, from, element));
        ServiceDiscoveryManager.getInstanceFor(connection()).addFeature(node + PLUS_NOTIFY);
    }

    /** A PEP event: its ControlML items to the handlers of its node, if any. */
    private void onPepEvent(Stanza stanza) {
        if (!(EventElement.from(stanza).getEvent() instanceof ItemsExtension items)) {
            return;
        }
        List<BiConsumer<EntityBareJid, ControlMlElement>> handlers = itemHandlers.get(items.getNode());
        if (handlers == null) {
            return;
        }
        EntityBareJid from = stanza.getFrom().asEntityBareJidIfPossible();
        for (NamedElement item : items.getItems()) {
            if (item instanceof PayloadItem<?> payloadItem
                    && payloadItem.getPayload() instanceof ControlMlElement element) {
                for (BiConsumer<EntityBareJid, ControlMlElement> h : handlers) {
                    try {
                        h.accept(from, element);
                    } catch (RuntimeException e) {
                        // one failing listener must not cost the others (or this event's next items) their telemetry
                        LOG.warn("telemetry listener failed on {} from {}", items.getNode(), from, e);
                    }
                }
            }
        }
    }

    /** One telemetry item of {@code resource} from {@code from}: checked, deduplicated, decoded and passed on. */
    private <T> void accept(Resource<T, ?> resource, TelemetryListener<T> listener,
            Map<EntityBareJid, RequestId> lastAccepted, EntityBareJid from, ControlMlElement element) {
        if (element.defect() != null || element.payload() == null || !resource.name().equals(element.res())) {
            rejected.incrementAndGet();
            LOG.debug("rejected telemetry {} from {}", element, from);
            return;
        }
        if (!isNewer(lastAccepted, from, element.id())) {
            // the same item again (e.g. Prosody 0.12 delivers it for +notify and for the explicit subscription) or
            // an older one overtaken: section 6's rule, by the publication's id
            LOG.trace("duplicate telemetry {} from {}", element, from);
            return;
        }
        T value;
        try {
            value = element.value(resource);
        } catch (PayloadException e) {
            rejected.incrementAndGet();
            LOG.debug("rejected telemetry from {}: {}", from, e.getMessage());
            return;
        }
        received.incrementAndGet();
        listener.onTelemetry(from, value);
    }
}
