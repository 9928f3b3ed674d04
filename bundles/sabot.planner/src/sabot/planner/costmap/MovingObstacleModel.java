package sabot.planner.costmap;

/**
 * The cost of the space a moving obstacle is about to sweep, so that the robot prefers paths that pass behind a
 * person rather than across their way. For a cell at map-frame point x and an obstacle at p moving with velocity v
 * (speed |v|) while the robot moves with velocity u:
 *
 * <pre>
 *   s     = (x - p) . v / |v|, clamped to [0, |v| * horizon]      distance ahead along the obstacle's track, m
 *   d     = | x - (p + s v / |v|) |                               distance from the predicted position, m
 *   w     = max(|v - u|, minClosingSpeed)                         relative (closing) speed, m/s
 *   cost  = peakCost * exp(-(s / w) / timeConstant) * g(d)        g(d) = 1 within the obstacle's radius,
 *                                                                 exp(-(d - radius)^2 / (2 lateralSigma^2)) beyond
 * </pre>
 *
 * {@code s / w} is the time in which the gap to that point closes at the relative speed: cost is high close ahead of
 * a fast-closing obstacle and fades with distance ahead and with lateral distance from its track. A standing obstacle
 * (|v| = 0) costs only its own blurred disc. Costs stay graded ({@code <= 252}): a prediction never makes a cell
 * impassable. The form (predicted occupancy decaying with time-to-conflict, Gaussian across the track) follows the
 * social-navigation costmaps of R. Kirby, "Social robot navigation", CMU 2010, and the ROS {@code social_navigation_layers}.
 *
 * @param horizon         seconds of motion to sweep ahead, positive
 * @param peakCost        cost 1..252 at the obstacle and right ahead of it
 * @param lateralSigma    metres, positive: spread across the track beyond the obstacle's radius
 * @param timeConstant    seconds, positive: decay of the cost with time-to-conflict
 * @param minClosingSpeed metres per second, positive: floor of the relative speed (avoids dividing by zero)
 */
public record MovingObstacleModel(double horizon, int peakCost, double lateralSigma, double timeConstant,
        double minClosingSpeed) {

    /** Lateral reach of the cost, in standard deviations beyond the radius. */
    static final double LATERAL_CUTOFF_SIGMAS = 3;

    /** @throws IllegalArgumentException naming the parameter when a value is unusable */
    public MovingObstacleModel {
        if (!(horizon > 0) || !Double.isFinite(horizon)) {
            throw new IllegalArgumentException("horizon must be > 0 s, got " + horizon);
        }
        if (peakCost < 1 || peakCost > 252) {
            throw new IllegalArgumentException("peak cost must be 1..252, got " + peakCost);
        }
        if (!(lateralSigma > 0) || !Double.isFinite(lateralSigma)) {
            throw new IllegalArgumentException("lateral sigma must be > 0 m, got " + lateralSigma);
        }
        if (!(timeConstant > 0) || !Double.isFinite(timeConstant)) {
            throw new IllegalArgumentException("time constant must be > 0 s, got " + timeConstant);
        }
        if (!(minClosingSpeed > 0) || !Double.isFinite(minClosingSpeed)) {
            throw new IllegalArgumentException("minimum closing speed must be > 0 m/s, got " + minClosingSpeed);
        }
    }

    /** @return 3 s horizon, peak 200, 0.3 m lateral spread, 1.5 s time constant, 0.1 m/s floor */
    public static MovingObstacleModel defaults() {
        return new MovingObstacleModel(3.0, 200, 0.3, 1.5, 0.1);
    }

    /** @return metres beyond the obstacle's centre that can receive cost sideways */
    double lateralReach(MovingObstacle obstacle) {
        return obstacle.radius() + LATERAL_CUTOFF_SIGMAS * lateralSigma;
    }

    /**
     * @param x        map-frame x of the cell centre, metres
     * @param y        map-frame y of the cell centre, metres
     * @param robotVx  robot's map-frame velocity along x, m/s
     * @param robotVy  robot's map-frame velocity along y, m/s
     * @return the swept cost 0..peakCost of that point
     */
    public int cost(MovingObstacle obstacle, double x, double y, double robotVx, double robotVy) {
        double speed = obstacle.speed();
        double rx = x - obstacle.position().x();
        double ry = y - obstacle.position().y();
        double ahead = 0;
        if (speed > 0) {
            ahead = (rx * obstacle.vx() + ry * obstacle.vy()) / speed;
            ahead = Math.max(0, Math.min(speed * horizon, ahead));
        }
        double px = speed > 0 ? ahead * obstacle.vx() / speed : 0;
        double py = speed > 0 ? ahead * obstacle.vy() / speed : 0;
        double lateral = Math.hypot(rx - px, ry - py);
        double beyond = lateral - obstacle.radius();
        if (beyond > LATERAL_CUTOFF_SIGMAS * lateralSigma) {
            return 0;
        }
        double across = beyond <= 0 ? 1 : Math.exp(-beyond * beyond / (2 * lateralSigma * lateralSigma));
        double closing = Math.max(minClosingSpeed, Math.hypot(obstacle.vx() - robotVx, obstacle.vy() - robotVy));
        double along = Math.exp(-(ahead / closing) / timeConstant);
        return (int) Math.round(peakCost * along * across);
    }
}
