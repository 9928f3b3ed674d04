package sabot.workbench.fleet;

import java.time.Duration;
import java.time.Instant;
import java.util.List;
import java.util.Objects;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.BatteryState;

/**
 * One robot as the workbench knows it: an immutable snapshot. Everything is in the map frame, SI units (metres,
 * radians, seconds); values the robot has not sent yet are null.
 *
 * @param jid           the robot's bare JID, e.g. {@code sabot-01@sabot.local}; never null
 * @param name          the nickname to show (roster name, else the JID's local part); never null
 * @param availability  its presence level, {@link Availability#OFFLINE} without an available presence; never null
 * @param reason        the presence's status text (the mission's detail, "maintenance"...), empty when none; never
 *                      null
 * @param pose          the last pose estimate ({@code cm.position}: x, y in m, theta in rad, covariance in m&sup2;,
 *                      m&middot;rad, rad&sup2;), or null
 * @param velocity      the last executed twist ({@code cm.velocity}: m/s, rad/s), or null
 * @param mission       the last mission status ({@code cm.mission}: state, progress in percent 0..100, detail; for
 *                      a mission of several targets also the targets with their states, the index of the current one
 *                      and the missions queued after it), or null
 * @param path          the planned trajectory of the current or last mission ({@code cm.trajectory}), or null
 * @param obstacles     what the sonar board sees ({@code cm.obstacles}: discs in m), or null
 * @param goal          the goal of the current or last mission ({@code cm.goal}), or null
 * @param trail         where the robot has been lately (oldest first, at most {@link #TRAIL_POINTS} points at least
 *                      {@link #TRAIL_SPACING_M} apart); never null
 * @param lastTelemetry when the workbench last received telemetry from it (workbench clock), or null
 * @param poseLag       how late its last pose arrived compared with its fastest ({@link PoseLag}), or null before its
 *                      first pose since it last went offline or came online
 * @param battery       the last battery reading ({@code cm.battery}: charge, voltage, current, docked, charging, full),
 *                      or null
 */
public record RobotState(String jid, String name, Availability availability, String reason, PoseEstimate pose,
        Twist2D velocity, MissionStatus mission, TrajectoryPayload path, Obstacles obstacles, Goal goal,
        List<Point2D> trail, Instant lastTelemetry, PoseLag poseLag, BatteryState battery) {

    /**
     * Telemetry received longer ago than this, or a last pose that arrived this much later than the robot's fastest,
     * makes a robot stale (drawn greyed): five periods of the slowest pose rate the onboard product is configured with
     * by default (10 Hz) would be 0.5 s; 2 s leaves room for a slow server.
     */
    public static final Duration STALE_AFTER = Duration.ofSeconds(2);
    /** Most points a trail keeps. */
    public static final int TRAIL_POINTS = 600;
    /** Least distance between two trail points, metres. */
    public static final double TRAIL_SPACING_M = 0.05;

    public RobotState {
        Objects.requireNonNull(jid, "jid");
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(availability, "availability");
        Objects.requireNonNull(reason, "reason");
        trail = List.copyOf(trail);
    }

    /** @return a robot known by name only: offline, nothing received */
    public static RobotState unknown(String jid, String name) {
        return new RobotState(jid, name, Availability.OFFLINE, "", null, null, null, null, null, null, List.of(),
                null, null, null);
    }

    /**
     * @param now the workbench clock's present
     * @return true when the robot is offline, its telemetry is older than {@link #STALE_AFTER} or its last pose
     *         arrived more than {@link #STALE_AFTER} later than its fastest ({@link #isLate()})
     */
    public boolean isStale(Instant now) {
        return availability == Availability.OFFLINE || lastTelemetry == null || Duration.between(lastTelemetry, now)
                .compareTo(STALE_AFTER) > 0 || isLate();
    }

    /**
     * @return true when the robot is online and its last pose arrived more than {@link #STALE_AFTER} later than the
     *         robot's fastest: a backlog on the way (the server, or the workbench's own ingest behind on a busy CPU),
     *         although poses keep coming. An offline robot is stale, never late, even when poses of its backlog still
     *         arrive after its presence went.
     */
    public boolean isLate() {
        return availability != Availability.OFFLINE && poseLag != null && poseLag.lag().compareTo(STALE_AFTER) > 0;
    }

    /** @return how old the last telemetry is at {@code now}, or null when none was received */
    public Duration telemetryAge(Instant now) {
        return lastTelemetry == null ? null : Duration.between(lastTelemetry, now);
    }

    /** @return this state with another name */
    public RobotState withName(String n) {
        return new RobotState(jid, n, availability, reason, pose, velocity, mission, path, obstacles, goal, trail,
                lastTelemetry, poseLag, battery);
    }

    /**
     * @return this state with another presence; the pose lag starts anew when the robot goes offline and when it comes
     *         online again (it may have restarted with another clock, and poses that arrived while it was offline
     *         measured nothing about its new session)
     */
    public RobotState withPresence(Availability a, String r) {
        boolean crossing = (a == Availability.OFFLINE) != (availability == Availability.OFFLINE);
        PoseLag lag = crossing ? null : poseLag;
        return new RobotState(jid, name, a, r, pose, velocity, mission, path, obstacles, goal, trail, lastTelemetry,
                lag, battery);
    }

    /**
     * @param p       the pose
     * @param at      its receipt on the workbench's clock
     * @param atNanos its receipt on the workbench's monotonic clock ({@link System#nanoTime()}), for its lag
     * @return this state with a new pose, the trail extended and its lag measured
     */
    public RobotState withPose(PoseEstimate p, Instant at, long atNanos) {
        PoseLag lag = poseLag == null ? PoseLag.first(p.time(), atNanos) : poseLag.next(p.time(), atNanos);
        return new RobotState(jid, name, availability, reason, p, velocity, mission, path, obstacles, goal, extend(
                trail, p), at, lag, battery);
    }

    /** @return this state with a new twist received at {@code at} */
    public RobotState withVelocity(Twist2D v, Instant at) {
        return new RobotState(jid, name, availability, reason, pose, v, mission, path, obstacles, goal, trail, at,
                poseLag, battery);
    }

    /** @return this state with a new mission status received at {@code at} */
    public RobotState withMission(MissionStatus m, Instant at) {
        return new RobotState(jid, name, availability, reason, pose, velocity, m, path, obstacles, goal, trail, at,
                poseLag, battery);
    }

    /** @return this state with new obstacles received at {@code at} */
    public RobotState withObstacles(Obstacles o, Instant at) {
        return new RobotState(jid, name, availability, reason, pose, velocity, mission, path, o, goal, trail, at,
                poseLag, battery);
    }

    /** @return this state with another planned path and goal (either may be null) */
    public RobotState withPlan(TrajectoryPayload t, Goal g) {
        return new RobotState(jid, name, availability, reason, pose, velocity, mission, t, obstacles, g, trail,
                lastTelemetry, poseLag, battery);
    }

    /** @return this state with a new battery reading received at {@code at} */
    public RobotState withBattery(BatteryState b, Instant at) {
        return new RobotState(jid, name, availability, reason, pose, velocity, mission, path, obstacles, goal, trail,
                at, poseLag, b);
    }

    private static List<Point2D> extend(List<Point2D> trail, PoseEstimate p) {
        Point2D at = new Point2D(p.pose().x(), p.pose().y());
        if (!trail.isEmpty()) {
            Point2D last = trail.get(trail.size() - 1);
            if (Math.hypot(at.x() - last.x(), at.y() - last.y()) < TRAIL_SPACING_M) {
                return trail;
            }
        }
        int from = trail.size() >= TRAIL_POINTS ? trail.size() - TRAIL_POINTS + 1 : 0;
        java.util.ArrayList<Point2D> next = new java.util.ArrayList<>(trail.subList(from, trail.size()));
        next.add(at);
        return next;
    }
}
