package sabot.modbus;

import java.time.Duration;

/**
 * The latest measurement of the ceiling-landmark board (slave 4): which ceiling marker the up-looking camera at the
 * robot centre saw, and where, in the robot frame at the instant the measurement was taken ({@code age} ago).
 *
 * @param sequence   measurement counter, 0–65535, wraps: a new value means a new measurement (seen or not)
 * @param landmarkId the marker's id, 1–65535 as in the map's landmarks file; 0 when no marker was within the view
 *                   radius
 * @param range      horizontal distance from the robot centre to the marker, m (1 mm resolution); 0 when none seen
 * @param bearing    direction of the marker from the robot's heading, counter-clockwise, rad in [−π, π] (10⁻⁴ rad
 *                   resolution); 0 when none seen
 * @param age        how long before the read the measurement was taken (1 ms resolution, saturating at 65.535 s);
 *                   never null
 */
public record LandmarkSighting(int sequence, int landmarkId, double range, double bearing, Duration age) {

    /** @return whether a marker was seen ({@code landmarkId != 0}) */
    public boolean seen() {
        return landmarkId != 0;
    }
}
