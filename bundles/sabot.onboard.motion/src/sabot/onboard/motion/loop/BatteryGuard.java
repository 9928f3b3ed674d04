package sabot.onboard.motion.loop;

import java.util.List;
import java.util.Optional;

import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.robot.BatteryState;

/**
 * What the robot does about a low battery (docs/ONBOARD.md, "Battery"). Plain Java, fed each new reading of the power
 * board with the pose and the mission; its owner carries out what it answers.
 * <ul>
 * <li><b>normal</b>: when the charge falls below {@code low} away from a dock (and not in maintenance), the robot
 * <em>aborts</em> its mission (and drops the queue) rather than finish it: a mission's length is unknown, a robot
 * stranded with an empty battery is worse than a mission to send again. It then goes to the nearest of the map's
 * docks: {@link Decision#goToDock()} names it (<b>to dock</b>).</li>
 * <li><b>to dock</b>: on the dock's contacts (the power board says docked), <b>charging</b>. A dock mission that
 * ends elsewhere (failed, aborted by an operator) is followed by a new one at the next reading while the charge is
 * still low: only maintenance mode stops a low robot from docking.</li>
 * <li><b>charging</b>: the robot is Away "charging" until the charge reaches {@code charged} (or the charge ends
 * full), then Free again (<b>normal</b>); taken off the dock before, it is normal again too (and goes back if low).</li>
 * </ul>
 * Without a dock on the map a low battery is only logged (the decision says so once). Used by one thread.
 */
public final class BatteryGuard {

    /**
     * m: the dock mission's position tolerance, tighter than the dock's reach (the simulator's contacts meet within
     * 0.15 m of the dock's point, onboard-bridge/sim/world.h WORLD_DOCK_REACH), so that a robot that arrives docks.
     */
    public static final double DOCK_TOLERANCE = 0.05;

    /** Where the guard stands. */
    public enum State {
        NORMAL, TO_DOCK, CHARGING
    }

    /**
     * What to do after a reading.
     *
     * @param goToDock the dock to abort the mission for and drive to, when it is time to
     * @param note     a line for the log when something changed (else empty)
     */
    public record Decision(Optional<Point2D> goToDock, String note) {
        static final Decision NONE = new Decision(Optional.empty(), "");
    }

    private final double low;
    private final double charged;
    private final List<Point2D> docks;
    private State state = State.NORMAL;
    private boolean toldNoDock;

    /**
     * @param low     state of charge (0–1) below which the robot goes to its dock
     * @param charged state of charge (0–1, above {@code low}) at which a charging robot is free again
     * @param docks   the map's docks, m, map frame (possibly none)
     */
    public BatteryGuard(double low, double charged, List<Point2D> docks) {
        if (!(low >= 0 && low < charged && charged <= 1)) {
            throw new IllegalArgumentException("battery thresholds must be 0 <= low < charged <= 1, were low " + low
                    + ", charged " + charged);
        }
        this.low = low;
        this.charged = charged;
        this.docks = List.copyOf(docks);
    }

    /** @return where the guard stands */
    public State state() {
        return state;
    }

    /** @return whether the robot stands on its dock charging after a low battery (presence Away "charging") */
    public boolean charging() {
        return state == State.CHARGING;
    }

    /**
     * @param battery a new reading of the power board
     * @param pose    where the robot believes it is
     * @param mission the mission now
     * @return what to do
     */
    public Decision update(BatteryState battery, Pose2D pose, MissionStatus mission) {
        double soc = battery.stateOfCharge();
        switch (state) {
            case CHARGING -> {
                if (!battery.docked()) {
                    state = State.NORMAL;
                    return new Decision(Optional.empty(), "taken off the dock while charging at " + percent(soc));
                }
                if (soc >= charged || battery.full()) {
                    state = State.NORMAL;
                    return new Decision(Optional.empty(), "charged to " + percent(soc) + ": free again");
                }
                return Decision.NONE;
            }
            case TO_DOCK -> {
                if (battery.docked()) {
                    state = State.CHARGING;
                    return new Decision(Optional.empty(), "docked at " + percent(soc) + ": charging");
                }
                boolean underway = mission.state() == MissionState.RUNNING || mission.state() == MissionState.PAUSED;
                if (underway) {
                    return Decision.NONE;
                }
                state = State.NORMAL; // the dock mission ended elsewhere: decided again below
            }
            case NORMAL -> {
                // judged below
            }
        }
        if (soc >= low || battery.docked() || mission.maintenance()) {
            return Decision.NONE;
        }
        Optional<Point2D> dock = nearest(pose);
        if (dock.isEmpty()) {
            if (toldNoDock) {
                return Decision.NONE;
            }
            toldNoDock = true;
            return new Decision(Optional.empty(), "battery low (" + percent(soc) + ") and the map has no dock");
        }
        state = State.TO_DOCK;
        Point2D d = dock.get();
        return new Decision(dock, String.format(java.util.Locale.ROOT, "battery low (%s, below %s): to the dock at "
                + "(%.2f, %.2f)", percent(soc), percent(low), d.x(), d.y()));
    }

    private Optional<Point2D> nearest(Pose2D pose) {
        Point2D best = null;
        double bestDistance = Double.POSITIVE_INFINITY;
        for (Point2D d : docks) {
            double distance = Math.hypot(d.x() - pose.x(), d.y() - pose.y());
            if (distance < bestDistance) {
                best = d;
                bestDistance = distance;
            }
        }
        return Optional.ofNullable(best);
    }

    private static String percent(double soc) {
        return String.format(java.util.Locale.ROOT, "%.0f %%", soc * 100);
    }
}
