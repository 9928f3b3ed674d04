package sabot.workbench.statistics.internal;

import java.util.HashMap;
import java.util.Map;

import sabot.workbench.fleet.TrafficStatistics;

/**
 * The Traffic view's plots' memory (plain Java: no SWT): per robot, the last {@link #SAMPLES} snapshots' rates and
 * round trip, one per refresh, in a ring of primitive arrays; nothing else is kept.
 */
public final class TrafficHistory {

    /** Samples per robot: five minutes at the view's 1 Hz. */
    public static final int SAMPLES = 300;

    /** One robot's ring. */
    private static final class Ring {
        final double[] t = new double[SAMPLES];
        final double[] in = new double[SAMPLES];
        final double[] out = new double[SAMPLES];
        final double[] p99 = new double[SAMPLES];
        int next;
        int size;
    }

    private final Map<String, Ring> robots = new HashMap<>();

    /**
     * Adds a snapshot.
     *
     * @param seconds when it was taken, s on any monotonic scale
     */
    public void add(double seconds, TrafficStatistics s) {
        Ring r = robots.computeIfAbsent(s.robot(), k -> new Ring());
        r.t[r.next] = seconds;
        r.in[r.next] = s.stanzasInPerSecond();
        r.out[r.next] = s.stanzasOutPerSecond();
        r.p99[r.next] = s.roundTripP99Ms();
        r.next = (r.next + 1) % SAMPLES;
        r.size = Math.min(r.size + 1, SAMPLES);
    }

    /** Forgets a robot (no longer followed). */
    public void remove(String robot) {
        robots.remove(robot);
    }

    /** @return how many samples a robot has, 0..{@link #SAMPLES} */
    public int size(String robot) {
        Ring r = robots.get(robot);
        return r == null ? 0 : r.size;
    }

    /** What a series plots. */
    public enum Series {
        /** stanzas received per second */
        IN,
        /** stanzas sent per second */
        OUT,
        /** round-trip p99, ms (a second without an answer in the window has no point) */
        ROUND_TRIP_P99
    }

    /**
     * @param now the x axis' zero: samples are at {@code t - now} seconds (negative: in the past)
     * @return {x, y}, oldest first, without the points that have no value; empty arrays for a robot without samples
     */
    public double[][] series(String robot, Series which, double now) {
        Ring r = robots.get(robot);
        if (r == null) {
            return new double[][] { {}, {} };
        }
        double[] source = switch (which) {
            case IN -> r.in;
            case OUT -> r.out;
            case ROUND_TRIP_P99 -> r.p99;
        };
        double[] x = new double[r.size];
        double[] y = new double[r.size];
        int n = 0;
        int first = (r.next - r.size + SAMPLES) % SAMPLES;
        for (int i = 0; i < r.size; i++) {
            int k = (first + i) % SAMPLES;
            if (!Double.isNaN(source[k])) { // a second without answers: no point
                x[n] = r.t[k] - now;
                y[n++] = source[k];
            }
        }
        return new double[][] { java.util.Arrays.copyOf(x, n), java.util.Arrays.copyOf(y, n) };
    }
}
