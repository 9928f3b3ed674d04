package sabot.controlml.bench;

import java.io.IOException;
import java.lang.management.ManagementFactory;
import java.time.Instant;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;

import org.jivesoftware.smack.SmackConfiguration;
import org.jivesoftware.smack.StanzaCollector;
import org.jivesoftware.smack.iqrequest.AbstractIqRequestHandler;
import org.jivesoftware.smack.iqrequest.IQRequestHandler.Mode;
import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.IqData;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.provider.IqProvider;
import org.jivesoftware.smack.provider.ProviderManager;
import org.jivesoftware.smack.roster.AbstractPresenceEventListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.SubscribeListener.SubscribeAnswer;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smack.util.PacketParserUtils;
import org.jivesoftware.smack.xml.SmackXmlParser;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.FullJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMl;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.RequestId;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.TelemetryManager;
import sabot.controlml.TelemetryPublication;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * {@code ./sabot bench controlml}: starts its own private Prosody (or ejabberd) and measures
 * <ol>
 * <li>the round trip of a {@code cm.position} get between two clients, beside a raw XMPP IQ between the same two
 * clients, requests alternating so that both see the same server and machine state; and</li>
 * <li>telemetry: N robots publishing {@code cm.position} to their PEP nodes at R Hz into S subscribed workbenches
 * for D seconds: delivered percentage, latency percentiles, server CPU.</li>
 * </ol>
 * The server runs on a CPU of its own and the clients (this JVM) on the others ({@link CpuLayout}; {@code
 * --shared-cpus} leaves all on all CPUs); the JSON's {@code cpu_layout} says which. The last line printed is one JSON
 * object with the figures.
 */
public final class ControlMlBench {

    private static final String ECHO_NS = "urn:sabot:bench:echo";

    private int requests = 10_000;
    private int warmup = 1_000;
    private PrivateXmppServer.Kind kind = PrivateXmppServer.Kind.PROSODY;
    private int robots = 100;
    private int subscribers = 2;
    private double rateHz = 10;
    private int durationS = 60;
    private boolean telemetry = true;
    private boolean textForm = true;
    private boolean sharedCpus = false;
    /** {@code --tls}: only the cost of TLS and SCRAM ({@link TlsCost}). */
    private boolean tlsCost = false;
    private int logins = 200;

    public static void main(String[] args) throws Exception {
        ControlMlBench bench = new ControlMlBench();
        bench.parse(args);
        System.exit(bench.run());
    }

    private void parse(String[] args) {
        for (int i = 0; i < args.length; i++) {
            String a = args[i];
            switch (a) {
                case "--requests" -> requests = Integer.parseInt(args[++i]);
                case "--warmup" -> warmup = Integer.parseInt(args[++i]);
                case "--server" -> kind = PrivateXmppServer.Kind.valueOf(args[++i].toUpperCase(Locale.ROOT));
                case "--robots" -> robots = Integer.parseInt(args[++i]);
                case "--subscribers" -> subscribers = Integer.parseInt(args[++i]);
                case "--rate" -> rateHz = Double.parseDouble(args[++i]);
                case "--duration" -> durationS = Integer.parseInt(args[++i]);
                case "--no-telemetry" -> telemetry = false;
                case "--xml-form" -> textForm = false;
                case "--shared-cpus" -> sharedCpus = true;
                case "--tls" -> tlsCost = true;
                case "--logins" -> logins = Integer.parseInt(args[++i]);
                case "--help", "-h" -> {
                    System.out.println("usage: ./sabot bench controlml [--requests N (10000)] [--warmup N (1000)] "
                            + "[--server prosody|ejabberd] [--robots N (100)] [--subscribers N (2)] "
                            + "[--rate HZ (10)] [--duration S (60)] [--no-telemetry] [--xml-form] [--shared-cpus]\n"
                            + "       ./sabot bench controlml --tls [--server prosody|ejabberd] [--requests N (10000)] "
                            + "[--logins N (200)] [--robots N (100)]: what TLS and SCRAM cost (TlsCost)");
                    System.exit(0);
                }
                default -> throw new IllegalArgumentException("unknown option " + a + " (--help)");
            }
        }
    }

    private int run() throws Exception {
        // one parser factory for all connections, instead of a ServiceLoader lookup per parser
        SmackXmlParser.setXmlPullParserFactory(SmackXmlParser.getXmlPullParserFactory());
        SmackConfiguration.setDefaultReplyTimeout(20_000);
        XMPPTCPConnection.setUseStreamManagementDefault(false); // measure the protocol, not the ack traffic
        if (System.getProperty("sabot.root") == null && System.getenv("SABOT_ROOT") != null) {
            System.setProperty("sabot.root", System.getenv("SABOT_ROOT"));
        }
        Map<String, Object> figures = new java.util.LinkedHashMap<>();
        figures.put("server", kind.name().toLowerCase(Locale.ROOT));
        if (tlsCost) {
            new TlsCost(kind, requests, warmup, logins, robots).run(figures);
            printJson(figures);
            return 0;
        }
        try (PrivateXmppServer server = PrivateXmppServer.of(kind).start()) {
            figures.put("server_ready_ms", server.startupTime().toMillis());
            CpuLayout cpus = sharedCpus ? CpuLayout.shared("--shared-cpus") : CpuLayout.split(server.pid());
            System.out.println("[bench] CPUs: " + cpus.description());
            figures.put("cpu_layout", cpus.description());
            roundTrips(server, figures);
            if (telemetry) {
                telemetry(server, figures);
            }
        }
        printJson(figures);
        return 0;
    }

    static void printJson(Map<String, Object> figures) {
        StringBuilder json = new StringBuilder("{");
        figures.forEach((k, v) -> json.append(json.length() > 1 ? ", " : "").append('"').append(k).append("\": ")
                .append(v instanceof String s ? "\"" + s + "\"" : v));
        System.out.println(json.append('}'));
    }

    // ------------------------------------------------------------------------------------------------ round trips

    /** The raw IQ: an empty child element that the responder answers with an empty result. */
    static final class EchoIQ extends IQ {
        EchoIQ() {
            super("echo", ECHO_NS);
        }

        EchoIQ(IqData data) {
            super(data, "echo", ECHO_NS);
        }

        @Override
        protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
            xml.setEmptyElement();
            return xml;
        }
    }

    /** A result carrying pre-serialised XML: the raw IQ with the same bytes as a cm.position result. */
    static final class PayloadIQ extends IQ {
        private final String payload;

        PayloadIQ(String payload) {
            super("echo", ECHO_NS);
            this.payload = payload;
        }

        @Override
        protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
            xml.rightAngleBracket();
            xml.append(payload);
            return xml;
        }
    }

    /** Namespace of {@link ShapedIQ}: one that no ControlML provider reads. */
    static final String SHAPE_NS = "urn:sabot:bench:shape";

    /**
     * A raw IQ with ControlML's shape: a {@code control-ml} child with the same three attributes (and, in the result,
     * the same payload bytes) in a namespace of its own, read and answered without any ControlML code. The breakdown
     * of what the protocol's shape costs the server against what ControlML's code costs the clients.
     */
    static final class ShapedIQ extends IQ {
        private final String cmType;
        private final String payload;

        ShapedIQ(String cmType, String payload) {
            super(ControlMl.ELEMENT, SHAPE_NS);
            this.cmType = cmType;
            this.payload = payload;
        }

        @Override
        protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
            xml.attribute("type", cmType).attribute("id", "20261121:1").attribute("res", Resources.POSITION.name());
            if (payload == null) {
                xml.setEmptyElement();
            } else {
                xml.rightAngleBracket();
                xml.append(payload);
            }
            return xml;
        }
    }

    private void roundTrips(PrivateXmppServer server, Map<String, Object> figures) throws Exception {
        ProviderManager.addIQProvider(ControlMl.ELEMENT, SHAPE_NS, new IqProvider<ShapedIQ>() {
            @Override
            public ShapedIQ parse(XmlPullParser parser, int initialDepth, IqData iqData, XmlEnvironment env)
                    throws IOException, XmlPullParserException {
                PacketParserUtils.parseElement(parser); // read like any unknown element, into a string
                return new ShapedIQ(null, null);
            }
        });
        ProviderManager.addIQProvider("echo", ECHO_NS, new IqProvider<EchoIQ>() {
            @Override
            public EchoIQ parse(XmlPullParser parser, int initialDepth, IqData iqData, XmlEnvironment env) {
                return new EchoIQ(iqData);
            }
        });
        XMPPTCPConnection workbench = server.login("bench-wb");
        XMPPTCPConnection robot = server.login("bench-robot");
        robot.registerIQRequestHandler(new AbstractIqRequestHandler("echo", ECHO_NS, IQ.Type.get, Mode.sync) {
            @Override
            public IQ handleIQRequest(IQ request) {
                return IQ.createResultIQ(request);
            }
        });
        PoseEstimate pose = new PoseEstimate(Instant.parse("2026-11-21T10:15:30.123456Z"), new Pose2D(1.25, -3.5,
                0.785), new PoseCovariance(0.01, 0.001, -0.0002, 0.02, 0.0003, 0.0004));
        // the payload exactly as a cm.position result carries it, as opaque XML, for the breakdown (raw with payload)
        String sizedXml = ControlMlElement.result(RequestId.parse("20261121:1"), Resources.POSITION.name(),
                Resources.POSITION.codec().encode(pose)).withTextForm(textForm).contentXml();
        robot.registerIQRequestHandler(new AbstractIqRequestHandler("echo", ECHO_NS, IQ.Type.set, Mode.sync) {
            @Override
            public IQ handleIQRequest(IQ request) {
                PayloadIQ r = new PayloadIQ(sizedXml);
                r.setType(IQ.Type.result);
                return r;
            }
        });
        robot.registerIQRequestHandler(new AbstractIqRequestHandler(ControlMl.ELEMENT, SHAPE_NS, IQ.Type.get,
                Mode.sync) {
            @Override
            public IQ handleIQRequest(IQ request) {
                ShapedIQ r = new ShapedIQ("result", sizedXml);
                r.setType(IQ.Type.result);
                return r;
            }
        });
        ControlMlManager robotCm = ControlMlManager.getInstanceFor(robot);
        robotCm.setAccessPolicy(j -> j.asBareJid().equals(workbench.getUser().asBareJid()) ? Role.MAINTAINER
                : Role.NONE);
        robotCm.setTextForm(textForm);
        robotCm.onGet(Resources.POSITION, (r, q) -> Outcome.success(pose));
        ControlMlManager client = ControlMlManager.getInstanceFor(workbench);
        FullJid robotJid = robot.getUser();

        long[] raw = new long[requests];
        long[] sizedRaw = new long[requests];
        long[] cm = new long[requests];
        System.out.printf("[bench] %s: %d warm-up + %d requests each, raw IQ, cm.position get and same-payload raw IQ"
                + " in rotating order%n",
                kind.name().toLowerCase(Locale.ROOT), warmup, requests);
        long t0 = System.nanoTime();
        for (int i = -warmup; i < requests; i++) {
            // the three kinds take turns at each position of the triple: a request right after another may pay for
            // what the previous one left behind (scheduling, a server's event loop), and no kind should always pay
            int rotation = Math.floorMod(i, 3);
            for (int k = 0; k < 3; k++) {
                int kind = (k + rotation) % 3;
                long start = System.nanoTime();
                if (kind == 0) {
                    EchoIQ echo = new EchoIQ();
                    echo.setTo(robotJid);
                    echo.setStanzaId();
                    try (StanzaCollector c = workbench.createStanzaCollectorAndSend(echo)) {
                        c.nextResultOrThrow();
                    }
                } else if (kind == 1) {
                    Outcome<PoseEstimate> got = client.get(robotJid, Resources.POSITION);
                    if (!got.isSuccess() || !pose.equals(got.orElseThrow())) {
                        throw new IllegalStateException("cm.position get failed: " + got);
                    }
                } else {
                    EchoIQ sizedEcho = new EchoIQ();
                    sizedEcho.setType(IQ.Type.set);
                    sizedEcho.setTo(robotJid);
                    sizedEcho.setStanzaId();
                    try (StanzaCollector c = workbench.createStanzaCollectorAndSend(sizedEcho)) {
                        c.nextResultOrThrow();
                    }
                }
                long elapsed = System.nanoTime() - start;
                if (i >= 0) {
                    (kind == 0 ? raw : kind == 1 ? cm : sizedRaw)[i] = elapsed;
                }
            }
        }
        double seconds = (System.nanoTime() - t0) / 1e9;
        Arrays.sort(raw);
        Arrays.sort(cm);
        Arrays.sort(sizedRaw);
        System.out.printf("[bench] raw IQ         p50 %.3f ms  p90 %.3f ms  p99 %.3f ms  max %.3f ms%n", ms(raw, 0.5),
                ms(raw, 0.9), ms(raw, 0.99), raw[raw.length - 1] / 1e6);
        System.out.printf("[bench] raw IQ, %d B result p50 %.3f ms  p90 %.3f ms  p99 %.3f ms  (breakdown: payload size "
                + "alone)%n", sizedXml.length(), ms(sizedRaw, 0.5), ms(sizedRaw, 0.9), ms(sizedRaw, 0.99));
        System.out.printf("[bench] cm.position get p50 %.3f ms  p90 %.3f ms  p99 %.3f ms  max %.3f ms%n", ms(cm, 0.5),
                ms(cm, 0.9), ms(cm, 0.99), cm[cm.length - 1] / 1e6);
        System.out.printf("[bench] ratio p50 %.2f, p99 %.2f (%d + %d requests in %.1f s)%n", ms(cm, 0.5) / ms(raw, 0.5),
                ms(cm, 0.99) / ms(raw, 0.99), requests + warmup, requests + warmup, seconds);
        figures.put("requests", requests);
        figures.put("raw_iq_p50_ms", round(ms(raw, 0.5)));
        figures.put("raw_iq_p99_ms", round(ms(raw, 0.99)));
        figures.put("controlml_p50_ms", round(ms(cm, 0.5)));
        figures.put("controlml_p99_ms", round(ms(cm, 0.99)));
        figures.put("controlml_to_raw_p50", round(ms(cm, 0.5) / ms(raw, 0.5)));
        figures.put("raw_iq_sized_p50_ms", round(ms(sizedRaw, 0.5)));
        figures.put("payload_form", textForm ? "text" : "xml");
        figures.put("payload_bytes", sizedXml.length());
        shapeBreakdown(workbench, robotJid, figures);
        workbench.disconnect();
        robot.disconnect();
    }

    /**
     * A second pass, apart so that the main comparison keeps its mix of requests (how requests are interleaved moves
     * the ratio by up to 0.1 on this VM): raw IQs and {@link ShapedIQ}s in turn, their ratio the share of the
     * protocol's shape (attributes, payload) in the ratio above, without any ControlML code.
     */
    private void shapeBreakdown(XMPPTCPConnection workbench, FullJid robotJid, Map<String, Object> figures)
            throws Exception {
        long[] raw = new long[requests];
        long[] shaped = new long[requests];
        for (int i = -warmup; i < requests; i++) {
            for (int k = 0; k < 2; k++) {
                boolean shape = (i + k) % 2 == 0;
                IQ request = shape ? new ShapedIQ("get", null) : new EchoIQ();
                request.setTo(robotJid);
                request.setStanzaId();
                long start = System.nanoTime();
                try (StanzaCollector c = workbench.createStanzaCollectorAndSend(request)) {
                    c.nextResultOrThrow();
                }
                if (i >= 0) {
                    (shape ? shaped : raw)[i] = System.nanoTime() - start;
                }
            }
        }
        Arrays.sort(raw);
        Arrays.sort(shaped);
        System.out.printf("[bench] breakdown pass: raw IQ p50 %.3f ms, raw IQ shaped as control-ml (same attributes and"
                + " result bytes, no ControlML code) p50 %.3f ms, ratio %.2f: the protocol's shape alone%n",
                ms(raw, 0.5), ms(shaped, 0.5), ms(shaped, 0.5) / ms(raw, 0.5));
        figures.put("shape_pass_raw_iq_p50_ms", round(ms(raw, 0.5)));
        figures.put("shape_pass_shaped_p50_ms", round(ms(shaped, 0.5)));
        figures.put("shaped_to_raw_p50", round(ms(shaped, 0.5) / ms(raw, 0.5)));
    }

    /** @return quantile {@code q} of sorted nanoseconds, in ms */
    static double ms(long[] sorted, double q) {
        int i = (int) Math.min(sorted.length - 1, Math.ceil(q * sorted.length) - 1);
        return sorted[Math.max(0, i)] / 1e6;
    }

    /** @return {@code v} to three decimals (the JSON's figures) */
    static double round(double v) {
        return Math.round(v * 1000) / 1000.0;
    }

    // ------------------------------------------------------------------------------------------------ telemetry

    private void telemetry(PrivateXmppServer server, Map<String, Object> figures) throws Exception {
        TelemetryRun.Result r = TelemetryRun.run(server, new TelemetryRun.Options(robots, subscribers, rateHz,
                durationS, textForm, 1, 1, false), Map.of("server", server.pid()));
        long[] lat = r.latenciesNs();
        System.out.printf("[bench] telemetry: offered %d items x %d subscribers = %d, delivered %d (%.2f %%), "
                + "publish failures %d%n", r.sent(), subscribers, r.expected(), r.delivered(), 100.0 * r.delivered()
                        / Math.max(1, r.expected()), r.failed());
        if (lat.length > 0) {
            System.out.printf("[bench] telemetry latency p50 %.3f ms  p90 %.3f ms  p99 %.3f ms  max %.3f ms%n", ms(lat,
                    0.5), ms(lat, 0.9), ms(lat, 0.99), lat[lat.length - 1] / 1e6);
        }
        double serverCpuPct = r.cpuPct().get("server");
        System.out.printf("[bench] CPU over the %.1f s window: server %.1f %% of one core, benchmark JVM (all %d "
                + "clients) %.1f %%%n", r.wallS(), serverCpuPct, robots + subscribers, r.clientCpuPct());
        figures.put("telemetry_robots", robots);
        figures.put("telemetry_subscribers", subscribers);
        figures.put("telemetry_rate_hz", rateHz);
        figures.put("telemetry_duration_s", durationS);
        figures.put("telemetry_expected", r.expected());
        figures.put("telemetry_delivered", r.delivered());
        figures.put("telemetry_delivered_pct", round(100.0 * r.delivered() / Math.max(1, r.expected())));
        figures.put("telemetry_p50_ms", lat.length == 0 ? "null" : round(ms(lat, 0.5)));
        figures.put("telemetry_p99_ms", lat.length == 0 ? "null" : round(ms(lat, 0.99)));
        figures.put("server_cpu_pct", round(serverCpuPct));
        figures.put("client_cpu_pct", round(r.clientCpuPct()));
    }
}
