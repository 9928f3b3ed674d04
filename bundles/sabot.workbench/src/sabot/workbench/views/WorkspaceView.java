package sabot.workbench.views;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Objects;

import org.eclipse.jface.action.Action;
import org.eclipse.jface.action.IStatusLineManager;
import org.eclipse.jface.action.MenuManager;
import org.eclipse.jface.viewers.ISelection;
import org.eclipse.jface.viewers.ISelectionChangedListener;
import org.eclipse.jface.viewers.ISelectionProvider;
import org.eclipse.jface.viewers.IStructuredSelection;
import org.eclipse.jface.viewers.SelectionChangedEvent;
import org.eclipse.jface.viewers.StructuredSelection;
import org.eclipse.swt.SWT;
import org.eclipse.swt.events.MouseEvent;
import org.eclipse.swt.events.MouseListener;
import org.eclipse.swt.events.MouseMoveListener;
import org.eclipse.swt.events.PaintEvent;
import org.eclipse.swt.graphics.Color;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.PaletteData;
import org.eclipse.swt.graphics.Path;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.graphics.RGB;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.graphics.TextLayout;
import org.eclipse.swt.widgets.Canvas;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Display;
import org.eclipse.ui.ISelectionListener;
import org.eclipse.ui.IWorkbenchPart;
import org.eclipse.ui.contexts.IContextService;
import org.eclipse.ui.part.ViewPart;
import org.osgi.annotation.versioning.ConsumerType;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.Obstacle;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.fleet.FleetBinding;
import sabot.workbench.internal.FleetJobs;
import sabot.workbench.map.MapViewport;

/**
 * The shared workspace: a map canvas in the map frame (metres, y up) with a metric grid, the frame's axes and a
 * scale bar, the robots' map (fetched with {@code cm.map}), and every robot of the {@link FleetState}: footprint with
 * heading, 95 % covariance ellipse, planned path, trail, sonar obstacles and goal; stale robots greyed (late ones too:
 * {@link RobotState#isStale}).
 * <p>
 * Mouse: click a robot to select it; with a robot selected, press at a target and drag for the heading, release sends
 * the goal (a click without drag: heading from the robot towards the target); right-click for go here, stop, centre.
 * Drag with no robot selected, with the middle button or with Ctrl to pan; wheel zooms at the pointer; double-click
 * empty floor or Home shows the default area; Esc clears the selection.
 */
public final class WorkspaceView extends ViewPart implements ISelectionProvider {

    private static final org.slf4j.Logger LOG = org.slf4j.LoggerFactory.getLogger("sabot.workbench");

    public static final String ID = "sabot.workbench.views.workspace";
    /**
     * The key-binding context of the views that operate the fleet (Workspace, Fleet): active while one of them is the
     * active part; Stop All Robots is bound in it (plugin.xml).
     */
    public static final String FLEET_CONTEXT = "sabot.workbench.context.fleet";

    /** Area shown at start and on Home: a 10 m × 10 m lab floor from the map origin. */
    private static final double[] HOME = { -1, -1, 11, 11 };
    private static final double WHEEL_ZOOM = 1.2;
    private static final int GRID_MIN_PX = 40;
    private static final int SCALE_BAR_MIN_PX = 100;
    /** Footprint radius drawn, metres: the planner's default robot radius ({@code planner.robotRadius}). */
    public static final double FOOTPRINT_RADIUS_M = 0.25;
    /** Goal tolerances sent with a click-to-goal: position m, heading rad (as {@code ./sabot controlml set-goal}). */
    public static final double GOAL_POSITION_TOLERANCE_M = 0.1;
    public static final double GOAL_HEADING_TOLERANCE_RAD = 0.2;
    /** Chi-square 95 % quantile for 2 degrees of freedom: the ellipse holds the robot with 95 % probability. */
    private static final double ELLIPSE_SCALE = Math.sqrt(5.991);
    /** Drags shorter than this (pixels) are clicks. */
    private static final int CLICK_SLOP_PX = 5;
    /** A trail point closer than this (pixels, either axis) to the last one drawn is left out. */
    private static final int TRAIL_STEP_PX = 4;
    /** Paint times kept for the frame-time figure. */
    private static final int FRAME_SAMPLES = 4096;

    private final MapViewport viewport = new MapViewport(50, 5, 5);
    private final List<ISelectionChangedListener> selectionListeners = new ArrayList<>();
    private final long[] frameNanos = new long[FRAME_SAMPLES];
    /** The paints' CPU time on the UI thread (ns), as {@link #frameNanos}. */
    private final long[] frameCpuNanos = new long[FRAME_SAMPLES];
    private final java.lang.management.ThreadMXBean threads = java.lang.management.ManagementFactory
            .getThreadMXBean();
    private long lastPaintEnd;
    /** ./sabot bench workbench's measurement hook (does nothing unless its system property is set). */
    private final sabot.workbench.internal.PaintProbe probe = sabot.workbench.internal.PaintProbe.fromSystemProperty();
    private int frames;
    private Canvas canvas;
    private FleetBinding fleet;
    private Point dragFrom;
    private Point pressAt;
    private boolean panning;
    private Point pointer;
    private boolean homed;
    private String selected;
    private boolean liveShown;
    private String message;
    private boolean messageIsError;
    /** The map drawn: the first robot's with a map, fetched once. */
    private GridMap map;
    private Image mapImage;
    /**
     * The frame the paint draws into, the canvas's size: an image in the workbench's memory, so that cairo rasterizes
     * in this process and the X server receives one image a paint instead of every shape to rasterize in software
     * (Xvfb: as much CPU again as the paint; docs/WORKBENCH.md).
     */
    private MemoryImage frame;
    /**
     * The static layers (white, the map scaled, the grid, the axes) as last drawn, and what for: redrawn only when the
     * view moves, zooms, is resized or gets another map ({@link #drawBackground}).
     */
    private MemoryImage background;
    private BackgroundKey backgroundKey;
    /** Counts the maps shown, so that the background knows when the map changed. */
    private int mapVersion;
    private String mapFrom;
    private boolean mapRequested;
    /** Each robot's label laid out, by JID: {@link #drawLabel}. */
    private final java.util.Map<String, TextLayout> labels = new java.util.HashMap<>();
    /** Each robot's trail as last stroked, by JID: {@link #trailPath}. */
    private final java.util.Map<String, TrailShape> trails = new java.util.HashMap<>();
    private final ISelectionListener otherViews = this::otherViewSelected;

    @Override
    public void createPartControl(Composite parent) {
        canvas = new Canvas(parent, SWT.DOUBLE_BUFFERED | SWT.NO_BACKGROUND);
        canvas.addPaintListener(this::paint);
        canvas.addListener(SWT.Resize, e -> {
            Rectangle r = canvas.getClientArea();
            viewport.setCanvasSize(r.width, r.height);
            if (!homed && r.width > 0 && r.height > 0) {
                home();
                homed = true;
            }
        });
        canvas.addListener(SWT.MouseVerticalWheel, e -> {
            viewport.zoomAt(Math.pow(WHEEL_ZOOM, Math.signum(e.count)), e.x, e.y);
            canvas.redraw();
        });
        canvas.addMouseListener(new MouseListener() {
            @Override
            public void mouseDown(MouseEvent e) {
                pressed(e);
            }

            @Override
            public void mouseUp(MouseEvent e) {
                released(e);
            }

            @Override
            public void mouseDoubleClick(MouseEvent e) {
                if (robotAt(e.x, e.y) == null && selected == null) {
                    home();
                }
            }
        });
        canvas.addMouseMoveListener((MouseMoveListener) e -> {
            if (dragFrom != null && panning) {
                viewport.panByPixels(e.x - dragFrom.x, e.y - dragFrom.y);
                dragFrom = new Point(e.x, e.y);
            }
            pointer = new Point(e.x, e.y);
            canvas.redraw();
        });
        canvas.addListener(SWT.KeyDown, e -> {
            int step = 40;
            switch (e.keyCode) {
                case SWT.ARROW_LEFT -> viewport.panByPixels(step, 0);
                case SWT.ARROW_RIGHT -> viewport.panByPixels(-step, 0);
                case SWT.ARROW_UP -> viewport.panByPixels(0, step);
                case SWT.ARROW_DOWN -> viewport.panByPixels(0, -step);
                case SWT.HOME -> home();
                case SWT.ESC -> select(null, true);
                default -> {
                    if (e.character == '+' || e.character == '=') {
                        viewport.zoomAt(WHEEL_ZOOM, viewport.width() / 2.0, viewport.height() / 2.0);
                    } else if (e.character == '-') {
                        viewport.zoomAt(1 / WHEEL_ZOOM, viewport.width() / 2.0, viewport.height() / 2.0);
                    }
                }
            }
            canvas.redraw();
        });
        createContextMenu();
        getSite().getService(IContextService.class).activateContext(FLEET_CONTEXT);
        getSite().setSelectionProvider(this);
        getSite().getPage().addSelectionListener(otherViews);
        fleet = new FleetBinding(canvas.getDisplay()::asyncExec, this::fleetChanged);
        canvas.addDisposeListener(e -> {
            if (mapImage != null) {
                mapImage.dispose();
            }
            if (frame != null) {
                frame.close();
            }
            if (background != null) {
                background.close();
            }
            labels.values().forEach(TextLayout::dispose);
            labels.clear();
            trails.values().forEach(TrailShape::dispose);
            trails.clear();
        });
    }

    @Override
    public void dispose() {
        getSite().getPage().removeSelectionListener(otherViews);
        if (fleet != null) {
            fleet.dispose();
        }
        super.dispose();
    }

    // ---------------------------------------------------------------------------------------------- mouse

    private void pressed(MouseEvent e) {
        if (e.button == 2 || e.button == 1 && (e.stateMask & SWT.MOD1) != 0) {
            dragFrom = new Point(e.x, e.y);
            panning = true;
            return;
        }
        if (e.button != 1) {
            return;
        }
        String hit = robotAt(e.x, e.y);
        if (hit != null) {
            select(hit, true);
            return;
        }
        if (selected != null && fleet.robot(selected) != null) {
            pressAt = new Point(e.x, e.y); // a goal: the release gives the heading
            return;
        }
        dragFrom = new Point(e.x, e.y);
        panning = true;
    }

    private void released(MouseEvent e) {
        dragFrom = null;
        panning = false;
        if (pressAt != null && e.button == 1) {
            Point at = pressAt;
            pressAt = null;
            sendGoal(selected, goalFor(at, new Point(e.x, e.y)));
        }
        canvas.redraw();
    }

    /**
     * @return the goal of a press at {@code at} released at {@code to}: the target under the press, the heading along
     *         the drag; a click without drag faces away from the robot's position
     */
    Goal goalFor(Point at, Point to) {
        double x = viewport.toMapX(at.x);
        double y = viewport.toMapY(at.y);
        double theta;
        if (Math.hypot(to.x - at.x, to.y - at.y) >= CLICK_SLOP_PX) {
            theta = Math.atan2(-(to.y - at.y), to.x - at.x); // screen y grows downwards
        } else {
            RobotState r = fleet.robot(selected);
            theta = r != null && r.pose() != null ? Math.atan2(y - r.pose().pose().y(), x - r.pose().pose().x()) : 0;
        }
        return new Goal(new Pose2D(x, y, theta), GOAL_POSITION_TOLERANCE_M, GOAL_HEADING_TOLERANCE_RAD);
    }

    /** Sends a goal to a robot in a job; the answer appears in the status line and on the map. */
    public void sendGoal(String robot, Goal goal) {
        if (robot == null) {
            return;
        }
        String what = String.format(Locale.ROOT, "%s: go to (%.2f, %.2f, %.2f rad)", name(robot), goal.pose().x(),
                goal.pose().y(), goal.pose().theta());
        FleetJobs.run(what, canvas.getDisplay(), fleet.fleet(), f -> f.goTo(robot, goal), this::show);
    }

    /** Stops a robot in a job. */
    public void stopRobot(String robot) {
        if (robot != null) {
            FleetJobs.run(name(robot) + ": stop", canvas.getDisplay(), fleet.fleet(), f -> f.stop(robot), this::show);
        }
    }

    private String name(String jid) {
        RobotState r = fleet.robot(jid);
        return r == null ? jid : r.name();
    }

    /**
     * Shows a command's answer: in the status line (an error for a refusal) and on the map (UI thread).
     *
     * @param text  for the operator, e.g. {@code sabot-01: stop: done}
     * @param error true for a refusal or failure
     */
    public void show(String text, boolean error) {
        message = text;
        messageIsError = error;
        IStatusLineManager status = getViewSite().getActionBars().getStatusLineManager();
        if (error) {
            status.setErrorMessage(text);
        } else {
            status.setErrorMessage(null);
            status.setMessage(text);
        }
        if (!canvas.isDisposed()) {
            canvas.redraw();
        }
    }

    /** @return true once a live robot has been drawn on its map */
    public boolean showsLiveRobot() {
        return liveShown;
    }

    /** A robot drawn live (fresh telemetry, a pose) on the map, the condition {@link #whenDrawn} waits for. */
    @ConsumerType
    @FunctionalInterface
    public interface DrawnCondition {
        /** @param robot a robot just drawn live on the map; never null */
        boolean holds(RobotState robot);
    }

    private record Waiter(DrawnCondition condition, Runnable then) {
    }

    private final List<Waiter> waiters = new ArrayList<>();

    /**
     * Runs {@code then} once on the UI thread right after the first paint in which a robot was drawn live on the map
     * (map shown, pose known, telemetry fresh) and satisfied {@code condition}: no polling, the paints that telemetry
     * causes decide (the demo's screenshot waits so for a running mission).
     */
    public void whenDrawn(DrawnCondition condition, Runnable then) {
        waiters.add(new Waiter(Objects.requireNonNull(condition), Objects.requireNonNull(then)));
        if (canvas != null && !canvas.isDisposed()) {
            canvas.redraw();
        }
    }

    /** @return true when a robot runs a mission whose planned path and trail (at least 20 cm of it) are drawn */
    public static boolean showsRunningMission(RobotState r) {
        return r.mission() != null && r.mission().state() == sabot.controlml.payload.MissionState.RUNNING && r
                .path() != null && r.path().points().size() > 1 && r.trail().size() >= MISSION_TRAIL_POINTS;
    }

    /** Trail points that make a running mission visible in a picture: 4 spacings, at least 20 cm driven. */
    static final int MISSION_TRAIL_POINTS = 5;

    /** @return the last command answer shown, or null (for tests) */
    public String lastMessage() {
        return message;
    }

    private void createContextMenu() {
        MenuManager menu = new MenuManager();
        menu.setRemoveAllWhenShown(true);
        menu.addMenuListener(m -> {
            Point at = canvas.toControl(canvas.getDisplay().getCursorLocation());
            String hit = robotAt(at.x, at.y);
            if (hit != null) {
                select(hit, true);
            }
            String robot = selected;
            boolean known = robot != null && fleet.robot(robot) != null;
            Action go = new Action("&Go here") {
                @Override
                public void run() {
                    sendGoal(robot, goalFor(at, at));
                }
            };
            go.setEnabled(known && hit == null);
            Action stop = new Action("&Stop") {
                @Override
                public void run() {
                    stopRobot(robot);
                }
            };
            stop.setEnabled(known);
            Action centre = new Action("&Centre") {
                @Override
                public void run() {
                    centreOn(robot);
                }
            };
            centre.setEnabled(known && fleet.robot(robot).pose() != null);
            m.add(go);
            m.add(stop);
            m.add(centre);
        });
        canvas.setMenu(menu.createContextMenu(canvas));
    }

    /** Centres the map on a robot's last pose (nothing when it has none). */
    public void centreOn(String robot) {
        RobotState r = fleet.robot(robot);
        if (r != null && r.pose() != null) {
            viewport.panByPixels(viewport.width() / 2.0 - viewport.toScreenX(r.pose().pose().x()), viewport.height()
                    / 2.0 - viewport.toScreenY(r.pose().pose().y()));
            canvas.redraw();
        }
    }

    /** @return the robot whose footprint is under a pixel, or null */
    String robotAt(int px, int py) {
        double x = viewport.toMapX(px);
        double y = viewport.toMapY(py);
        double reach = Math.max(FOOTPRINT_RADIUS_M, 8 / viewport.scale());
        for (RobotState r : fleet == null ? List.<RobotState>of() : fleet.robots()) {
            if (r.pose() != null && Math.hypot(r.pose().pose().x() - x, r.pose().pose().y() - y) <= reach) {
                return r.jid();
            }
        }
        return null;
    }

    // ---------------------------------------------------------------------------------------------- selection

    /** Selects a robot (null: none) and, when {@code announce}, tells the workbench's selection service. */
    public void select(String jid, boolean announce) {
        if (Objects.equals(jid, selected)) {
            return;
        }
        selected = jid;
        if (announce) {
            SelectionChangedEvent event = new SelectionChangedEvent(this, getSelection());
            for (ISelectionChangedListener l : List.copyOf(selectionListeners)) {
                l.selectionChanged(event);
            }
        }
        canvas.redraw();
    }

    /** @return the selected robot's JID, or null */
    public String selectedRobot() {
        return selected;
    }

    private void otherViewSelected(IWorkbenchPart part, ISelection selection) {
        if (part != this && selection instanceof IStructuredSelection s && s.getFirstElement() instanceof RobotState r) {
            select(r.jid(), false);
        }
    }

    @Override
    public ISelection getSelection() {
        RobotState r = fleet == null ? null : fleet.robot(selected);
        return r == null ? StructuredSelection.EMPTY : new StructuredSelection(r);
    }

    @Override
    public void setSelection(ISelection selection) {
        if (selection instanceof IStructuredSelection s && s.getFirstElement() instanceof RobotState r) {
            select(r.jid(), true);
        } else {
            select(null, true);
        }
    }

    @Override
    public void addSelectionChangedListener(ISelectionChangedListener listener) {
        selectionListeners.add(listener);
    }

    @Override
    public void removeSelectionChangedListener(ISelectionChangedListener listener) {
        selectionListeners.remove(listener);
    }

    // ---------------------------------------------------------------------------------------------- fleet

    private void fleetChanged() {
        if (canvas.isDisposed()) {
            return;
        }
        if (map == null && !mapRequested) {
            requestMap();
        }
        canvas.redraw();
    }

    /** Fetches the map of the first robot online (robots of one lab share it), off the UI thread. */
    private void requestMap() {
        FleetState f = fleet.fleet();
        RobotState source = fleet.robots().stream().filter(r -> r.availability()
                != sabot.workbench.fleet.Availability.OFFLINE).findFirst().orElse(null);
        if (f == null || source == null) {
            return;
        }
        mapRequested = true;
        Display display = canvas.getDisplay();
        f.map(source.jid()).whenComplete((m, e) -> display.asyncExec(() -> {
            if (canvas.isDisposed()) {
                return;
            }
            if (m != null) {
                setMap(m, source.jid());
            } else {
                mapRequested = false; // asked again with the next change
                show("map of " + source.name() + ": " + describe(e), true);
            }
        }));
    }

    private static String describe(Throwable e) {
        sabot.workbench.fleet.FleetCommandException f = sabot.workbench.fleet.FleetCommandException.in(e);
        return f != null ? f.text() + " (" + f.condition().element() + ")" : String.valueOf(e);
    }

    /** Shows a map (UI thread). */
    public void setMap(GridMap m, String from) {
        map = m;
        mapFrom = from;
        if (mapImage != null) {
            mapImage.dispose();
        }
        mapImage = new Image(canvas.getDisplay(), imageOf(m));
        mapVersion++;
        canvas.redraw();
    }

    /** @return the map shown, or null */
    public GridMap map() {
        return map;
    }

    /** @return the JID of the robot the map came from, or null */
    public String mapSource() {
        return mapFrom;
    }

    /** An 8-bit grey image of a grid, row 0 at the top (the grid's row 0 is at the bottom). */
    static ImageData imageOf(GridMap m) {
        RGB[] greys = new RGB[256];
        for (int i = 0; i < 256; i++) {
            greys[i] = new RGB(i, i, i);
        }
        ImageData data = new ImageData(m.width(), m.height(), 8, new PaletteData(greys));
        byte[] cells = m.cells();
        byte[] line = new byte[m.width()];
        for (int row = 0; row < m.height(); row++) {
            for (int col = 0; col < m.width(); col++) {
                int v = cells[row * m.width() + col];
                // map_server's look: free white, occupied black, unknown mid grey (a lighter one: less ink)
                line[col] = (byte) (v < 0 ? 214 : 255 - Math.round(v * 2.3f));
            }
            data.setPixels(0, m.height() - 1 - row, m.width(), line, 0);
        }
        return data;
    }

    // ---------------------------------------------------------------------------------------------- view

    /** @return the viewport (for plug-ins drawing on the map and for tests) */
    public MapViewport viewport() {
        return viewport;
    }

    /** @return the canvas (for tests) */
    public Canvas canvas() {
        return canvas;
    }

    /** @return how many paints there were since the view opened */
    public int frameCount() {
        return frames;
    }

    /** @return {@link System#nanoTime()} at the end of the last paint, 0 before the first */
    public long lastPaintEndNanos() {
        return lastPaintEnd;
    }

    /** @return the UI-thread CPU time of the paints so far, ns, as {@link #frameTimesNanos()} */
    public long[] frameCpuTimesNanos() {
        int n = Math.min(frames, FRAME_SAMPLES);
        long[] out = new long[n];
        for (int i = 0; i < n; i++) {
            out[i] = frameCpuNanos[(frames - n + i) % FRAME_SAMPLES];
        }
        return out;
    }

    /** @return the durations of the paints so far, nanoseconds, at most the last {@value #FRAME_SAMPLES} */
    public long[] frameTimesNanos() {
        int n = Math.min(frames, FRAME_SAMPLES);
        long[] out = new long[n];
        for (int i = 0; i < n; i++) {
            out[i] = frameNanos[(frames - n + i) % FRAME_SAMPLES];
        }
        return out;
    }

    /** Shows the default area. */
    public void home() {
        viewport.fit(HOME[0], HOME[1], HOME[2], HOME[3], 20);
        if (canvas != null && !canvas.isDisposed()) {
            canvas.redraw();
        }
    }

    private void paint(PaintEvent e) {
        long t0 = System.nanoTime();
        long cpu0 = threads.getCurrentThreadCpuTime();
        Display d = canvas.getDisplay();
        Rectangle area = canvas.getClientArea();
        if (area.width <= 0 || area.height <= 0) {
            return; // a view minimized or not laid out yet: no frame, and no paint to measure
        }
        probe.paintStarting();
        frame = MemoryImage.sized(frame, d, area);
        GC gc = new GC(frame.image());
        Drawn drawn;
        try {
            gc.setFont(canvas.getFont());
            drawn = drawFrame(gc, d, area);
        } finally {
            gc.dispose();
        }
        long copyFrom = System.nanoTime();
        frame.drawOnto(e.gc);
        lastPaintEnd = System.nanoTime();
        frameNanos[frames % FRAME_SAMPLES] = lastPaintEnd - t0;
        frameCpuNanos[frames % FRAME_SAMPLES] = threads.getCurrentThreadCpuTime() - cpu0;
        frames++;
        probe.painted(t0, lastPaintEnd - copyFrom, drawn.all(), fleet.fleet());
        if (!waiters.isEmpty()) {
            for (Waiter w : List.copyOf(waiters)) {
                if (drawn.live().stream().anyMatch(w.condition()::holds)) {
                    waiters.remove(w);
                    d.asyncExec(w.then()); // after this paint has reached the screen
                }
            }
        }
    }

    /** The view on the map a frame is drawn for: the canvas's size, the scale and the map point at its centre. */
    private record ViewKey(int width, int height, double scale, double centerX, double centerY) {
    }

    /** What the static layers were drawn for: the view and the map. */
    private record BackgroundKey(ViewKey view, int mapVersion) {
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

    /**
     * Draws the static layers: from {@link #background} as they were last drawn, after drawing them there again if
     * the view or the map changed.
     */
    private void drawBackground(GC gc, Display d, Rectangle area, ViewKey view) {
        BackgroundKey key = new BackgroundKey(view, mapVersion);
        if (!key.equals(backgroundKey)) {
            background = MemoryImage.sized(background, d, area);
            GC layers = new GC(background.image());
            try {
                layers.setFont(canvas.getFont());
                layers.setAntialias(SWT.OFF);
                layers.setBackground(d.getSystemColor(SWT.COLOR_WHITE));
                layers.fillRectangle(area);
                drawMap(layers);
                drawGrid(layers, area);
                drawAxes(layers, area);
            } finally {
                layers.dispose();
            }
            backgroundKey = key;
        }
        background.drawOnto(gc);
    }

    /** The robots a frame drew, and those of them drawn live on the map. */
    private record Drawn(List<RobotState> all, List<RobotState> live) {
    }

    private Drawn drawFrame(GC gc, Display d, Rectangle area) {
        // antialiasing only where it shows (the footprints, drawRobot): antialiased strokes cost cairo far more than
        // aliased ones (docs/WORKBENCH.md, "Paint of 100 robots without load")
        gc.setAntialias(SWT.OFF);
        ViewKey view = new ViewKey(area.width, area.height, viewport.scale(), viewport.centerX(), viewport.centerY());
        drawBackground(gc, d, area, view);
        Instant now = Instant.now();
        List<RobotState> drawn = fleet.robots();
        List<RobotState> drawnLive = new ArrayList<>();
        for (RobotState r : drawn) {
            boolean stale = r.isStale(now);
            drawRobot(gc, r, stale, view);
            if (!stale && r.pose() != null && map != null) {
                drawnLive.add(r);
            }
            if (!stale && r.pose() != null && map != null && !liveShown) {
                liveShown = true;
                // the figure "workbench start to first live robot on screen": from the JVM's start to this paint
                long ms = java.time.Duration.between(ProcessHandle.current().info().startInstant().orElse(now), now)
                        .toMillis();
                LOG.info("first live robot on screen: {} on the map {} ms after the workbench started", r.name(), ms);
            }
        }
        forgetGone(labels, drawn, TextLayout::dispose);
        forgetGone(trails, drawn, TrailShape::dispose);
        drawGoalGesture(gc);
        drawScaleBar(gc, area);
        drawPointer(gc, area);
        drawMessage(gc, area);
        return new Drawn(drawn, drawnLive);
    }

    private void drawMap(GC gc) {
        if (mapImage == null) {
            return;
        }
        double res = map.resolution();
        int x0 = (int) Math.round(viewport.toScreenX(map.origin().x()));
        int y1 = (int) Math.round(viewport.toScreenY(map.origin().y() + map.height() * res));
        int w = (int) Math.round(map.width() * res * viewport.scale());
        int h = (int) Math.round(map.height() * res * viewport.scale());
        gc.setInterpolation(SWT.NONE); // crisp cells when zoomed in
        gc.drawImage(mapImage, 0, 0, map.width(), map.height(), x0, y1, w, h);
    }

    private void drawRobot(GC gc, RobotState r, boolean stale, ViewKey view) {
        Display d = canvas.getDisplay();
        boolean sel = r.jid().equals(selected);
        RGB bodyRgb = stale ? new RGB(150, 150, 150) : sel ? new RGB(230, 120, 20) : new RGB(30, 110, 200);
        Color body = new Color(bodyRgb);
        Color fill = new Color(overWhite(bodyRgb, stale ? 90 : 160));
        Color path = new Color(stale ? new RGB(190, 190, 190) : new RGB(40, 160, 70));
        Color trail = new Color(new RGB(170, 140, 210));
        Color obstacle = new Color(stale ? new RGB(180, 180, 180) : new RGB(210, 40, 40));
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
            if (r.goal() != null && r.mission() != null && r.mission().state().isActive()) {
                drawGoal(gc, r.goal().pose(), path);
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
            int rad = Math.max(4, (int) Math.round(FOOTPRINT_RADIUS_M * viewport.scale()));
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
            gc.setForeground(d.getSystemColor(stale ? SWT.COLOR_GRAY : SWT.COLOR_BLACK));
            gc.setLineWidth(sel ? 3 : 1);
            gc.drawOval(cx - rad, cy - rad, 2 * rad, 2 * rad);
            gc.setLineWidth(2);
            int hx = cx + (int) Math.round(rad * Math.cos(p.theta()));
            int hy = cy - (int) Math.round(rad * Math.sin(p.theta()));
            gc.drawLine(cx, cy, hx, hy);
            gc.setAntialias(SWT.OFF);
            gc.setLineWidth(1);
            // late: poses keep coming but behind (RobotState.isLate); stale: none lately, or offline
            String label = r.name() + (r.isLate() ? " (late)" : stale ? " (stale)" : "");
            drawLabel(gc, r.jid(), label, cx + rad + 3, cy - rad - 14);
        } finally {
            body.dispose();
            fill.dispose();
            path.dispose();
            trail.dispose();
            obstacle.dispose();
        }
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

    /**
     * Disposes what is kept for robots gone from the fleet (label layouts, trails) once more is kept than there are
     * robots: never more is kept than the robots.
     */
    private static <T> void forgetGone(java.util.Map<String, T> byRobot, List<RobotState> drawn,
            java.util.function.Consumer<T> dispose) {
        if (byRobot.size() > drawn.size()) {
            java.util.Set<String> kept = new java.util.HashSet<>();
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

    /** @return {@code c} drawn with {@code alpha} (0..255) over white, as an opaque colour */
    static RGB overWhite(RGB c, int alpha) {
        return new RGB((c.red * alpha + 255 * (255 - alpha)) / 255, (c.green * alpha + 255 * (255 - alpha)) / 255,
                (c.blue * alpha + 255 * (255 - alpha)) / 255);
    }

    /**
     * A robot's trail as one path, kept from paint to paint while the robot's trail and the view stay the same: at
     * 10 Hz a robot adds a trail point every second or third pose, and a frame would otherwise project, thin out
     * ({@link #trailRuns}) and hand cairo all of the 100 robots' 600 points again (a third of the paint's CPU with
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
            List<int[]> runs = r.trail().size() > 1 ? trailRuns(toScreenDecimated(r.trail(), TRAIL_STEP_PX),
                    TRAIL_STEP_PX) : List.of();
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

    private void drawGoal(GC gc, Pose2D g, Color colour) {
        int gx = sx(g.x());
        int gy = sy(g.y());
        gc.setForeground(colour);
        gc.setLineWidth(3);
        gc.drawLine(gx - 7, gy - 7, gx + 7, gy + 7);
        gc.drawLine(gx - 7, gy + 7, gx + 7, gy - 7);
        gc.setLineWidth(2);
        gc.drawLine(gx, gy, gx + (int) Math.round(22 * Math.cos(g.theta())), gy - (int) Math.round(22 * Math.sin(g
                .theta())));
        gc.setLineWidth(1);
    }

    private void drawGoalGesture(GC gc) {
        if (pressAt == null || pointer == null) {
            return;
        }
        Color c = new Color(230, 120, 20);
        try {
            Goal g = goalFor(pressAt, pointer);
            drawGoal(gc, g.pose(), c);
        } finally {
            c.dispose();
        }
    }

    /**
     * A polyline's screen points without those closer than {@code minPx} to the last point kept (the last point is
     * always kept): a trail holds up to 600 points, often laid over one another; what the eye cannot tell apart the
     * renderer need not stroke.
     */
    private int[] toScreenDecimated(List<Point2D> pts, int minPx) {
        int[] out = new int[2 * pts.size()];
        int k = 0;
        for (int i = 0; i < pts.size(); i++) {
            int x = sx(pts.get(i).x());
            int y = sy(pts.get(i).y());
            boolean last = i == pts.size() - 1;
            if (k == 0 || last || Math.abs(x - out[k - 2]) >= minPx || Math.abs(y - out[k - 1]) >= minPx) {
                out[k++] = x;
                out[k++] = y;
            }
        }
        return java.util.Arrays.copyOf(out, k);
    }

    /**
     * A trail's screen polyline cut into runs that leave out segments between two points whose {@code cellPx} cells
     * the trail has already passed through: a robot that goes round the same loop (a patrol, a test circle) would
     * otherwise have its 600 points stroked lap over lap on the same pixels every frame.
     */
    static List<int[]> trailRuns(int[] xy, int cellPx) {
        List<int[]> runs = new ArrayList<>();
        CellSet visited = new CellSet(xy.length / 2);
        int start = -1;
        boolean previousSeen = false;
        for (int i = 0; i < xy.length / 2; i++) {
            boolean seen = !visited.add(Math.floorDiv(xy[2 * i], cellPx), Math.floorDiv(xy[2 * i + 1], cellPx));
            if (seen && previousSeen) {
                if (start >= 0 && i - 1 > start) {
                    runs.add(java.util.Arrays.copyOfRange(xy, 2 * start, 2 * i));
                }
                start = i; // the segment to the next new point is drawn from here
            } else if (start < 0) {
                start = i;
            }
            previousSeen = seen;
        }
        if (start >= 0 && xy.length / 2 - 1 > start) {
            runs.add(java.util.Arrays.copyOfRange(xy, 2 * start, xy.length));
        }
        return runs;
    }

    /**
     * The cells a trail has passed through: an open-addressing hash set of cell coordinates in one {@code long[]}
     * (a {@code HashSet<Long>} boxed each of a trail's up to 600 points).
     */
    static final class CellSet {
        /** A free slot; the cell of that key, (Integer.MIN_VALUE, 0), is held by {@link #holdsEmptyKey}. */
        private static final long EMPTY = Long.MIN_VALUE;
        private final long[] keys;
        private final int mask;
        private boolean holdsEmptyKey;

        /** @param most the most cells it will hold (the table is at most half full) */
        CellSet(int most) {
            keys = new long[Integer.highestOneBit(Math.max(2, most) * 2 - 1) * 2];
            mask = keys.length - 1;
            java.util.Arrays.fill(keys, EMPTY);
        }

        /** @return true if cell (col, row) was not in the set (it is now) */
        boolean add(int col, int row) {
            long key = (long) col << 32 | (row & 0xffffffffL);
            if (key == EMPTY) {
                boolean added = !holdsEmptyKey;
                holdsEmptyKey = true;
                return added;
            }
            long h = key * 0x9E3779B97F4A7C15L;
            for (int i = (int) (h >>> 40) & mask;; i = (i + 1) & mask) {
                if (keys[i] == key) {
                    return false;
                }
                if (keys[i] == EMPTY) {
                    keys[i] = key;
                    return true;
                }
            }
        }
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

    private void drawGrid(GC gc, Rectangle area) {
        double step = viewport.niceStep(GRID_MIN_PX);
        Color minor = new Color(232, 236, 240);
        Color major = new Color(200, 208, 216);
        // over a map the grid is drawn lightly, so the walls stay readable
        gc.setAlpha(mapImage != null ? 110 : 255);
        try {
            double x0 = Math.floor(viewport.toMapX(0) / step) * step;
            double x1 = viewport.toMapX(area.width);
            for (double x = x0; x <= x1; x += step) {
                gc.setForeground(isMajor(x, step) ? major : minor);
                int sx = (int) Math.round(viewport.toScreenX(x));
                gc.drawLine(sx, 0, sx, area.height);
            }
            double y0 = Math.floor(viewport.toMapY(area.height) / step) * step;
            double y1 = viewport.toMapY(0);
            for (double y = y0; y <= y1; y += step) {
                gc.setForeground(isMajor(y, step) ? major : minor);
                int sy = (int) Math.round(viewport.toScreenY(y));
                gc.drawLine(0, sy, area.width, sy);
            }
        } finally {
            gc.setAlpha(255);
            minor.dispose();
            major.dispose();
        }
    }

    private static boolean isMajor(double v, double step) {
        return Math.abs(Math.IEEEremainder(v, 5 * step)) < step / 2;
    }

    private void drawAxes(GC gc, Rectangle area) {
        int ox = (int) Math.round(viewport.toScreenX(0));
        int oy = (int) Math.round(viewport.toScreenY(0));
        int len = 60;
        gc.setLineWidth(2);
        gc.setForeground(canvas.getDisplay().getSystemColor(SWT.COLOR_DARK_RED));
        gc.drawLine(ox, oy, ox + len, oy);
        gc.drawString("x", ox + len + 3, oy - 8, true);
        gc.setForeground(canvas.getDisplay().getSystemColor(SWT.COLOR_DARK_GREEN));
        gc.drawLine(ox, oy, ox, oy - len);
        gc.drawString("y", ox - 4, oy - len - 16, true);
        gc.setLineWidth(1);
    }

    private void drawScaleBar(GC gc, Rectangle area) {
        double metres = viewport.niceStep(SCALE_BAR_MIN_PX);
        int px = (int) Math.round(metres * viewport.scale());
        int x = 16;
        int y = area.height - 20;
        gc.setForeground(canvas.getDisplay().getSystemColor(SWT.COLOR_BLACK));
        gc.setLineWidth(2);
        gc.drawLine(x, y, x + px, y);
        gc.drawLine(x, y - 5, x, y + 5);
        gc.drawLine(x + px, y - 5, x + px, y + 5);
        gc.setLineWidth(1);
        String label = MapViewport.formatLength(metres);
        Point size = gc.textExtent(label);
        gc.drawString(label, x + (px - size.x) / 2, y - size.y - 4, true);
    }

    private void drawPointer(GC gc, Rectangle area) {
        if (pointer == null) {
            return;
        }
        String text = String.format("x %.2f m, y %.2f m", viewport.toMapX(pointer.x), viewport.toMapY(pointer.y));
        Point size = gc.textExtent(text);
        gc.setForeground(canvas.getDisplay().getSystemColor(SWT.COLOR_DARK_GRAY));
        gc.drawString(text, area.width - size.x - 12, area.height - size.y - 10, true);
    }

    private void drawMessage(GC gc, Rectangle area) {
        if (message == null) {
            return;
        }
        gc.setForeground(canvas.getDisplay().getSystemColor(messageIsError ? SWT.COLOR_DARK_RED
                : SWT.COLOR_DARK_GRAY));
        gc.drawString(message, 12, 8, true);
    }

    @Override
    public void setFocus() {
        canvas.setFocus();
    }
}
