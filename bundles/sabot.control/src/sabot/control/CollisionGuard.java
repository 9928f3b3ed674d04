package sabot.control;

import java.util.Locale;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;

/**
 * Limits a velocity command so that the robot can stop before any obstacle it knows of, whatever produced the command:
 * the "approach" behaviour of Nav2's {@code collision_monitor}. The robot's footprint is a circle; the command's arc
 * (the path the robot would drive if the twist were held) is walked from the robot's pose until the footprint would
 * touch an obstacle, and the linear speed is bounded so that the robot, reacting within {@code reactionTime} and then
 * braking at {@code deceleration}, comes to rest {@code margin} short of that point:
 * <pre>
 *   v·t_r + v²/(2a) ≤ d − margin   ⇒   v_allowed = a·(√(t_r² + 2(d − margin)/a) − t_r)
 * </pre>
 * The angular speed is scaled with the linear one, so the commanded curvature is kept (a slowed robot keeps to the arc
 * it was asked to drive). A command without linear speed — turning in place — passes unchanged: a circular footprint
 * sweeps nothing new when it turns. An obstacle already under the footprint (an echo that came close) stops motion
 * towards it but not away from it: along the arc, only a footprint that comes closer to an obstacle than it already
 * is counts as contact.
 * <p>
 * Reversing: the robot's sonar looks forward only, so behind it nothing but the map and echoes seen earlier can prove
 * the way free; reversing is limited by those like any motion and, in addition, to {@code reverseSpeed}, at which a
 * person stepping behind the robot is touched at walking-into-a-chair speed. Pure algorithm: no threads, no state
 * between calls.
 */
public final class CollisionGuard {

    /** Step along the arc at which the footprint is checked, m (a map cell is 5 cm). */
    public static final double STEP = 0.02;
    /** Linear speed below which a command is a turn in place, m/s. */
    private static final double STANDSTILL = 1e-6;

    /**
     * Where the obstacles are, for the guard: the distance from a point to the nearest obstacle the robot knows of.
     */
    @FunctionalInterface
    public interface ObstacleField {
        /**
         * @param x     map-frame x, m
         * @param y     map-frame y, m
         * @param limit the distance beyond which obstacles do not matter, m
         * @return the distance from (x, y) to the nearest obstacle, m, or {@code limit} when none is nearer
         */
        double clearance(double x, double y, double limit);
    }

    /**
     * The guard's settings.
     *
     * @param radius       the footprint's radius, m
     * @param margin       distance the robot stops short of an obstacle, m
     * @param reactionTime s from a command to the wheels braking (the loop's period, the bus write, the motor board)
     * @param deceleration the braking deceleration, m/s² (the robot's acceleration limit)
     * @param maxSpeed     the robot's top linear speed, m/s: sets how far ahead the arc is checked
     * @param reverseSpeed the top speed backwards, m/s (no sensor looks behind)
     */
    public record Settings(double radius, double margin, double reactionTime, double deceleration, double maxSpeed,
            double reverseSpeed) {

        public Settings {
            if (!(radius > 0) || !(margin >= 0) || !(reactionTime >= 0) || !(deceleration > 0) || !(maxSpeed > 0)
                    || !(reverseSpeed >= 0) || !Double.isFinite(radius + margin + reactionTime + deceleration + maxSpeed
                            + reverseSpeed)) {
                throw new IllegalArgumentException("guard settings out of range: " + this);
            }
        }

        /** @return the distance the robot needs to come to rest from {@code speed}, margin included, m */
        public double stoppingDistance(double speed) {
            double v = Math.abs(speed);
            return v * reactionTime + v * v / (2 * deceleration) + margin;
        }

        /** @return the largest speed from which the robot stops within {@code distance}, margin included, m/s */
        public double speedFor(double distance) {
            double d = distance - margin;
            if (!(d > 0)) {
                return 0;
            }
            double a = deceleration;
            return a * (Math.sqrt(reactionTime * reactionTime + 2 * d / a) - reactionTime);
        }

        /** @return how far along an arc the guard looks, m: the stopping distance from the top speed, and a step */
        public double lookahead() {
            return stoppingDistance(maxSpeed) + STEP;
        }
    }

    /** What the guard did to a command. */
    public enum Action {
        /** Passed unchanged: nothing within the stopping distance. */
        FREE,
        /** Slowed: an obstacle ahead within the command's stopping distance. */
        SLOWED,
        /** Stopped: the robot is at its stopping distance from an obstacle ahead. */
        STOPPED,
        /** Backwards at creep speed: nothing known behind, but no sensor looks there. */
        REVERSE_CREEP
    }

    /**
     * The guard's verdict on one command.
     *
     * @param twist    the twist to apply
     * @param action   what the guard did
     * @param obstacle free travel along the command's arc before the footprint touches an obstacle, m; infinite when
     *                 none is within the lookahead (or for a turn in place)
     */
    public record Decision(Twist2D twist, Action action, double obstacle) {

        /** @return true when the guard changed the command */
        public boolean limited() {
            return action != Action.FREE;
        }

        /** @return the operator's words for it, e.g. {@code stopped: obstacle 0.31 m ahead}; empty when free */
        public String describe() {
            String where = Math.copySign(1, obstacle) < 0 ? "behind" : "ahead";
            return switch (action) {
                case FREE -> "";
                case STOPPED -> String.format(Locale.ROOT, "stopped: obstacle %.2f m %s", Math.abs(obstacle), where);
                case SLOWED -> String.format(Locale.ROOT, "slowed to %.2f m/s: obstacle %.2f m %s",
                        Math.abs(twist.linear()), Math.abs(obstacle), where);
                case REVERSE_CREEP -> String.format(Locale.ROOT, "reversing at %.2f m/s: no sensor looks behind",
                        Math.abs(twist.linear()));
            };
        }
    }

    private final Settings settings;

    public CollisionGuard(Settings settings) {
        this.settings = settings;
    }

    /** @return the settings */
    public Settings settings() {
        return settings;
    }

    /**
     * @param pose    where the robot stands (map frame)
     * @param command the twist asked for; a non-finite one is a stop
     * @param field   the obstacles
     * @return the twist the robot may drive now, and why
     */
    public Decision limit(Pose2D pose, Twist2D command, ObstacleField field) {
        if (!command.isFinite() || !pose.isFinite()) {
            return new Decision(Twist2D.ZERO, Action.STOPPED, 0);
        }
        double v = command.linear();
        if (Math.abs(v) < STANDSTILL) {
            return new Decision(command, Action.FREE, Double.POSITIVE_INFINITY);
        }
        double free = freeTravel(pose, v, command.angular(), field);
        double allowed = settings.speedFor(free);
        boolean reverse = v < 0;
        double sign = reverse ? -1 : 1;
        double signedFree = sign * free;
        if (reverse && settings.reverseSpeed() < allowed) {
            allowed = settings.reverseSpeed();
            if (Math.abs(v) > allowed) {
                return scaled(command, allowed, allowed > 0 ? Action.REVERSE_CREEP : Action.STOPPED, signedFree);
            }
        }
        if (Math.abs(v) <= allowed) {
            return new Decision(command, Action.FREE, signedFree);
        }
        return scaled(command, allowed, allowed > 0 ? Action.SLOWED : Action.STOPPED, signedFree);
    }

    /**
     * For a short move the guard cannot limit while it happens (the motor board's position step of one wheel, which
     * runs on the board): the free travel along the arc the move follows, to compare with the move's length plus the
     * margin before starting it.
     *
     * @param pose      where the robot stands (map frame)
     * @param direction a twist whose arc the move follows (its linear speed's sign gives forwards or backwards; only
     *                  the ratio of the two speeds matters); without linear speed the footprint sweeps nothing new
     * @param field     the obstacles
     * @return the distance along that arc to the last point before the footprint would come closer to an obstacle than
     *         its radius (and closer than before), m; infinite when none within the lookahead
     */
    public double freeTravel(Pose2D pose, Twist2D direction, ObstacleField field) {
        if (!pose.isFinite() || !direction.isFinite()) {
            return 0;
        }
        if (Math.abs(direction.linear()) < STANDSTILL) {
            return Double.POSITIVE_INFINITY;
        }
        return freeTravel(pose, direction.linear(), direction.angular(), field);
    }

    /** @return the command with its linear speed brought down to {@code speed}, its curvature kept */
    private static Decision scaled(Twist2D command, double speed, Action action, double obstacle) {
        double f = speed / Math.abs(command.linear());
        return new Decision(new Twist2D(command.linear() * f, command.angular() * f), action, obstacle);
    }

    /**
     * Walks the arc the twist (v, ω) describes from {@code pose} in steps of {@link #STEP} up to the lookahead.
     *
     * @return the distance along it to the last point before the footprint would come closer to an obstacle than its
     *         radius (and closer than the point before); infinite when that does not happen within the lookahead
     */
    private double freeTravel(Pose2D pose, double v, double w, ObstacleField field) {
        double r = settings.radius();
        double sign = Math.signum(v);
        double k = w / Math.abs(v); // heading change per metre of travel
        double previous = field.clearance(pose.x(), pose.y(), r);
        double lookahead = settings.lookahead();
        for (int i = 1; i * STEP <= lookahead; i++) {
            double s = i * STEP;
            double theta = pose.theta() + k * s;
            double x;
            double y;
            if (Math.abs(k * s) < 1e-9) {
                x = pose.x() + sign * s * Math.cos(pose.theta());
                y = pose.y() + sign * s * Math.sin(pose.theta());
            } else {
                x = pose.x() + sign * (Math.sin(theta) - Math.sin(pose.theta())) / k;
                y = pose.y() - sign * (Math.cos(theta) - Math.cos(pose.theta())) / k;
            }
            double c = field.clearance(x, y, r);
            if (c < r && c < previous) {
                return s - STEP;
            }
            previous = c;
        }
        return Double.POSITIVE_INFINITY;
    }
}
