package sabot.onboard.motion.loop;

import java.util.Locale;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.control.CollisionGuard;
import sabot.control.DifferentialDrive;
import sabot.control.MotionLimits;
import sabot.control.WheelSpeeds;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;

/**
 * The loop's collision guard: every twist the loop is about to hand to the velocity smoother — the tracker's, the
 * stabilizer's, the turn in place's, the joystick's — passes {@link CollisionGuard} against what the robot knows of
 * its surroundings, the static map's occupied cells, the sonar echoes in memory and the other robots' footprints
 * ({@link PeerField}). It remembers its last verdict for
 * the robot's status and logs each change of it once. Used by the loop's thread only.
 */
final class LoopGuard {

    private static final Logger LOG = LoggerFactory.getLogger("sabot.motion");

    private final NavigationPlanner planner;
    private final EchoMemory echoes;
    private final PeerField peers;
    private final CollisionGuard.ObstacleField field = this::clearance;
    private CollisionGuard guard;
    private CollisionGuard.Decision last = new CollisionGuard.Decision(Twist2D.ZERO, CollisionGuard.Action.FREE,
            Double.POSITIVE_INFINITY);

    LoopGuard(NavigationPlanner planner, EchoMemory echoes, PeerField peers) {
        this.planner = planner;
        this.echoes = echoes;
        this.peers = peers;
    }

    /** Takes new settings or limits: the footprint, margin, reaction time, deceleration and speeds. */
    void configure(LoopSettings settings, MotionLimits limits) {
        GuardSettings g = settings.guard();
        guard = new CollisionGuard(new CollisionGuard.Settings(settings.robotRadius(), g.margin(), g.reactionTime(),
                limits.maxLinearAcceleration(), limits.maxLinearSpeed(), g.reverseSpeed()));
    }

    /** @return the twist the robot may drive from {@code pose} instead of {@code command} */
    Twist2D limit(Pose2D pose, Twist2D command) {
        CollisionGuard.Decision d = guard.limit(pose, command, field);
        if (d.action() != last.action()) {
            if (d.limited()) {
                LOG.info("collision guard: {}", d.describe());
            } else {
                LOG.info("collision guard: free again");
            }
        }
        last = d;
        return d.twist();
    }

    /**
     * Whether a position step of one wheel (the PID step test) may start from {@code pose}. The motor board runs the
     * step on its own, beyond this guard, so it is judged before: the robot turns about its other wheel, its centre
     * travelling half the step along that arc, and the footprint must stay clear of every known obstacle by the travel
     * plus the margin (a robot that stands close to a wall may still step away from it).
     *
     * @param motor 0 the left wheel, 1 the right; another is left to the motor board to refuse
     * @param step  m of wheel travel, signed
     * @return why it may not, or null
     */
    String stepBlocked(Pose2D pose, DifferentialDrive drive, int motor, double step) {
        if ((motor != 0 && motor != 1) || !Double.isFinite(step) || step == 0) {
            return null;
        }
        Twist2D direction = drive.toTwist(motor == 0 ? new WheelSpeeds(step, 0) : new WheelSpeeds(0, step));
        double travel = Math.abs(direction.linear());
        double free = guard.freeTravel(pose, direction, field);
        double needed = travel + guard.settings().margin();
        if (free >= needed) {
            return null;
        }
        return String.format(Locale.ROOT, "collision guard: the step turns the robot about its %s wheel, its centre "
                + "%.4f m %s along an arc with an obstacle %.3f m along it; it needs %.3f m (the travel and "
                + "motion.guardMargin)", motor == 0 ? "right" : "left", travel, step > 0 ? "forwards" : "backwards",
                free, needed);
    }

    /** @return what the guard last did, in the operator's words ({@code stopped: obstacle 0.31 m ahead}); "" if free */
    String status() {
        return last.describe();
    }

    /** @return the last verdict */
    CollisionGuard.Decision last() {
        return last;
    }

    /** Forgets the last verdict (the robot came to rest: nothing is being limited). */
    void reset() {
        last = new CollisionGuard.Decision(Twist2D.ZERO, CollisionGuard.Action.FREE, Double.POSITIVE_INFINITY);
    }

    /** Distance from (x, y) to the nearest echo, other robot's disc or occupied cell of the static map, m. */
    private double clearance(double x, double y, double limit) {
        return planner.clearance(x, y, peers.nearest(x, y, echoes.nearest(x, y, limit)));
    }
}
