package sabot.controlml.payload;

import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Objects;
import java.util.Set;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.swe.SweComponent;

/**
 * {@code cm.telemetry} (section 6 of {@code docs/CONTROLML.md}, "Leases"): telemetry rates. The same record is a
 * get's answer (the rate each resource is published at now; {@code lease}: the longest lease the device grants), a
 * lease (the rates a watcher asks for, for {@code lease} seconds; 0 ends its lease) and the lease's answer (what the
 * device granted).
 *
 * @param lease   seconds, 0..{@value #MAX_LEASE_S}
 * @param streams one rate per telemetry resource, each resource once, at most {@value #MAX_STREAMS}
 */
public record TelemetryRates(double lease, List<StreamRate> streams) {

    /** Longest lease a payload can carry (a device grants at most its own limit). */
    public static final double MAX_LEASE_S = 3600;
    /** Highest rate a payload can carry (the Metatype's limit for a device's telemetry rates). */
    public static final double MAX_RATE_HZ = 100;
    /** Most streams in one record. */
    public static final int MAX_STREAMS = 16;

    public TelemetryRates {
        streams = List.copyOf(streams);
        if (!(lease >= 0 && lease <= MAX_LEASE_S)) {
            throw new IllegalArgumentException("lease must be 0.." + MAX_LEASE_S + " s, was " + lease);
        }
        if (streams.size() > MAX_STREAMS) {
            throw new IllegalArgumentException("at most " + MAX_STREAMS + " streams, were " + streams.size());
        }
        Set<String> seen = new HashSet<>();
        for (StreamRate s : streams) {
            if (!seen.add(s.resource())) {
                throw new IllegalArgumentException(s.resource() + " appears twice");
            }
        }
    }

    /** @return the stream of a resource, or null */
    public StreamRate stream(String resource) {
        return streams.stream().filter(s -> s.resource().equals(resource)).findFirst().orElse(null);
    }

    /**
     * One resource's telemetry rate.
     *
     * @param resource a resource name of section 1's syntax, e.g. {@code cm.position}
     * @param rate     publications per second, 0..{@value TelemetryRates#MAX_RATE_HZ}
     */
    public record StreamRate(String resource, double rate) {
        public StreamRate {
            Objects.requireNonNull(resource, "resource");
            if (!ControlMlElement.RESOURCE_SYNTAX.matcher(resource).matches()) {
                throw new IllegalArgumentException("not a resource name: " + resource);
            }
            if (!(rate >= 0 && rate <= MAX_RATE_HZ)) {
                throw new IllegalArgumentException(resource + ": rate must be 0.." + MAX_RATE_HZ + " Hz, was " + rate);
            }
        }
    }

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<TelemetryRates> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(TelemetryRates t) {
            RecordBuilder b = new RecordBuilder().quantity("lease", "s", t.lease()).count("count", t.streams()
                    .size());
            int i = 0;
            for (StreamRate s : t.streams()) {
                b.add("stream" + i++, new RecordBuilder().text("resource", s.resource()).quantity("rate", "Hz", s
                        .rate()).build());
            }
            return b.build();
        }

        @Override
        public TelemetryRates decode(SweComponent payload) throws PayloadException {
            String[] indexed = RecordReader.indexedFields(payload, "stream", MAX_STREAMS);
            String[] names = new String[indexed.length + 1];
            names[0] = "lease";
            System.arraycopy(indexed, 0, names, 1, indexed.length);
            RecordReader r = RecordReader.of(payload, names);
            double lease = r.quantity("lease", "s", 0, MAX_LEASE_S);
            List<StreamRate> streams = new ArrayList<>();
            Set<String> seen = new HashSet<>();
            for (int i = 2; i < names.length; i++) {
                RecordReader s = r.record(names[i], "resource", "rate");
                String resource = s.text("resource", 160);
                if (!ControlMlElement.RESOURCE_SYNTAX.matcher(resource).matches()) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, names[i] + ".resource '" + resource
                            + "' is not a resource name");
                }
                if (!seen.add(resource)) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, names[i] + ".resource " + resource
                            + " appears twice");
                }
                streams.add(new StreamRate(resource, s.quantity("rate", "Hz", 0, MAX_RATE_HZ)));
            }
            return new TelemetryRates(lease, streams);
        }
    };
}
