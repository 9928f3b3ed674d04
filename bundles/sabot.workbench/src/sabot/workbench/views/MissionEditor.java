package sabot.workbench.views;

import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.MissionTarget.Action;
import sabot.model.geometry.Point2D;
import sabot.workbench.map.MapViewport;

/**
 * A mission of several targets as the operator builds it on the Workspace's map, for one robot: the targets in order
 * (each a {@link GoalGesture}'s goal, an action and a wait), and the target the action keys and the context menu act
 * on (the last one added unless the operator picks another). Free of SWT; the view reads the mouse and keys, the
 * painter draws it ({@link MissionPainter}), and {@code FleetState.startMission} sends {@link #targets()}.
 */
final class MissionEditor {

    /** What a new target does: stop on it (the robot is where the operator put it before going on). */
    static final Action DEFAULT_ACTION = Action.STOP;
    /** The wait a target is given when its action becomes wait, seconds. */
    static final double DEFAULT_WAIT_S = 5;
    /** A press within this many pixels of a target's marker is on that target (context menu). */
    static final int PICK_PX = MissionPainter.MARKER_RADIUS_PX + 3;

    private final String robot;
    private final List<MissionTarget> targets = new ArrayList<>();
    private int selected = -1;

    /** @param robot bare JID of the robot the mission is for */
    MissionEditor(String robot) {
        this.robot = robot;
    }

    /** @return the robot the mission is for (bare JID) */
    String robot() {
        return robot;
    }

    /** @return the targets in order, pending: what is sent */
    List<MissionTarget> targets() {
        return List.copyOf(targets);
    }

    /** @return the index of the target the action keys and menu act on, -1 when there is none */
    int selected() {
        return selected;
    }

    /** Makes target {@code i} the one the action keys and menu act on (ignored outside the targets). */
    void select(int i) {
        if (i >= 0 && i < targets.size()) {
            selected = i;
        }
    }

    /** Selects the next target (by -1: the previous one), round the list. */
    void selectNext(int by) {
        if (!targets.isEmpty()) {
            selected = Math.floorMod(selected + by, targets.size());
        }
    }

    /**
     * Appends a target with the {@link #DEFAULT_ACTION} and selects it.
     *
     * @return false when the mission has {@link MissionStatus#MAX_TARGETS} already (nothing added)
     */
    boolean add(Goal goal) {
        if (targets.size() >= MissionStatus.MAX_TARGETS) {
            return false;
        }
        targets.add(MissionTarget.pending(goal, DEFAULT_ACTION, 0));
        selected = targets.size() - 1;
        return true;
    }

    /**
     * Sets what the robot does at target {@code i}.
     *
     * @param waitS seconds at the target for {@link Action#WAIT} (0 < s ≤ {@link MissionTarget#MAX_WAIT_S}); ignored
     *              for the other actions
     */
    void setAction(int i, Action action, double waitS) {
        targets.set(i, MissionTarget.pending(targets.get(i).goal(), action, action == Action.WAIT ? waitS : 0));
    }

    /** Removes target {@code i}; the selection goes to the one before it (the first when it was the first). */
    void remove(int i) {
        targets.remove(i);
        selected = targets.isEmpty() ? -1 : Math.max(0, Math.min(i - 1, targets.size() - 1));
    }

    /** Moves target {@code i} by {@code by} places (-1: earlier), within the list; it stays selected. */
    void move(int i, int by) {
        int to = Math.max(0, Math.min(targets.size() - 1, i + by));
        targets.add(to, targets.remove(i));
        selected = to;
    }

    /** @return where a new target's robot comes from: the last target, else {@code robotPosition} (may be null) */
    Point2D from(Point2D robotPosition) {
        if (targets.isEmpty()) {
            return robotPosition;
        }
        Goal last = targets.get(targets.size() - 1).goal();
        return new Point2D(last.pose().x(), last.pose().y());
    }

    /** @return the index of the target whose marker is under a pixel (the last one drawn on top first), or -1 */
    int targetAt(MapViewport viewport, int px, int py) {
        for (int i = targets.size() - 1; i >= 0; i--) {
            Goal g = targets.get(i).goal();
            if (Math.hypot(viewport.toScreenX(g.pose().x()) - px, viewport.toScreenY(g.pose().y()) - py) <= PICK_PX) {
                return i;
            }
        }
        return -1;
    }

    /** @return a target's action for the operator: {@code pass}, {@code stop}, {@code wait 5 s}, {@code dock} */
    static String describe(MissionTarget t) {
        return t.action() == Action.WAIT ? String.format(Locale.ROOT, "wait %s s", seconds(t.dwell())) : t.action()
                .code();
    }

    /** @return whole seconds without decimals, others with what they need ({@code 5}, {@code 2.5}) */
    static String seconds(double s) {
        return s == Math.rint(s) ? String.valueOf((long) s) : String.valueOf(s);
    }
}
