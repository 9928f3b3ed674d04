package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import java.io.StringReader;
import java.time.Clock;
import java.time.Instant;
import java.time.LocalDate;
import java.time.ZoneOffset;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import javax.xml.parsers.SAXParserFactory;

import org.jivesoftware.smack.packet.Message;
import org.jivesoftware.smack.packet.Stanza;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.junit.jupiter.api.Test;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.xml.sax.InputSource;

import sabot.controlml.AccessPolicy;
import sabot.controlml.Carrier;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlIQ;
import sabot.controlml.ControlMlType;
import sabot.controlml.RequestId;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.internal.Endpoint;
import sabot.controlml.payload.PayloadCodec;

/**
 * Feeds 100,000 mutated ControlML stanzas (fixed seed) through Smack's parser with ControlML's providers and then
 * through the endpoint with handlers for every resource. Nothing may escape: a stanza is either rejected by the XML
 * layer (an XmlPullParserException, or not well-formed for the JDK's SAX parser), or refused by Smack's own stanza
 * parser without any ControlML frame on the stack, or it yields an element and an answer.
 */
class ControlMlFuzzTest {

    private static final long SEED = 20261121L;
    private static final int STANZAS = 100_000;
    private static final String[] TOKENS = { "<", ">", "/>", "'", "\"", "&amp;", "&lt;", "NaN", "INF", "-1", "1e309",
        "0x10", "cm.", "::", "=", " ", "xmlns='urn:x'", "<field name='x'>", "</field>", "<Quantity>", "<uom code='s'/>",
        "<value>", "</value>", "type='get'", "type='result'", "id='20261121:1'", "res='cm.teleport'", "4294967296",
        "<DataRecord xmlns='http://www.opengis.net/swe/2.0'>", "</DataRecord>", "<failure condition='x' reason='y'/>",
        "\u00e9", "<!-- c -->", "<![CDATA[1]]>" };

    @Test
    void hundredThousandMutatedStanzasNeverThrowOutOfProvidersOrHandlers() throws Exception {
        Random random = new Random(SEED);
        List<String> seeds = seeds();
        Endpoint endpoint = RecordingDevice.endpoint(Clock.fixed(Instant.parse("2026-11-21T12:00:00Z"),
                ZoneOffset.UTC), new RecordingDevice());
        endpoint.setAccessPolicy(AccessPolicy.OPEN);
        endpoint.setSchemaValidation(false); // the XSD is exercised by the round-trip tests; keep this loop fast
        Jid from = JidCreate.from("fuzzer@sabot.local/f");
        SAXParserFactory sax = SAXParserFactory.newInstance();
        sax.setNamespaceAware(true);

        int notWellFormed = 0;
        int smackRejected = 0;
        int answered = 0;
        int defects = 0;
        long t0 = System.nanoTime();
        for (int i = 0; i < STANZAS; i++) {
            String seed = seeds.get(random.nextInt(seeds.size()));
            boolean asMessage = (i & 3) == 0;
            String body = mutate(seed, random);
            String stanza = asMessage ? "<message xmlns='jabber:client' from='fuzzer@sabot.local/f' type='normal'>"
                    + body + "</message>" : "<iq xmlns='jabber:client' from='fuzzer@sabot.local/f' type='set' id='f"
                            + i + "'>" + body + "</iq>";
            Stanza parsed;
            try {
                parsed = Xml.stanza(stanza);
            } catch (Exception e) {
                if (e instanceof org.jivesoftware.smack.xml.XmlPullParserException || !wellFormed(sax, stanza)) {
                    // the XML layer's business (XPP3 is stricter about namespaces than the JDK's SAX parser): a
                    // server closes such a stream before any stanza reaches a provider
                    notWellFormed++;
                    continue;
                }
                if (thrownByControlMl(e)) {
                    fail("a ControlML provider threw " + e + " on well-formed XML:\n" + stanza);
                }
                smackRejected++; // e.g. an <iq type='set'/> without child element: Smack's own parser gives up
                continue;
            }
            ControlMlElement element = parsed instanceof ControlMlIQ iq ? iq.element() : parsed instanceof Message m ? m
                    .getExtension(ControlMlElement.class) : null;
            if (element == null) {
                continue; // mutated out of the control-ml namespace: not ours
            }
            if (element.defect() != null) {
                defects++;
            }
            ControlMlType carrierType = asMessage ? element.type() : ControlMlType.SET;
            if (carrierType == null || !carrierType.isRequest()) {
                continue; // an answer, not a request: the manager logs and drops these
            }
            Endpoint.Answer answer = endpoint.serve(element, carrierType, from, null, asMessage ? Carrier.MESSAGE
                    : Carrier.IQ);
            assertNotNull(answer);
            assertTrue(answer.element() != null || answer.bareError() != null);
            if (answer.element() != null && (i % 8) == 1) {
                // what we answer must itself parse back to the same element (checked on every eighth answer)
                String xml = answer.element().toXML(XmlEnvironment.EMPTY).toString();
                assertEquals(answer.element(), Xml.element(xml), xml);
            }
            answered++;
        }
        double seconds = (System.nanoTime() - t0) / 1e9;
        System.out.printf("[fuzz] %d stanzas in %.1f s: %d not well-formed, %d refused by Smack's stanza parser, "
                + "%d answered, %d defective elements%n", STANZAS, seconds, notWellFormed, smackRejected, answered,
                defects);
        assertTrue(answered > STANZAS / 4, "the mutations are too destructive to test the handlers");
        assertTrue(defects > STANZAS / 10, "the mutations rarely produce bad ControlML");
    }

    /** True when the exception comes out of ControlML's own code (providers, SWE reader), not Smack's. */
    private static boolean thrownByControlMl(Throwable e) {
        for (Throwable t = e; t != null; t = t.getCause()) {
            for (StackTraceElement f : t.getStackTrace()) {
                if (f.getClassName().startsWith("sabot.controlml.") && !f.getClassName().startsWith(
                        "sabot.controlml.tests.")) {
                    return true;
                }
            }
        }
        return false;
    }

    private static boolean wellFormed(SAXParserFactory sax, String xml) {
        try {
            sax.newSAXParser().parse(new InputSource(new StringReader(xml)), new org.xml.sax.helpers.DefaultHandler());
            return true;
        } catch (Exception e) {
            return false;
        }
    }

    private static final String[] VALUES = { "NaN", "INF", "-INF", "-1", "1e309", "", "abc", "1,5", "0x1p3", " 1 ",
        "99999999999999999999", "-0", "1.7976931348623157E308", "2026-13-45T00:00:00Z", "true", "maybe", "..", "0" };
    private static final String[] UNITS = { "m", "s", "deg", "furlong", "", "m/s", "rad2", "cm", "%", "1", "m s" };
    private static final String[] TYPES = { "get", "set", "result", "error", "put", "" };
    private static final String[] IDS = { "20261121:1", "2026-11-21:1", "20261121:4294967296", "20260230:5", "x",
        "20261121:007" };
    private static final String[] RES = { "cm.goal", "cm.position", "cm.teleport", "CM.X", "cm.fs.read", "cm.tasks",
        "cm.", "cm.pid" };
    private static final Pattern VALUE = Pattern.compile("<value>[^<]*</value>");
    private static final Pattern UOM = Pattern.compile("code='[^']*'");
    private static final Pattern ATTRIBUTE = Pattern.compile(" (type|id|res)='[^']*'");
    private static final Pattern SIMPLE_FIELD = Pattern.compile(
            "<field name='[^']*'><(Quantity|Count|Text|Category|Boolean|Time)>.*?</\\1></field>");
    private static final Pattern COMPONENT = Pattern.compile("<(Quantity|Count|Text|Category|Boolean)>(.*?)</\\1>");
    private static final String[] COMPONENTS = { "Quantity", "Count", "Text", "Category", "Boolean", "Time",
        "Vector" };

    /** Mostly structure-aware mutations that keep the XML well-formed, plus some raw character damage. */
    private static String mutate(String s, Random r) {
        String out = s;
        int mutations = 1 + r.nextInt(3);
        for (int m = 0; m < mutations; m++) {
            out = switch (r.nextInt(10)) {
                case 0 -> replaceOne(out, VALUE, r, g -> "<value>" + pick(VALUES, r) + "</value>");
                case 1 -> replaceOne(out, UOM, r, g -> "code='" + pick(UNITS, r) + "'");
                case 2 -> replaceOne(out, ATTRIBUTE, r, g -> " " + g.group(1) + "='" + pick(switch (g.group(1)) {
                    case "type" -> TYPES;
                    case "id" -> IDS;
                    default -> RES;
                }, r) + "'");
                case 3 -> replaceOne(out, ATTRIBUTE, r, g -> r.nextBoolean() ? "" : g.group() + " extra='1'");
                case 4 -> replaceOne(out, SIMPLE_FIELD, r, g -> "");
                case 5 -> replaceOne(out, SIMPLE_FIELD, r, g -> g.group() + g.group());
                case 6 -> replaceOne(out, COMPONENT, r, g -> {
                    String c = pick(COMPONENTS, r);
                    return "<" + c + ">" + g.group(2) + "</" + c + ">";
                });
                case 7 -> replaceOne(out, VALUE, r, g -> "<value>" + "7,".repeat(r.nextInt(50) == 0 ? 40_000 : 3)
                        + "</value>");
                default -> damage(out, r);
            };
        }
        return out;
    }

    private static String pick(String[] options, Random r) {
        return options[r.nextInt(options.length)];
    }

    private static String replaceOne(String s, Pattern p, Random r, java.util.function.Function<Matcher, String> f) {
        Matcher m = p.matcher(s);
        int[] starts = new int[64];
        int matches = 0;
        while (matches < starts.length && m.find()) {
            starts[matches++] = m.start();
        }
        if (matches == 0) {
            return damage(s, r);
        }
        m.find(starts[r.nextInt(matches)]);
        return s.substring(0, m.start()) + f.apply(m) + s.substring(m.end());
    }

    private static String damage(String s, Random r) {
        StringBuilder b = new StringBuilder(s);
        int at = r.nextInt(b.length());
        switch (r.nextInt(4)) {
            case 0 -> b.deleteCharAt(at);
            case 1 -> b.insert(at, TOKENS[r.nextInt(TOKENS.length)]);
            case 2 -> b.setCharAt(at, (char) (32 + r.nextInt(95)));
            default -> b.delete(at, Math.min(b.length(), at + 1 + r.nextInt(20)));
        }
        return b.toString();
    }

    private static List<String> seeds() {
        List<String> seeds = new ArrayList<>();
        RequestId id = new RequestId(LocalDate.of(2026, 11, 21), 1);
        for (Resource<?, ?> r : Resources.all()) {
            Object v = Samples.VALUES.get(r);
            if (r.isSettable()) {
                seeds.add(xml(ControlMlElement.request(ControlMlType.SET, id, r.name(), encode(r, v))));
            }
            if (r.isGettable()) {
                seeds.add(xml(ControlMlElement.request(ControlMlType.GET, id, r.name(), r.queryCodec() == null ? null
                        : Resources.FS_READ.queryCodec().encode(Samples.QUERY))));
                seeds.add(xml(ControlMlElement.result(id, r.name(), encode(r, v))));
            }
        }
        return seeds;
    }

    @SuppressWarnings("unchecked")
    private static <T> sabot.controlml.swe.SweComponent encode(Resource<T, ?> r, Object v) {
        return ((PayloadCodec<T>) r.codec()).encode((T) v);
    }

    private static String xml(ControlMlElement e) {
        return e.toXML(XmlEnvironment.EMPTY).toString();
    }
}
