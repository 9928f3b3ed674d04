package sabot.workbench.views;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static sabot.workbench.views.FleetViewUpdatesUiTest.drain;
import static sabot.workbench.views.FleetViewUpdatesUiTest.waitFor;

import java.time.Instant;
import java.util.Arrays;
import java.util.List;

import org.eclipse.jface.action.ActionContributionItem;
import org.eclipse.jface.action.IContributionItem;
import org.eclipse.jface.dialogs.IDialogConstants;
import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.RGB;
import org.eclipse.swt.widgets.Button;
import org.eclipse.swt.widgets.Canvas;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Event;
import org.eclipse.swt.widgets.Menu;
import org.eclipse.swt.widgets.MenuItem;
import org.eclipse.swt.widgets.Shell;
import org.eclipse.swt.widgets.TableItem;
import org.eclipse.swt.widgets.Text;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.MissionTarget.Action;
import sabot.model.geometry.Pose2D;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.internal.DocScreenshots;
import sabot.workbench.internal.WorkbenchUiTest;
import sabot.workbench.map.MapViewport;

/**
 * Missions of several targets in the real workbench, through a {@link DrivenFleet}: a mission built on the map with
 * the mouse and the keys reaches {@code FleetState.startMission} with exactly the targets, headings, actions and waits
 * the operator gave; a robot's mission is drawn with its targets' progress on the map and in Fleet. Saves
 * {@code docs/images/workbench-mission-editor.png} and {@code workbench-mission-progress.png}.
 */
class MissionUiTest {

    /** Where the driven robot stands, m. */
    static final double ROBOT_X = 2;
    static final double ROBOT_Y = 2;
    /** A drag long enough to be one (the gesture's slop is 5 px). */
    static final int DRAG_PX = 40;

    private DrivenFleet fleet;

    /**
     * Leaves the workbench as the next test expects it: no editor, no selection, no driven fleet, and the keyboard's
     * focus in the Workspace (a dialog that closes leaves none where no window manager gives it back, and the tests
     * that type a key binding send it to the focus control).
     */
    @AfterEach
    void closeFleet() {
        WorkspaceView workspace = WorkspacePaintUiTest.workspace();
        workspace.cancelMission();
        workspace.select(null, true);
        if (fleet != null) {
            fleet.close();
            drain();
        }
        Display d = workspace.canvas().getDisplay();
        workspace.getSite().getShell().forceActive();
        workspace.setFocus();
        waitFor(() -> d.getFocusControl() == workspace.canvas(), 5, () -> "the Workspace has no focus: "
                + d.getFocusControl());
    }

    @Test
    void aMissionClickedOnTheMapIsSentWithItsTargetsHeadingsAndActions() throws Exception {
        WorkspaceView workspace = robotSelected();
        MapViewport v = workspace.viewport();
        Canvas canvas = workspace.canvas();

        ActionContributionItem newMission = toolbarItem(workspace);
        assertTrue(newMission.getAction().isEnabled(), "New Mission… disabled with a robot selected");
        newMission.getAction().run();
        assertTrue(workspace.editsMission(), "no mission editor after New Mission…");

        // 1: drag east; 2: drag north; 3: a click, facing away from 2; 4: drag south-west; 5: a click, removed
        drag(canvas, v, 4, 2, DRAG_PX, 0);
        drag(canvas, v, 4, 4, 0, -DRAG_PX);
        drag(canvas, v, 2, 4, 0, 0);
        drag(canvas, v, 1, 1, -30, 30);
        drag(canvas, v, 6, 1, 0, 0);
        assertEquals(5, workspace.missionEditor().targets().size());
        WorkbenchUiTest.key(canvas, SWT.DEL, '\u007f', 0); // the last target added is the selected one
        WorkbenchUiTest.key(canvas, 0, '1', 0);
        WorkbenchUiTest.key(canvas, 0, 'p', 0); // target 1: pass
        WorkbenchUiTest.key(canvas, 0, '4', 0);
        WorkbenchUiTest.key(canvas, 0, 'd', 0); // target 4: dock
        WorkbenchUiTest.key(canvas, 0, '2', 0);
        answerWaitDialog(canvas.getDisplay(), "Wait at target 2", "7.5");
        WorkbenchUiTest.key(canvas, 0, 'w', 0); // target 2: wait, asked in a dialog
        canvas.redraw();
        drain();
        DocScreenshots.window("workbench-mission-editor.png");

        WorkbenchUiTest.key(canvas, SWT.CR, '\r', 0);
        assertFalse(workspace.editsMission(), "the editor stays open after Enter");
        waitFor(() -> fleet.missions.size() == 1, 10, () -> "no mission sent: " + workspace.lastMessage());
        DrivenFleet.SentMission sent = fleet.missions.get(0);
        assertEquals(DrivenFleet.jid(0), sent.robot());
        assertFalse(sent.queue(), "Enter queued the mission");
        List<MissionTarget> expected = List.of(
                target(v, 4, 2, 0, Action.PASS, 0),
                target(v, 4, 4, Math.PI / 2, Action.WAIT, 7.5),
                target(v, 2, 4, Math.PI, Action.STOP, 0), // faces away from target 2, straight west
                target(v, 1, 1, Math.atan2(-30, -30), Action.DOCK, 0)); // south-west, as the gesture computes it
        assertEquals(expected, sent.targets());
        for (MissionTarget t : sent.targets()) {
            assertEquals(MissionTarget.State.PENDING, t.state());
        }
        waitFor(() -> "driven-000: start a mission of 4 target(s): done".equals(workspace.lastMessage()), 10,
                () -> "status: " + workspace.lastMessage());
    }

    @Test
    void shiftEnterQueuesTheMissionAndEscCancelsIt() {
        WorkspaceView workspace = robotSelected();
        MapViewport v = workspace.viewport();
        Canvas canvas = workspace.canvas();

        workspace.newMission();
        WorkbenchUiTest.key(canvas, SWT.CR, '\r', 0); // nothing to start yet: said, and the editor stays
        assertTrue(workspace.editsMission());
        assertEquals("driven-000: a mission needs a target: click one on the map", workspace.lastMessage());
        drag(canvas, v, 5, 3, 0, 0);
        WorkbenchUiTest.key(canvas, SWT.CR, '\r', SWT.SHIFT);
        waitFor(() -> fleet.missions.size() == 1, 10, () -> "no mission sent: " + workspace.lastMessage());
        assertTrue(fleet.missions.get(0).queue(), "Shift+Enter did not queue the mission");
        double x = v.toMapX(sx(v, 5));
        double y = v.toMapY(sy(v, 3));
        assertEquals(List.of(target(v, 5, 3, Math.atan2(y - ROBOT_Y, x - ROBOT_X), Action.STOP, 0)), fleet.missions
                .get(0).targets(), "a click faces away from the robot");

        workspace.newMission();
        drag(canvas, v, 6, 3, 0, 0);
        WorkbenchUiTest.key(canvas, SWT.ESC, '\u001b', 0);
        assertFalse(workspace.editsMission(), "Esc left the editor open");
        assertEquals(DrivenFleet.jid(0), workspace.selectedRobot(), "Esc in the editor cleared the selection");
        drain();
        assertEquals(1, fleet.missions.size(), "a cancelled mission was sent");
    }

    /**
     * A double-click (two presses, the second with a click count of 2) is one target; a mission the robot refuses
     * comes back into the editor with its targets, and goes once the operator sends it again.
     */
    @Test
    void aDoubleClickIsOneTargetAndARefusedMissionKeepsItsTargets() {
        WorkspaceView workspace = robotSelected();
        MapViewport v = workspace.viewport();
        Canvas canvas = workspace.canvas();
        workspace.newMission();
        int px = sx(v, 4);
        int py = sy(v, 2);
        click(canvas, px, py);
        Event second = new Event();
        second.x = px;
        second.y = py;
        second.button = 1;
        second.count = 2;
        canvas.notifyListeners(SWT.MouseDown, second);
        canvas.notifyListeners(SWT.MouseDoubleClick, second);
        canvas.notifyListeners(SWT.MouseUp, second);
        assertEquals(1, workspace.missionEditor().targets().size(), "a double-click added two targets");
        drag(canvas, v, 5, 3, 0, 0);
        List<MissionTarget> clicked = workspace.missionEditor().targets();

        fleet.refuseMissions = "target 2 (5.00, 3.00): no path to it";
        WorkbenchUiTest.key(canvas, SWT.CR, '\r', 0);
        String refused = "driven-000: start a mission of 2 target(s): target 2 (5.00, 3.00): no path to it "
                + "(invalid-value)" + WorkspaceView.MISSION_KEPT;
        waitFor(() -> refused.equals(workspace.lastMessage()), 10, () -> "status: " + workspace.lastMessage());
        assertTrue(workspace.editsMission(), "the editor did not come back after the refusal");
        assertEquals(clicked, workspace.missionEditor().targets(), "the refused mission's targets");
        assertTrue(fleet.missions.isEmpty(), "a refused mission was kept");

        fleet.refuseMissions = null;
        WorkbenchUiTest.key(canvas, SWT.CR, '\r', 0);
        waitFor(() -> fleet.missions.size() == 1, 10, () -> "no mission sent: " + workspace.lastMessage());
        assertEquals(clicked, fleet.missions.get(0).targets());
        assertFalse(workspace.editsMission(), "the editor stays open after an accepted mission");
    }

    @Test
    void theContextMenuSetsATargetsActionReordersAndRemovesTargetsAndQueues() {
        WorkspaceView workspace = robotSelected();
        MapViewport v = workspace.viewport();
        Canvas canvas = workspace.canvas();
        chooseFromMenu(workspace, v, 6, 6, "New Mission");
        assertTrue(workspace.editsMission(), "no mission editor after the menu's New Mission…");
        drag(canvas, v, 4, 2, 0, 0);
        drag(canvas, v, 4, 4, 0, 0);
        drag(canvas, v, 2, 4, 0, 0);
        List<MissionTarget> clicked = workspace.missionEditor().targets();

        chooseFromMenu(workspace, v, 4, 4, "Target 2: Pass"); // the menu acts on the target under the pointer
        chooseFromMenu(workspace, v, 4, 4, "Move Earlier");
        chooseFromMenu(workspace, v, 2, 4, "Remove Target 3");
        chooseFromMenu(workspace, v, 6, 6, "Queue Mission"); // on empty floor: the mission's commands
        waitFor(() -> fleet.missions.size() == 1, 10, () -> "no mission sent: " + workspace.lastMessage());
        assertTrue(fleet.missions.get(0).queue(), "Queue Mission did not queue");
        assertEquals(List.of(MissionTarget.pending(clicked.get(1).goal(), Action.PASS, 0), clicked.get(0)), fleet
                .missions.get(0).targets());
    }

    @Test
    void aRobotsMissionIsDrawnWithItsTargetsProgressOnTheMapAndInFleet() throws Exception {
        WorkspaceView workspace = robotSelected();
        MapViewport v = workspace.viewport();
        Instant at = Instant.now();
        List<MissionTarget> targets = List.of(
                MissionTarget.pending(goal(4.5, 1.5, 0), Action.PASS, 0).in(MissionTarget.State.REACHED),
                MissionTarget.pending(goal(5, 4.5, Math.PI / 2), Action.WAIT, 5).in(MissionTarget.State.REACHED),
                MissionTarget.pending(goal(3, 6.5, Math.PI), Action.STOP, 0).in(MissionTarget.State.ACTIVE),
                MissionTarget.pending(goal(1, 4, -Math.PI / 2), Action.DOCK, 0));
        MissionStatus mission = new MissionStatus(MissionState.RUNNING, false, 37, "", targets, 2, 1);
        // on its way from target 2 to target 3
        fleet.put(fleet.get(DrivenFleet.jid(0)).withPresence(Availability.BUSY, "").withPose(DrivenFleet.pose(4.2, 5.3, 2.36, at), at, DrivenFleet.receipt(
                at)).withMission(mission, at));
        workspace.show(null, false); // the previous test's answer off the map
        drain();

        String text = "running · target 3/4 · 37 % · 1 queued";
        assertEquals(text, FleetView.texts(fleet.get(DrivenFleet.jid(0)), at).get(3));
        FleetView fleetView = FleetViewUpdatesUiTest.fleetView();
        waitFor(() -> text.equals(row(fleetView, DrivenFleet.jid(0)).getText(3)), 5, () -> "Fleet's mission column: "
                + row(fleetView, DrivenFleet.jid(0)).getText(3));

        boolean[] drawn = { false };
        workspace.whenDrawn(r -> r.mission() != null && r.mission().targets().size() == targets.size(), () -> drawn[0]
                = true);
        waitFor(() -> drawn[0], 5, () -> "the robot's mission never drawn");
        ImageData screen = WorkspacePaintUiTest.screen(workspace.canvas());
        WorkspacePaintUiTest.save(screen, "target/mission-progress-canvas.png"); // to judge a failure by
        // each target's disc, left of its number: the reached ones green, the active one orange, the pending white
        RGB[] fills = { MissionPainter.REACHED, MissionPainter.REACHED, MissionPainter.ACTIVE, MissionPainter.PENDING };
        for (int i = 0; i < targets.size(); i++) {
            Pose2D p = targets.get(i).goal().pose();
            int px = (int) Math.round(v.toScreenX(p.x())) - MissionPainter.MARKER_RADIUS_PX + 3;
            int py = (int) Math.round(v.toScreenY(p.y()));
            assertEquals(fills[i], screen.palette.getRGB(screen.getPixel(px, py)), "target " + (i + 1) + " ("
                    + targets.get(i).state() + ") at " + px + "," + py);
        }
        // the route runs from the robot through the targets ahead (3, 4), not through those reached (1, 2)
        assertTrue(routeBetween(screen, v, targets.get(2), targets.get(3)) > 0, "no route from target 3 to 4");
        assertEquals(0, routeBetween(screen, v, targets.get(0), targets.get(1)), "a route through reached targets");
        DocScreenshots.window("workbench-mission-progress.png");
    }

    /** @return a Workspace showing the driven fleet's one robot, idle at ({@link #ROBOT_X}, {@link #ROBOT_Y}), selected */
    private WorkspaceView robotSelected() {
        WorkspaceView workspace = WorkspacePaintUiTest.workspace();
        fleet = new DrivenFleet();
        Instant at = Instant.now();
        fleet.put(RobotState.unknown(DrivenFleet.jid(0), "driven-000").withPresence(Availability.FREE, "").withPose(
                DrivenFleet.pose(ROBOT_X, ROBOT_Y, 0, at), at, DrivenFleet.receipt(at)).withMission(new MissionStatus(
                        MissionState.IDLE, false, 0, ""), at));
        waitFor(() -> workspace.map() != null && workspace.robot(DrivenFleet.jid(0)) != null, 10, () -> "no map or "
                + "robot: " + workspace.lastMessage());
        MapViewport v = workspace.viewport();
        v.fit(-0.5, -0.5, 7.5, 7.5, 20); // the room's left half, large enough to read in the screenshots
        workspace.canvas().redraw();
        drain();
        click(workspace.canvas(), sx(v, ROBOT_X), sy(v, ROBOT_Y));
        assertEquals(DrivenFleet.jid(0), workspace.selectedRobot(), "a click on the robot did not select it");
        return workspace;
    }

    private static ActionContributionItem toolbarItem(WorkspaceView workspace) {
        IContributionItem item = workspace.getViewSite().getActionBars().getToolBarManager().find(
                WorkspaceView.NEW_MISSION_ID);
        assertNotNull(item, "no " + WorkspaceView.NEW_MISSION + " on the Workspace's toolbar");
        return (ActionContributionItem) item;
    }

    /**
     * Opens the Workspace's context menu with the pointer at map point (x, y), as a right-click there does, and
     * chooses the item whose label (without mnemonics) starts with {@code label}.
     */
    private static void chooseFromMenu(WorkspaceView workspace, MapViewport v, double x, double y, String label) {
        Canvas c = workspace.canvas();
        c.getDisplay().setCursorLocation(c.toDisplay(sx(v, x), sy(v, y)));
        Menu menu = c.getMenu();
        menu.notifyListeners(SWT.Show, new Event()); // the menu manager fills it
        try {
            MenuItem item = Arrays.stream(menu.getItems()).filter(i -> i.getText().replace("&", "").startsWith(label))
                    .findFirst().orElseThrow(() -> new AssertionError("no '" + label + "' in the menu: " + Arrays
                            .stream(menu.getItems()).map(MenuItem::getText).toList()));
            assertTrue(item.isEnabled(), label + " is disabled");
            if ((item.getStyle() & SWT.RADIO) != 0) {
                item.setSelection(true);
            }
            item.notifyListeners(SWT.Selection, new Event());
        } finally {
            menu.notifyListeners(SWT.Hide, new Event());
        }
    }

    /** Presses at map point (x, y), drags by (dx, dy) pixels through a move, and releases: one target. */
    private static void drag(Canvas c, MapViewport v, double x, double y, int dx, int dy) {
        int px = sx(v, x);
        int py = sy(v, y);
        WorkbenchUiTest.mouse(c, SWT.MouseDown, px, py);
        WorkbenchUiTest.mouse(c, SWT.MouseMove, px + dx, py + dy);
        WorkbenchUiTest.mouse(c, SWT.MouseUp, px + dx, py + dy);
    }

    private static void click(Canvas c, int x, int y) {
        WorkbenchUiTest.mouse(c, SWT.MouseDown, x, y);
        WorkbenchUiTest.mouse(c, SWT.MouseUp, x, y);
    }

    /**
     * Answers the wait dialog once it is open (its event loop runs this): types {@code seconds} and presses OK.
     */
    private static void answerWaitDialog(Display d, String title, String seconds) {
        d.asyncExec(new Runnable() {
            private int attempts;

            @Override
            public void run() {
                for (Shell s : d.getShells()) {
                    if (title.equals(s.getText()) && s.isVisible()) {
                        WorkbenchUiTest.find(s, Text.class, t -> true).setText(seconds);
                        WorkbenchUiTest.find(s, Button.class, b -> IDialogConstants.OK_LABEL.equals(b.getText()))
                                .notifyListeners(SWT.Selection, new Event());
                        return;
                    }
                }
                if (++attempts < 10_000) {
                    d.asyncExec(this); // not open yet
                }
            }
        });
    }

    /**
     * @return the target the editor made of a gesture at map point (x, y): its position is the pixel's, a pixel holds
     *         the point within half a pixel
     */
    private static MissionTarget target(MapViewport v, double x, double y, double theta, Action action, double wait) {
        double mx = v.toMapX(sx(v, x));
        double my = v.toMapY(sy(v, y));
        assertEquals(x, mx, 0.5 / v.scale() * (1 + 1e-9)); // at most half a pixel away
        assertEquals(y, my, 0.5 / v.scale() * (1 + 1e-9));
        return MissionTarget.pending(new Goal(new Pose2D(mx, my, theta), WorkspaceView.GOAL_POSITION_TOLERANCE_M,
                WorkspaceView.GOAL_HEADING_TOLERANCE_RAD), action, wait);
    }

    private static Goal goal(double x, double y, double theta) {
        return new Goal(new Pose2D(x, y, theta), WorkspaceView.GOAL_POSITION_TOLERANCE_M,
                WorkspaceView.GOAL_HEADING_TOLERANCE_RAD);
    }

    /** @return the pixels of the route's colour on the straight line between two targets, outside their discs */
    private static int routeBetween(ImageData screen, MapViewport v, MissionTarget a, MissionTarget b) {
        double ax = v.toScreenX(a.goal().pose().x());
        double ay = v.toScreenY(a.goal().pose().y());
        double bx = v.toScreenX(b.goal().pose().x());
        double by = v.toScreenY(b.goal().pose().y());
        double length = Math.hypot(bx - ax, by - ay);
        int found = 0;
        for (double s = MissionPainter.MARKER_RADIUS_PX + 4; s < length - MissionPainter.MARKER_RADIUS_PX - 4; s++) {
            int x = (int) Math.round(ax + (bx - ax) * s / length);
            int y = (int) Math.round(ay + (by - ay) * s / length);
            if (MissionPainter.ROUTE.equals(screen.palette.getRGB(screen.getPixel(x, y)))) {
                found++;
            }
        }
        return found;
    }

    private static TableItem row(FleetView view, String jid) {
        for (TableItem item : view.table().getItems()) {
            if (item.getData() instanceof RobotState r && r.jid().equals(jid)) {
                return item;
            }
        }
        throw new AssertionError("no row for " + jid);
    }

    private static int sx(MapViewport v, double x) {
        return (int) Math.round(v.toScreenX(x));
    }

    private static int sy(MapViewport v, double y) {
        return (int) Math.round(v.toScreenY(y));
    }
}
