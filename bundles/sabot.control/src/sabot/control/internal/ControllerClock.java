package sabot.control.internal;

/** Validates the caller's clock: finite and non-decreasing. */
final class ControllerClock {

    private double last = Double.NaN;

    /**
     * @return the elapsed time since the previous accepted call (0 on the first), or -1 when {@code time} is not finite
     *         or earlier than the previous call (the clock then forgets the previous time)
     */
    double advance(double time) {
        if (!Double.isFinite(time) || (!Double.isNaN(last) && time < last)) {
            last = Double.NaN;
            return -1;
        }
        double dt = Double.isNaN(last) ? 0 : time - last;
        last = time;
        return dt;
    }

    void reset() {
        last = Double.NaN;
    }
}
