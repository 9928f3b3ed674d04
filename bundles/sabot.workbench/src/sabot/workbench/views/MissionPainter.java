package sabot.workbench.views;

import java.util.ArrayList;
import java.util.List;

import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.Color;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.graphics.RGB;

import sabot.controlml.payload.MissionTarget;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.workbench.map.MapViewport;

/**
 * Draws a mission of several targets on the Workspace's frame: the route from the robot through the targets still
 * ahead (dashed), and each target as a numbered disc with its heading and its action beside it. A robot's mission
 * ({@link RobotPainter}) shows each target's state — reached filled green, the active one orange with a thick ring,
 * pending white, failed red; the mission being edited ({@link MissionEditor}) shows its targets pending, the one the
 * keys act on ringed, in the gesture's orange.
 */
final class MissionPainter {

    /** Radius of a target's disc, pixels: room for a two-digit number. */
    static final int MARKER_RADIUS_PX = 9;
    /** A reached target's fill (the planned path's green). */
    static final RGB REACHED = RobotPainter.PATH;
    /** The active target's fill, and the mission being edited (the selection's and the goal gesture's orange). */
    static final RGB ACTIVE = RobotPainter.SELECTED;
    /** A pending target's fill. */
    static final RGB PENDING = new RGB(255, 255, 255);
    /** A failed target's fill (the obstacles' red). */
    static final RGB FAILED = RobotPainter.OBSTACLE;
    /** The route through the targets ahead of a robot. */
    static final RGB ROUTE = new RGB(0, 120, 150);
    /** A target's ring. */
    static final RGB RING = new RGB(40, 40, 40);
    /** Everything of a stale robot's mission. */
    static final RGB STALE = new RGB(170, 170, 170);

    private MissionPainter() {
    }

    /**
     * @param from        where the route starts (the robot's position), or null
     * @param targets     the mission's targets in order
     * @param highlighted the target drawn with a thick ring besides the active one (the editor's selection), or -1
     * @param editing     true for the mission being edited (the gesture's colours), false for a robot's
     * @param stale       true for a stale robot's mission (greyed)
     */
    static void draw(GC gc, MapViewport viewport, Point2D from, List<MissionTarget> targets, int highlighted,
            boolean editing, boolean stale) {
        List<Point> route = new ArrayList<>();
        if (from != null) {
            route.add(screen(viewport, from.x(), from.y()));
        }
        for (MissionTarget t : targets) {
            if (t.state() == MissionTarget.State.PENDING || t.state() == MissionTarget.State.ACTIVE) {
                route.add(screen(viewport, t.goal().pose().x(), t.goal().pose().y()));
            }
        }
        Color routeColour = new Color(stale ? STALE : editing ? ACTIVE : ROUTE);
        try {
            if (route.size() > 1) {
                int[] xy = new int[2 * route.size()];
                for (int i = 0; i < route.size(); i++) {
                    xy[2 * i] = route.get(i).x;
                    xy[2 * i + 1] = route.get(i).y;
                }
                gc.setForeground(routeColour);
                gc.setLineWidth(2);
                gc.setLineStyle(SWT.LINE_DASH);
                gc.drawPolyline(xy);
                gc.setLineStyle(SWT.LINE_SOLID);
                gc.setLineWidth(1);
            }
            for (int i = 0; i < targets.size(); i++) {
                drawTarget(gc, viewport, targets.get(i), i, i == highlighted, editing, stale, routeColour);
            }
        } finally {
            routeColour.dispose();
        }
    }

    private static void drawTarget(GC gc, MapViewport viewport, MissionTarget t, int index, boolean highlighted,
            boolean editing, boolean stale, Color routeColour) {
        Pose2D p = t.goal().pose();
        Point c = screen(viewport, p.x(), p.y());
        int r = MARKER_RADIUS_PX;
        RGB fill = stale ? STALE : switch (t.state()) {
            case REACHED -> REACHED;
            case ACTIVE -> ACTIVE;
            case FAILED -> FAILED;
            case PENDING -> PENDING;
        };
        boolean ringed = highlighted || t.state() == MissionTarget.State.ACTIVE;
        Color fillColour = new Color(fill);
        Color ringColour = new Color(editing && highlighted ? ACTIVE : RING);
        try {
            gc.setForeground(routeColour);
            RobotPainter.drawHeading(gc, c.x, c.y, p.theta());
            gc.setAntialias(SWT.ON); // a numbered disc, as the footprints: aliased it looks like a toy
            gc.setBackground(fillColour);
            gc.fillOval(c.x - r, c.y - r, 2 * r, 2 * r);
            gc.setForeground(ringColour);
            gc.setLineWidth(ringed ? 3 : 1);
            gc.drawOval(c.x - r, c.y - r, 2 * r, 2 * r);
            gc.setLineWidth(1);
            gc.setAntialias(SWT.OFF);
            String number = String.valueOf(index + 1);
            Point size = gc.textExtent(number);
            boolean dark = fill.equals(PENDING) || fill.equals(STALE);
            gc.setForeground(gc.getDevice().getSystemColor(dark ? SWT.COLOR_BLACK : SWT.COLOR_WHITE));
            gc.drawString(number, c.x - size.x / 2, c.y - size.y / 2, true);
            gc.setForeground(gc.getDevice().getSystemColor(stale ? SWT.COLOR_GRAY : SWT.COLOR_DARK_GRAY));
            gc.drawString(MissionEditor.describe(t), c.x + r + 3, c.y + 2, true);
        } finally {
            fillColour.dispose();
            ringColour.dispose();
        }
    }

    private static Point screen(MapViewport viewport, double x, double y) {
        return new Point((int) Math.round(viewport.toScreenX(x)), (int) Math.round(viewport.toScreenY(y)));
    }
}
