package sabot.workbench.views;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.function.Consumer;

import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.Color;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Path;
import org.eclipse.swt.graphics.RGB;
import org.eclipse.swt.graphics.TextLayout;

import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.Obstacle;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.map.MapViewport;

/**
 * Draws one robot of the fleet on the Workspace's frame: trail, planned path, goal (or a mission's targets and route,
 * {@link MissionPainter}), sonar obstacles, footprint with heading, 95 % covariance ellipse and label. Keeps, per
 * robot, what is costly to make again each frame (the label's layout, the trail's path) and disposes of it when the
 * robot is gone or at {@link #close}.
 */
final class RobotPainter implements AutoCloseable {

    /** Chi-square 95 % quantile for 2 degrees of freedom: the ellipse holds the robot with 95 % probability. */
    private static final double ELLIPSE_SCALE = Math.sqrt(5.991);
    /** A trail point closer than this (pixels, either axis) to the last one drawn is left out. */
    private static final int TRAIL_STEP_PX = 4;
    /** The selected robot's body, and what the operator is about to send (the goal gesture, a mission edited). */
    static final RGB SELECTED = new RGB(230, 120, 20);
    /** The planned path and goal (a reached target too). */
    static final RGB PATH = new RGB(40, 160, 70);
    /** Sonar obstacles (a failed target too). */
    static final RGB OBSTACLE = new RGB(210, 40, 40);
    /** Length of a goal's or a target's heading line, pixels. */
    static final int HEADING_PX = 22;

    private final MapViewport viewport;
    /** Each robot's label laid out, by JID: {@link #drawLabel}. */
    private final Map<String, TextLayout> labels = new HashMap<>();
    /** Each robot's trail as last stroked, by JID: {@link #trailPath}. */
    private final Map<String, TrailShape> trails = new HashMap<>();

    RobotPainter(MapViewport viewport) {
        this.viewport = viewport;
    }

    /**
     * A robot's trail as stroked: the trail it was made of (the same list as long as the robot has not moved
     * {@link RobotState#TRAIL_SPACING_M}), the view it was made for, and its runs as one path (null: nothing to
     * stroke).
     */
    private record TrailShape(List<Point2D> trail, ViewKey view, Path path) {
        void dispose() {
            if (path != null) {
                path.dispose();
            }
        }
    }

    void draw(GC gc, RobotState r, boolean stale, boolean selected, ViewKey view) {
        RGB bodyRgb = stale ? new RGB(150, 150, 150) : selected ? SELECTED : new RGB(30, 110, 200);
        Color body = new Color(bodyRgb);
        Color fill = new Color(overWhite(bodyRgb, stale ? 90 : 160));
        Color path = new Color(stale ? new RGB(190, 190, 190) : PATH);
        Color trail = new Color(new RGB(170, 140, 210));
        Color obstacle = new Color(stale ? new RGB(180, 180, 180) : OBSTACLE);
        try {
            Path trailPath = trailPath(gc, r, view);
            if (trailPath != null) {
                gc.setForeground(trail);
                gc.setLineWidth(2);
                gc.drawPath(trailPath);
            }
            if (r.path() != null && r.path().points().size() > 1) {
                List<Point2D> pts = new ArrayList<>();
                for (TrajectoryPoint p : r.path().points()) {
                    pts.add(new Point2D(p.x(), p.y()));
                }
                gc.setForeground(path);
                gc.setLineWidth(2);
                gc.setLineStyle(SWT.LINE_DASH);
                gc.drawPolyline(toScreen(pts));
                gc.setLineStyle(SWT.LINE_SOLID);
            }
            MissionStatus mission = r.mission();
            boolean active = mission != null && mission.state().isActive();
            if (active && !mission.targets().isEmpty()) {
                // a mission of several targets: its targets (the goal is the active one's) and the route ahead
                MissionPainter.draw(gc, viewport, GoalGesture.positionOf(r), mission.targets(), -1, false, stale);
            } else if (r.goal() != null && active) {
                drawGoal(gc, viewport, r.goal().pose(), path);
            }
            if (r.obstacles() != null) {
                gc.setForeground(obstacle);
                gc.setLineWidth(2);
                for (Obstacle o : r.obstacles().obstacles()) {
                    int rad = Math.max(3, (int) Math.round(o.radius() * viewport.scale()));
                    gc.drawOval(sx(o.x()) - rad, sy(o.y()) - rad, 2 * rad, 2 * rad);
                }
            }
            if (r.pose() == null) {
                return;
            }
            Pose2D p = r.pose().pose();
            int rad = Math.max(4, (int) Math.round(WorkspaceView.FOOTPRINT_RADIUS_M * viewport.scale()));
            int cx = sx(p.x());
            int cy = sy(p.y());
            gc.setAntialias(SWT.ON); // a round footprint and its heading: aliased, they look like toys
            // the fill is the body colour as it looked at alpha 160 (90 stale) over white, opaque: the X server
            // blends nothing; the ellipse, once seen through the fill, is drawn over it
            gc.setBackground(fill);
            gc.fillOval(cx - rad, cy - rad, 2 * rad, 2 * rad);
            gc.setAntialias(SWT.OFF);
            drawEllipse(gc, p, r.pose().covariance(), body);
            gc.setAntialias(SWT.ON);
            gc.setForeground(gc.getDevice().getSystemColor(stale ? SWT.COLOR_GRAY : SWT.COLOR_BLACK));
            gc.setLineWidth(selected ? 3 : 1);
            gc.drawOval(cx - rad, cy - rad, 2 * rad, 2 * rad);
            gc.setLineWidth(2);
            int hx = cx + (int) Math.round(rad * Math.cos(p.theta()));
            int hy = cy - (int) Math.round(rad * Math.sin(p.theta()));
            gc.drawLine(cx, cy, hx, hy);
            gc.setAntialias(SWT.OFF);
            gc.setLineWidth(1);
            // late: poses keep coming but behind (RobotState.isLate); stale: none lately, or offline
            String label = r.name() + battery(r) + (r.isLate() ? " (late)" : stale ? " (stale)" : "");
            drawLabel(gc, r.jid(), label, cx + rad + 3, cy - rad - 14);
        } finally {
            body.dispose();
            fill.dispose();
            path.dispose();
            trail.dispose();
            obstacle.dispose();
        }
    }

    /** @return the robot's battery for its label on the map: {@code  87 %}, {@code  87 % charging}, or nothing */
    static String battery(RobotState r) {
        if (r.battery() == null) {
            return "";
        }
        return String.format(java.util.Locale.ROOT, " %.0f %%%s", r.battery().stateOfCharge() * 100, r.battery()
                .charging() ? " charging" : "");
    }

    /**
     * Disposes what is kept for robots gone from the fleet (label layouts, trails) once more is kept than there are
     * robots: never more is kept than the robots.
     */
    void forgetAllBut(List<RobotState> drawn) {
        forgetGone(labels, drawn, TextLayout::dispose);
        forgetGone(trails, drawn, TrailShape::dispose);
    }

    @Override
    public void close() {
        labels.values().forEach(TextLayout::dispose);
        labels.clear();
        trails.values().forEach(TrailShape::dispose);
        trails.clear();
    }

    /** Draws a goal: a cross at the target and a line along the heading. */
    static void drawGoal(GC gc, MapViewport viewport, Pose2D g, Color colour) {
        int gx = (int) Math.round(viewport.toScreenX(g.x()));
        int gy = (int) Math.round(viewport.toScreenY(g.y()));
        gc.setForeground(colour);
        gc.setLineWidth(3);
        gc.drawLine(gx - 7, gy - 7, gx + 7, gy + 7);
        gc.drawLine(gx - 7, gy + 7, gx + 7, gy - 7);
        drawHeading(gc, gx, gy, g.theta());
    }

    /** Draws a heading: a line from a pixel along {@code theta} (rad, map frame), in the foreground colour. */
    static void drawHeading(GC gc, int x, int y, double theta) {
        gc.setLineWidth(2);
        gc.drawLine(x, y, x + (int) Math.round(HEADING_PX * Math.cos(theta)), y - (int) Math.round(HEADING_PX * Math
                .sin(theta)));
        gc.setLineWidth(1);
    }

    /** @return {@code c} drawn with {@code alpha} (0..255) over white, as an opaque colour */
    private static RGB overWhite(RGB c, int alpha) {
        return new RGB((c.red * alpha + 255 * (255 - alpha)) / 255, (c.green * alpha + 255 * (255 - alpha)) / 255,
                (c.blue * alpha + 255 * (255 - alpha)) / 255);
    }

    /**
     * Draws a robot's label with its own {@link TextLayout}, kept from paint to paint: {@code drawString} has Pango
     * lay out and shape the string at each call (100 labels: ~2.5 ms of the UI thread a paint).
     */
    private void drawLabel(GC gc, String robot, String text, int x, int y) {
        TextLayout layout = labels.get(robot);
        if (layout == null) {
            layout = new TextLayout(gc.getDevice());
            layout.setFont(gc.getFont());
            labels.put(robot, layout);
        }
        if (!text.equals(layout.getText())) {
            layout.setText(text);
        }
        layout.draw(gc, x, y);
    }

    private static <T> void forgetGone(Map<String, T> byRobot, List<RobotState> drawn, Consumer<T> dispose) {
        if (byRobot.size() > drawn.size()) {
            Set<String> kept = new HashSet<>();
            for (RobotState r : drawn) {
                kept.add(r.jid());
            }
            byRobot.entrySet().removeIf(e -> {
                boolean gone = !kept.contains(e.getKey());
                if (gone) {
                    dispose.accept(e.getValue());
                }
                return gone;
            });
        }
    }

    /**
     * A robot's trail as one path, kept from paint to paint while the robot's trail and the view stay the same: at
     * 10 Hz a robot adds a trail point every second or third pose, and a frame would otherwise project, thin out
     * ({@link TrailRuns}) and hand cairo all of the 100 robots' 600 points again (a third of the paint's CPU with
     * 100 robots, docs/WORKBENCH.md). The runs are one path, one stroke: each stroke is a composite request the
     * renderer carries out on its own (~1,700 strokes a frame as polylines, 100 as paths; one path for all the robots
     * costs twice as much, the stroker then intersecting every robot's segments with every other's).
     *
     * @return the path, or null when the trail has no segment to stroke
     */
    private Path trailPath(GC gc, RobotState r, ViewKey view) {
        TrailShape shape = trails.get(r.jid());
        if (shape == null || shape.trail() != r.trail() || !shape.view().equals(view)) {
            if (shape != null) {
                shape.dispose();
            }
            List<int[]> runs = r.trail().size() > 1 ? TrailRuns.runs(TrailRuns.decimated(toScreen(r.trail()),
                    TRAIL_STEP_PX), TRAIL_STEP_PX) : List.of();
            Path path = null;
            if (!runs.isEmpty()) {
                path = new Path(gc.getDevice());
                for (int[] run : runs) {
                    path.moveTo(run[0], run[1]);
                    for (int i = 2; i < run.length; i += 2) {
                        path.lineTo(run[i], run[i + 1]);
                    }
                }
            }
            shape = new TrailShape(r.trail(), view, path);
            trails.put(r.jid(), shape);
        }
        return shape.path();
    }

    /** The 95 % ellipse of the position's 2×2 covariance (eigenvectors of [[xx, xy], [xy, yy]]). */
    private void drawEllipse(GC gc, Pose2D p, PoseCovariance c, Color colour) {
        double tr = c.xx() + c.yy();
        double det = c.xx() * c.yy() - c.xy() * c.xy();
        double disc = Math.sqrt(Math.max(0, tr * tr / 4 - det));
        double l1 = Math.max(0, tr / 2 + disc);
        double l2 = Math.max(0, tr / 2 - disc);
        double angle = 0.5 * Math.atan2(2 * c.xy(), c.xx() - c.yy());
        double a = ELLIPSE_SCALE * Math.sqrt(l1);
        double b = ELLIPSE_SCALE * Math.sqrt(l2);
        if (a * viewport.scale() < 1) {
            return; // smaller than a pixel
        }
        // vertices about every 6 pixels of the outline (12..36): a 95 % ellipse of a well-localised robot is a few
        // pixels across, and each dotted segment costs the renderer; 100 robots are 100 ellipses a frame
        double perimeterPx = Math.PI * (a + b) * viewport.scale();
        int n = (int) Math.max(12, Math.min(36, Math.round(perimeterPx / 6)));
        int[] pts = new int[2 * n];
        for (int i = 0; i < n; i++) {
            double t = 2 * Math.PI * i / n;
            double ex = a * Math.cos(t);
            double ey = b * Math.sin(t);
            double x = p.x() + ex * Math.cos(angle) - ey * Math.sin(angle);
            double y = p.y() + ex * Math.sin(angle) + ey * Math.cos(angle);
            pts[2 * i] = sx(x);
            pts[2 * i + 1] = sy(y);
        }
        gc.setForeground(colour);
        gc.setLineWidth(1);
        gc.setLineStyle(SWT.LINE_DOT);
        gc.drawPolygon(pts);
        gc.setLineStyle(SWT.LINE_SOLID);
    }

    private int[] toScreen(List<Point2D> pts) {
        int[] out = new int[2 * pts.size()];
        for (int i = 0; i < pts.size(); i++) {
            out[2 * i] = sx(pts.get(i).x());
            out[2 * i + 1] = sy(pts.get(i).y());
        }
        return out;
    }

    private int sx(double x) {
        return (int) Math.round(viewport.toScreenX(x));
    }

    private int sy(double y) {
        return (int) Math.round(viewport.toScreenY(y));
    }
}
