package sabot.localization;

/** What the filter did with one measurement. */
public enum MeasurementResult {
    /** Fused. */
    ACCEPTED,
    /** Its Mahalanobis distance exceeded the gate: treated as an outlier and ignored. */
    REJECTED_OUTLIER,
    /** A NaN or infinite value (measurement, variance or time): ignored. */
    REJECTED_NOT_FINITE,
    /** Older than the filter's current time: ignored (the filter does not rewind). */
    REJECTED_OUT_OF_ORDER
}
