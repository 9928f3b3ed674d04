package sabot.workbench.views;

import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.HashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Objects;

import org.eclipse.jface.action.Action;
import org.eclipse.jface.action.IStatusLineManager;
import org.eclipse.jface.dialogs.InputDialog;
import org.eclipse.jface.window.Window;
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
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.graphics.Rectangle;
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
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.model.geometry.Point2D;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.FleetBinding;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
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
 * <p>
 * A mission of several targets ({@link #newMission}: the view's toolbar or the context menu, a robot selected): each
 * press adds a target, a drag gives its heading (the goal gesture's); the context menu (or the keys P, S, W, D on the
 * selected target, 1..9 to select one, Delete to remove it) sets each target's action; Enter starts the mission,
 * Shift+Enter queues it, Esc cancels ({@link MissionEditor}). A robot's mission is drawn with its targets' progress
 * ({@link MissionPainter}).
 * <p>
 * The view holds the operator's state (selection, pointer, last answer) and the commands; {@link WorkspacePainter}
 * draws, {@link GoalGesture} and {@link MapNavigation} read the mouse and keys; every paint is told to the
 * {@link WorkspacePaintObserver}s.
 */
public final class WorkspaceView extends ViewPart implements ISelectionProvider {

    private static final org.slf4j.Logger LOG = org.slf4j.LoggerFactory.getLogger("sabot.workbench");

    public static final String ID = "sabot.workbench.views.workspace";
    /**
     * The key-binding context of the views that operate the fleet (Workspace, Fleet): active while one of them is the
     * active part; Stop All Robots is bound in it (plugin.xml).
     */
    public static final String FLEET_CONTEXT = "sabot.workbench.context.fleet";

    /** Footprint radius drawn, metres: the planner's default robot radius ({@code planner.robotRadius}). */
    public static final double FOOTPRINT_RADIUS_M = 0.25;
    /** Beyond the visible map, the distance within which a robot's telemetry is still leased: a second's travel. */
    static final double WATCH_MARGIN_M = 1;
    /** Most robots the map leases at their full rate: those nearest its centre (and the selected one). */
    static final int FULL_RATE_ROBOTS = 20;
    /**
     * Telemetry repaints the map at most this often, Hz: each robot's pose comes at 10 Hz, at its own moment, and five
     * patrolling robots repainted the map some 50 times a second (a core of the demo's machine). RViz renders at 30.
     */
    static final int TELEMETRY_FPS = 25;
    /** Goal tolerances sent with a click-to-goal: position m, heading rad (as {@code ./sabot controlml set-goal}). */
    public static final double GOAL_POSITION_TOLERANCE_M = 0.1;
    public static final double GOAL_HEADING_TOLERANCE_RAD = 0.2;
    /** The command that opens the mission editor: the view's toolbar and the map's context menu. */
    public static final String NEW_MISSION = "New Mission…";
    /** The id of the toolbar's {@link #NEW_MISSION} action. */
    public static final String NEW_MISSION_ID = "sabot.workbench.views.workspace.newMission";
    /** What the map says while a mission is edited (after the robot's name). */
    static final String MISSION_HINT = "new mission: click the targets in order (drag for the heading); right-click a "
            + "target for its action; Enter starts, Shift+Enter queues, Esc cancels";
    /** Added to a refused mission's answer: the editor is open again with its targets. */
    static final String MISSION_KEPT = " — the targets are kept: change them and press Enter again, or Esc";
    /** Trail points that make a running mission visible in a picture: 4 spacings, at least 20 cm driven. */
    static final int MISSION_TRAIL_POINTS = 5;

    private final MapViewport viewport = new MapViewport(50, 5, 5);
    private final List<ISelectionChangedListener> selectionListeners = new ArrayList<>();
    /** How a robot's collision guard says that it stopped before an obstacle (docs/USER-GUIDE.md). */
    static final String GUARD_STOP = "stopped: obstacle ";
    /** The robots whose guard stop the status line has told (UI thread): told once per stop. */
    private final java.util.Set<String> guardStopped = new java.util.HashSet<>();
    private final PaintObservers observers = new PaintObservers();
    private final GoalGesture gesture = new GoalGesture(viewport);
    private final DrawnWaiters waiters = new DrawnWaiters();
    private final WorkspacePainter painter = new WorkspacePainter(viewport);
    private Canvas canvas;
    private MapNavigation navigation;
    private FleetBinding fleet;
    private Point pointer;
    private String selected;
    private boolean liveShown;
    private String message;
    private boolean messageIsError;
    private String mapFrom;
    private MapFetch mapFetch;
    /** When the map was last painted (UI thread), and whether a telemetry frame waits for its time. */
    private long lastPaintNanos = System.nanoTime();
    private boolean frameScheduled;
    /** The mission being edited, or null (UI thread). */
    private MissionEditor mission;
    private Action newMissionAction;
    private final ISelectionListener otherViews = this::otherViewSelected;

    @Override
    public void createPartControl(Composite parent) {
        canvas = new Canvas(parent, SWT.DOUBLE_BUFFERED | SWT.NO_BACKGROUND);
        canvas.addPaintListener(this::paint);
        navigation = new MapNavigation(viewport, canvas);
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
            navigation.moved(e.x, e.y);
            pointer = new Point(e.x, e.y);
            canvas.redraw();
        });
        canvas.addListener(SWT.Traverse, e -> {
            if (mission != null && (e.detail == SWT.TRAVERSE_RETURN || e.detail == SWT.TRAVERSE_ESCAPE)) {
                e.doit = false; // Enter and Esc are the editor's keys, not the window's default button or close
            }
        });
        canvas.addListener(SWT.KeyDown, e -> {
            boolean editorKey = mission != null && missionKey(e.keyCode, e.character, e.stateMask);
            if (!editorKey && e.keyCode == SWT.ESC) {
                select(null, true);
            } else if (!editorKey) {
                navigation.key(e);
            }
            canvas.redraw();
        });
        WorkspaceMenu.install(this, canvas, gesture);
        newMissionAction = new Action(NEW_MISSION) {
            @Override
            public void run() {
                newMission();
            }
        };
        newMissionAction.setId(NEW_MISSION_ID);
        newMissionAction.setToolTipText("A mission of several targets for the selected robot: click them on the map");
        newMissionAction.setEnabled(false);
        getViewSite().getActionBars().getToolBarManager().add(newMissionAction);
        getSite().getService(IContextService.class).activateContext(FLEET_CONTEXT);
        getSite().setSelectionProvider(this);
        getSite().getPage().addSelectionListener(otherViews);
        fleet = new FleetBinding(canvas.getDisplay()::asyncExec, this::fleetChanged);
        mapFetch = new MapFetch(fleet, canvas, this::setMap, reason -> show(reason, true));
        observers.open();
        canvas.addDisposeListener(e -> painter.close());
    }

    @Override
    public void dispose() {
        getSite().getPage().removeSelectionListener(otherViews);
        if (fleet != null) {
            fleet.dispose();
        }
        observers.close();
        super.dispose();
    }

    // ---------------------------------------------------------------------------------------------- mouse

    private void pressed(MouseEvent e) {
        if (e.button == 2 || e.button == 1 && (e.stateMask & SWT.MOD1) != 0) {
            navigation.startPan(e.x, e.y);
            return;
        }
        if (e.button != 1) {
            return;
        }
        if (mission != null) {
            if (e.count < 2) { // the second press of a double-click is not a second target on the same spot
                gesture.press(new Point(e.x, e.y)); // a target: the release gives its heading
            }
            return;
        }
        String hit = robotAt(e.x, e.y);
        if (hit != null) {
            select(hit, true);
            return;
        }
        if (selected != null && fleet.robot(selected) != null) {
            gesture.press(new Point(e.x, e.y)); // a goal: the release gives the heading
            return;
        }
        navigation.startPan(e.x, e.y);
    }

    private void released(MouseEvent e) {
        navigation.endPan();
        if (gesture.pressed() && e.button == 1) {
            if (mission != null) {
                Goal target = gesture.release(new Point(e.x, e.y), mission.from(GoalGesture.positionOf(fleet.robot(
                        mission.robot()))));
                if (!mission.add(target)) {
                    show("a mission has at most " + MissionStatus.MAX_TARGETS + " targets", true);
                }
            } else {
                sendGoal(selected, gesture.release(new Point(e.x, e.y), GoalGesture.positionOf(fleet.robot(
                        selected))));
            }
        }
        canvas.redraw();
    }

    // ---------------------------------------------------------------------------------------------- commands

    /**
     * Sends a goal to a robot in a job; the answer appears in the status line and on the map. To a robot that is
     * offline it goes as a stored command ({@code FleetState.goToWhenOnline}): Fleet lists it until the robot, back,
     * takes it or refuses it (older than its stale limit).
     */
    public void sendGoal(String robot, Goal goal) {
        if (robot == null) {
            return;
        }
        String what = String.format(Locale.ROOT, "%s: go to (%.2f, %.2f, %.2f rad)", name(robot), goal.pose().x(),
                goal.pose().y(), goal.pose().theta());
        RobotState r = fleet.robot(robot);
        FleetState service = fleet.fleet();
        if (r != null && r.availability() == Availability.OFFLINE && service != null) {
            // an offline robot: the goal waits for it at the server, listed in Fleet until the robot answers
            show(what + ": queued until " + name(robot) + " is online (refused if older than its stale limit then)",
                    false);
            Display display = canvas.getDisplay();
            service.goToWhenOnline(robot, goal).whenComplete((done, failure) -> {
                String text = what + " (queued): " + (failure == null ? "done" : FleetJobs.describe(failure));
                if (!display.isDisposed()) {
                    display.asyncExec(() -> show(text, failure != null));
                }
            });
            return;
        }
        FleetJobs.run(what, canvas.getDisplay(), fleet.fleet(), f -> f.goTo(robot, goal), this::show);
    }

    // ---------------------------------------------------------------------------------------------- mission editor

    /**
     * Opens the mission editor for the selected robot (nothing without one): from now on each press on the map adds a
     * target, until the mission is started, queued or cancelled.
     */
    public void newMission() {
        if (selected == null || fleet.robot(selected) == null) {
            return;
        }
        if (mission != null && mission.robot().equals(selected)) {
            canvas.setFocus(); // editing it already: the targets stay
            return;
        }
        mission = new MissionEditor(selected);
        show(name(selected) + ": " + MISSION_HINT, false);
        canvas.setFocus();
    }

    /** @return true while a mission is being edited */
    public boolean editsMission() {
        return mission != null;
    }

    /** @return the mission being edited, or null */
    MissionEditor missionEditor() {
        return mission;
    }

    /**
     * Sends the mission being edited to its robot ({@code FleetState.startMission}) in a job and closes the editor; the
     * answer appears in the status line and on the map, as a goal's. A refused or failed mission opens the editor again
     * with its targets (unless the operator has begun another mission or chosen another robot meanwhile), to be
     * corrected and sent again. Without a target it says so and keeps editing.
     *
     * @param queue true: after the robot's other missions (Shift+Enter); false: now (Enter)
     */
    public void startMission(boolean queue) {
        MissionEditor m = mission;
        if (m == null) {
            return;
        }
        List<MissionTarget> targets = m.targets();
        if (targets.isEmpty()) {
            show(name(m.robot()) + ": a mission needs a target: click one on the map", true);
            return;
        }
        mission = null;
        String what = String.format(Locale.ROOT, "%s: %s a mission of %d target(s)", name(m.robot()), queue ? "queue"
                : "start", targets.size());
        FleetJobs.run(what, canvas.getDisplay(), fleet.fleet(), f -> f.startMission(m.robot(), targets, queue), (
                text, failed) -> {
                    boolean reopen = failed && mission == null && m.robot().equals(selected) && !canvas.isDisposed();
                    if (reopen) {
                        mission = m;
                    }
                    show(reopen ? text + MISSION_KEPT : text, failed);
                });
        canvas.redraw();
    }

    /** Closes the mission editor without sending anything. */
    public void cancelMission() {
        if (mission != null) {
            String robot = mission.robot();
            mission = null;
            show(name(robot) + ": new mission cancelled", false);
        }
    }

    /**
     * Sets the action of the edited mission's target {@code i}; for {@link MissionTarget.Action#WAIT} it asks how long
     * (a dialog, {@link MissionEditor#DEFAULT_WAIT_S} proposed; cancelled: nothing changes).
     */
    void chooseAction(int i, MissionTarget.Action action) {
        if (mission == null || i < 0 || i >= mission.targets().size()) {
            return;
        }
        double wait = 0;
        if (action == MissionTarget.Action.WAIT) {
            MissionTarget t = mission.targets().get(i);
            InputDialog ask = new InputDialog(canvas.getShell(), "Wait at target " + (i + 1), "Seconds the robot "
                    + "stands at target " + (i + 1) + " (above 0, at most " + MissionEditor.seconds(
                            MissionTarget.MAX_WAIT_S) + "):", MissionEditor.seconds(t.dwell() > 0 ? t.dwell()
                                    : MissionEditor.DEFAULT_WAIT_S), WorkspaceView::waitError);
            if (ask.open() != Window.OK) {
                return;
            }
            wait = Double.parseDouble(ask.getValue().strip());
        }
        mission.select(i);
        mission.setAction(i, action, wait);
        canvas.redraw();
    }

    /** @return why a typed wait is not one, or null when it is (seconds, 0 < s ≤ the longest wait) */
    static String waitError(String text) {
        try {
            double s = Double.parseDouble(text.strip());
            return s > 0 && s <= MissionTarget.MAX_WAIT_S ? null : "a wait is above 0 s and at most "
                    + MissionEditor.seconds(MissionTarget.MAX_WAIT_S) + " s";
        } catch (NumberFormatException e) {
            return "seconds, e.g. " + MissionEditor.seconds(MissionEditor.DEFAULT_WAIT_S);
        }
    }

    /**
     * The mission editor's keys: Enter starts (Shift+Enter queues), Esc cancels, Delete or Backspace removes the
     * selected target, 1..9 select a target, P, S, W, D set the selected target's action.
     *
     * @return true when the key was the editor's
     */
    private boolean missionKey(int keyCode, char character, int stateMask) {
        int i = mission.selected();
        switch (keyCode) {
            case SWT.CR, SWT.KEYPAD_CR -> startMission((stateMask & SWT.SHIFT) != 0);
            case SWT.ESC -> cancelMission();
            case SWT.DEL, SWT.BS -> {
                if (i >= 0) {
                    mission.remove(i);
                }
            }
            default -> {
                MissionTarget.Action action = switch (Character.toLowerCase(character)) {
                    case 'p' -> MissionTarget.Action.PASS;
                    case 's' -> MissionTarget.Action.STOP;
                    case 'w' -> MissionTarget.Action.WAIT;
                    case 'd' -> MissionTarget.Action.DOCK;
                    default -> null;
                };
                if (action != null) {
                    chooseAction(i, action);
                } else if (character >= '1' && character <= '9') {
                    mission.select(character - '1');
                } else {
                    return false;
                }
            }
        }
        return true;
    }

    /** Stops a robot in a job. */
    public void stopRobot(String robot) {
        if (robot != null) {
            FleetJobs.run(name(robot) + ": stop", canvas.getDisplay(), fleet.fleet(), f -> f.stop(robot), this::show);
        }
    }

    /** @return the robot's last state, or null when it is not in the fleet */
    RobotState robot(String jid) {
        return fleet.robot(jid);
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

    /** @return the last command answer shown, or null */
    public String lastMessage() {
        return message;
    }

    /** Centres the map on a robot's last pose (nothing when it has none). */
    public void centreOn(String robot) {
        RobotState r = fleet.robot(robot);
        if (r != null && r.pose() != null) {
            navigation.centreOn(r.pose().pose().x(), r.pose().pose().y());
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
        if (mission != null && !mission.robot().equals(jid)) {
            cancelMission(); // the mission was for the robot that was selected
        }
        if (newMissionAction != null) {
            newMissionAction.setEnabled(jid != null);
        }
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

    // ---------------------------------------------------------------------------------------------- fleet and map

    private void fleetChanged() {
        if (canvas.isDisposed()) {
            return;
        }
        reportGuardStops();
        if (painter.map() == null) {
            mapFetch.request();
        }
        telemetryFrame();
    }

    /** Redraws for new telemetry now, or once {@link #TELEMETRY_FPS}'s frame time since the last paint has passed. */
    private void telemetryFrame() {
        if (frameScheduled) {
            return;
        }
        long wait = lastPaintNanos + 1_000_000_000L / TELEMETRY_FPS - System.nanoTime();
        if (wait <= 0) {
            canvas.redraw();
            return;
        }
        frameScheduled = true;
        canvas.getDisplay().timerExec((int) Math.max(1, wait / 1_000_000), () -> {
            frameScheduled = false;
            if (!canvas.isDisposed()) {
                canvas.redraw();
            }
        });
    }

    /**
     * Says in the status line, once per stop, that a robot's collision guard stopped it before an obstacle
     * ({@code sabot-01: stopped: obstacle 0.31 m ahead}): the robot's own words, read from its mission's detail.
     */
    private void reportGuardStops() {
        for (RobotState r : fleet.robots()) {
            String stop = guardStop(r);
            if (stop == null) {
                guardStopped.remove(r.jid());
            } else if (guardStopped.add(r.jid())) {
                show(r.name() + ": " + stop, false);
            }
        }
    }

    /**
     * @return the part of the robot's mission detail in which its collision guard says it stopped before an obstacle
     *         ({@code stopped: obstacle 0.31 m ahead}; during a mission it follows the mission's own detail after
     *         {@code "; "}), or null
     */
    static String guardStop(RobotState r) {
        if (r.mission() == null) {
            return null;
        }
        for (String part : r.mission().detail().split("; ")) {
            if (part.startsWith(GUARD_STOP)) {
                return part;
            }
        }
        return null;
    }

    /** Shows a map (UI thread). */
    public void setMap(GridMap m, String from) {
        painter.setMap(canvas.getDisplay(), m);
        mapFrom = from;
        canvas.redraw();
    }

    /** @return the map shown, or null */
    public GridMap map() {
        return painter.map();
    }

    /** @return the JID of the robot the map came from, or null */
    public String mapSource() {
        return mapFrom;
    }

    // ---------------------------------------------------------------------------------------------- view

    /** @return the viewport (for plug-ins drawing on the map and for tests) */
    public MapViewport viewport() {
        return viewport;
    }

    /** @return the canvas (for plug-ins and tests) */
    public Canvas canvas() {
        return canvas;
    }

    /** Shows the default area. */
    public void home() {
        if (navigation != null) {
            navigation.home();
        }
    }

    /** Tells {@code observer} of this view's paints from the next on (UI thread), besides the observer services. */
    public void addPaintObserver(WorkspacePaintObserver observer) {
        observers.add(observer);
    }

    public void removePaintObserver(WorkspacePaintObserver observer) {
        observers.remove(observer);
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

    /**
     * Runs {@code then} once on the UI thread right after the first paint in which a robot was drawn live on the map
     * (map shown, pose known, telemetry fresh) and satisfied {@code condition}: no polling, the paints that telemetry
     * causes decide (the demo's screenshot waits so for a running mission).
     */
    public void whenDrawn(DrawnCondition condition, Runnable then) {
        waiters.add(condition, then);
        if (canvas != null && !canvas.isDisposed()) {
            canvas.redraw();
        }
    }

    /** @return true when a robot runs a mission whose planned path and trail (at least 20 cm of it) are drawn */
    public static boolean showsRunningMission(RobotState r) {
        return r.mission() != null && r.mission().state() == MissionState.RUNNING && r.path() != null && r.path()
                .points().size() > 1 && r.trail().size() >= MISSION_TRAIL_POINTS;
    }

    private void paint(PaintEvent e) {
        long start = System.nanoTime();
        lastPaintNanos = start;
        Display d = canvas.getDisplay();
        Rectangle area = canvas.getClientArea();
        if (area.width <= 0 || area.height <= 0) {
            return; // a view minimized or not laid out yet: no frame, and no paint to measure
        }
        List<WorkspacePaintObserver> told = observers.now();
        for (WorkspacePaintObserver o : told) {
            o.paintStarting();
        }
        Point2D robotAt = GoalGesture.positionOf(fleet.robot(selected));
        WorkspacePainter.Drawn drawn = painter.draw(d, canvas.getFont(), area, fleet.robots(),
                new WorkspacePainter.Overlay(selected, gesture.preview(pointer, mission != null ? mission.from(robotAt)
                        : robotAt), pointer, message, messageIsError, mission, robotAt));
        long copyFrom = System.nanoTime();
        painter.copyTo(e.gc);
        long end = System.nanoTime();
        if (!liveShown && !drawn.live().isEmpty()) {
            liveShown = true;
            // the figure "workbench start to first live robot on screen": from the JVM's start to this paint
            Instant now = Instant.now();
            long ms = Duration.between(ProcessHandle.current().info().startInstant().orElse(now), now).toMillis();
            LOG.info("first live robot on screen: {} on the map {} ms after the workbench started", drawn.live().get(0)
                    .name(), ms);
        }
        if (!told.isEmpty()) {
            WorkspacePaintObserver.Paint paint = new WorkspacePaintObserver.Paint(start, end, end - copyFrom, drawn
                    .all(), drawn.live(), fleet.fleet());
            for (WorkspacePaintObserver o : told) {
                o.painted(paint);
            }
        }
        waiters.painted(drawn.live(), d);
        watchShown(area);
    }

    /**
     * Leases the telemetry of the robots this view shows (docs/CONTROLML.md section 6): those on the visible part of
     * the map (with a margin of a footprint and a second's travel), the selected one, and those whose position is not
     * known yet. The {@value #FULL_RATE_ROBOTS} nearest the view's centre and the selected one at their full rate, the
     * others shown at the overview's {@link FleetState#LISTED_HZ}: a map showing a thousand robots is an overview,
     * and costs what one does. Robots off the map fall back to their base rate.
     */
    private void watchShown(Rectangle area) {
        double margin = FOOTPRINT_RADIUS_M + WATCH_MARGIN_M;
        double minX = viewport.toMapX(0) - margin;
        double maxX = viewport.toMapX(area.width) + margin;
        double minY = viewport.toMapY(area.height) - margin;
        double maxY = viewport.toMapY(0) + margin;
        List<RobotState> shown = new ArrayList<>();
        for (RobotState r : fleet.robots()) {
            if (r.pose() == null || r.jid().equals(selected) || (r.pose().pose().x() >= minX && r.pose().pose()
                    .x() <= maxX && r.pose().pose().y() >= minY && r.pose().pose().y() <= maxY)) {
                shown.add(r);
            }
        }
        if (shown.size() > FULL_RATE_ROBOTS) {
            double cx = viewport.centerX();
            double cy = viewport.centerY();
            shown.sort(Comparator.comparingDouble(r -> r.pose() == null ? 0 : Math.hypot(r.pose().pose().x() - cx,
                    r.pose().pose().y() - cy)));
        }
        Map<String, Double> rates = new HashMap<>();
        for (int i = 0; i < shown.size(); i++) {
            RobotState r = shown.get(i);
            rates.put(r.jid(), i < FULL_RATE_ROBOTS || r.jid().equals(selected) ? FleetState.SHOWN_HZ
                    : FleetState.LISTED_HZ);
        }
        fleet.watch(rates);
    }

    @Override
    public void setFocus() {
        canvas.setFocus();
    }
}
