package sabot.planner.internal;

/**
 * The interpolated update of {@link LpnNavigationFunction}: the value a cell p gets from a final axis neighbour a and
 * the adjacent diagonal neighbour d (the corner). In the triangle (p, a, d) the wave may cross the edge [a, d] at any
 * point; for edge density {@code c} the least of {@code (1 - t) N(a) + t N(d) + c sqrt(1 + t^2)} over t in [0, 1]
 * is, with {@code delta = max(0, N(a) - N(d))},
 *
 * <pre>
 *   N(a) + sqrt(c^2 - delta^2)     when delta &lt; c / sqrt(2)       (crossing inside the edge)
 *   N(d) + c sqrt(2)               otherwise                         (straight from d)
 * </pre>
 *
 * (J. N. Tsitsiklis, "Efficient algorithms for globally optimal trajectories", IEEE TAC 40(9), 1995; the same
 * interpolation idea as navfn's quadratic update, on eight neighbours). Of the two triangles through an axis
 * neighbour a, the one whose corner d is lower gives the lower value, so an update evaluates one square root.
 *
 * <p>Why a class of its own: the formula is the cost model of one step, shared by the propagation's hot loop and the
 * repair's recomputation, so that both give a cell the same value. Its methods are static, small and branch-free on
 * the data, so C2 inlines them into the loop: whether a corner is lower, and whether the crossing is interior, are
 * coin tosses, and C2 compiles a float selection ({@code a < b ? a : b}) on x86 to a compare and a jump (there is no
 * conditional move for floats), which would be mispredicted about half the time; every selection is therefore made
 * on the float bits with integer operations, which C2 compiles to conditional moves.
 */
final class InterpolatedUpdate {

    static final float SQRT2 = (float) Math.sqrt(2);
    static final float INV_SQRT2 = (float) (1 / Math.sqrt(2));

    private InterpolatedUpdate() {
    }

    /**
     * The lower of two stored values (see {@link LpnNavigationFunction#decode}), decoded: the minimum of their value
     * bits as ints (non-negative floats order like their bits).
     */
    static float lower(int bits, int otherBits) {
        return Float.intBitsToFloat(Math.min(bits & LpnNavigationFunction.VALUE, otherBits & LpnNavigationFunction.VALUE));
    }

    /**
     * The update of a cell from a final axis neighbour of value {@code value} through the lower of its two diagonal
     * corners next to that neighbour, {@code corner}, for edge density {@code c}. A corner at or above {@code value}
     * gives the axis step {@code value + c}, whatever its value.
     */
    static float update(float value, float corner, float c) {
        return Float.intBitsToFloat(updateBits(value, corner, c));
    }

    /** {@link #update} as float bits, computed without a jump. */
    static int updateBits(float value, float corner, float c) {
        float limit = c * INV_SQRT2;
        // delta = max(0, N(a) - N(corner)): a negative difference (sign bit set) masked to +0
        int deltaBits = Float.floatToRawIntBits(value - corner);
        deltaBits &= ~(deltaBits >> 31);
        float delta = Float.intBitsToFloat(deltaBits);
        // interior crossing (or the axis step when delta = 0), and the straight diagonal from the corner; the choice
        // is by delta alone: below the limit the crossing is never dearer (sqrt(c^2 - delta^2) + delta <= c sqrt 2,
        // equal at the limit), above it the square root is of a negative number (NaN) and not chosen
        float interior = value + (float) Math.sqrt(c * c - delta * delta);
        float straight = corner + c * SQRT2;
        // delta < limit, both non-negative: compared as bits, the difference's sign is the mask of the interior
        int interiorMask = (deltaBits - Float.floatToRawIntBits(limit)) >> 31;
        return Float.floatToRawIntBits(interior) & interiorMask | Float.floatToRawIntBits(straight) & ~interiorMask;
    }
}
