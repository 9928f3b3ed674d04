package sabot.workbench.controlml.internal;

import java.util.EnumMap;
import java.util.Map;

import sabot.controlml.ControlMlCondition;
import sabot.workbench.fleet.TrafficStatistics;

/**
 * The workbench's counters of its traffic with one robot (plain Java: no OSGi, XMPP or SWT; every method takes the
 * monotonic time, so that a test drives it with a fixed clock). Threads: Smack's (stanzas, telemetry) and the request
 * pool's (requests) write, any thread reads a {@link #snapshot}.
 */
public final class RobotTraffic {

    private static final double NANOS_PER_MS = 1e6;
    private static final double NANOS_PER_S = 1e9;
    /** The round trips' window in slices of this many seconds (TrafficStatistics.ROUND_TRIP_WINDOW_S in all). */
    private static final int ROUND_TRIP_SLICE_S = 10;

    private final String robot;
    private final RateWindow in;
    private final RateWindow out;
    private final RateWindow telemetry;
    private final LatencyWindow roundTrips = new LatencyWindow(TrafficStatistics.ROUND_TRIP_WINDOW_S
            / ROUND_TRIP_SLICE_S, ROUND_TRIP_SLICE_S);
    private final Map<ControlMlCondition, Long> errors = new EnumMap<>(ControlMlCondition.class);
    private long requests;
    private long lastTelemetryNanos;
    private boolean anyTelemetry;

    /** @param startNanos when counting started ({@code System.nanoTime()} scale) */
    public RobotTraffic(String robot, long startNanos) {
        this.robot = robot;
        in = new RateWindow(TrafficStatistics.RATE_WINDOW_S, startNanos);
        out = new RateWindow(TrafficStatistics.RATE_WINDOW_S, startNanos);
        telemetry = new RateWindow(TrafficStatistics.RATE_WINDOW_S, startNanos);
    }

    /** A stanza from the robot, of {@code bytes} bytes. */
    public void received(long nanos, long bytes) {
        in.add(nanos, bytes);
    }

    /** A stanza to the robot, of {@code bytes} bytes. */
    public void sent(long nanos, long bytes) {
        out.add(nanos, bytes);
    }

    /** A telemetry item from the robot. */
    public void telemetry(long nanos) {
        telemetry.add(nanos, 0);
        synchronized (this) {
            if (!anyTelemetry || nanos > lastTelemetryNanos) {
                lastTelemetryNanos = nanos;
            }
            anyTelemetry = true;
        }
    }

    /** A ControlML request sent to the robot. */
    public synchronized void requested() {
        requests++;
    }

    /**
     * The answer to a request.
     *
     * @param nanos         when it came ({@code System.nanoTime()} scale)
     * @param roundTripNanos how long after its request
     * @param error         its condition when it is an error (TIMEOUT: none came; NOT_CONNECTED: it could not be
     *                      sent), null for a result; only answers that came are round trips
     */
    public void answered(long nanos, long roundTripNanos, ControlMlCondition error) {
        if (error != ControlMlCondition.TIMEOUT && error != ControlMlCondition.NOT_CONNECTED) {
            roundTrips.add(nanos, roundTripNanos);
        }
        if (error != null) {
            synchronized (this) {
                errors.merge(error, 1L, Long::sum);
            }
        }
    }

    /** @return the counters at {@code nowNanos} */
    public TrafficStatistics snapshot(long nowNanos) {
        long answeredInWindow = roundTrips.count(nowNanos);
        Map<ControlMlCondition, Long> errorsNow;
        long requestsNow;
        double age;
        synchronized (this) {
            errorsNow = Map.copyOf(errors);
            requestsNow = requests;
            age = anyTelemetry ? Math.max(0, nowNanos - lastTelemetryNanos) / NANOS_PER_S : Double.NaN;
        }
        return new TrafficStatistics(robot, in.totalEvents(), out.totalEvents(), in.totalAmount(), out.totalAmount(),
                in.eventsPerSecond(nowNanos), out.eventsPerSecond(nowNanos), in.amountPerSecond(nowNanos), out
                        .amountPerSecond(nowNanos), requestsNow, errorsNow, answeredInWindow, roundTrips
                                .quantileNanos(0.5, nowNanos) / NANOS_PER_MS, roundTrips.quantileNanos(0.99,
                                        nowNanos) / NANOS_PER_MS, telemetry.totalEvents(), telemetry
                                                .eventsPerSecond(nowNanos), age);
    }
}
