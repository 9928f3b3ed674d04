package sabot.planner.costmap;

import sabot.model.geometry.Point2D;

/**
 * An obstacle that moves, as a tracker reports it (a person, another robot).
 *
 * @param position map-frame centre, metres
 * @param vx       map-frame velocity along x, metres per second
 * @param vy       map-frame velocity along y, metres per second
 * @param radius   metres, radius of a circle holding the obstacle
 */
public record MovingObstacle(Point2D position, double vx, double vy, double radius) {

    /** @throws IllegalArgumentException when a component is not finite or the radius is negative */
    public MovingObstacle {
        if (position == null || !position.isFinite() || !Double.isFinite(vx) || !Double.isFinite(vy)) {
            throw new IllegalArgumentException("moving obstacle needs a finite position and velocity");
        }
        if (!(radius >= 0) || !Double.isFinite(radius)) {
            throw new IllegalArgumentException("moving obstacle radius must be >= 0 m, got " + radius);
        }
    }

    /** @return speed in metres per second */
    public double speed() {
        return Math.hypot(vx, vy);
    }
}
