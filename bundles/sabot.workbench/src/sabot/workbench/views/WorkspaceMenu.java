package sabot.workbench.views;

import org.eclipse.jface.action.Action;
import org.eclipse.jface.action.IAction;
import org.eclipse.jface.action.IMenuManager;
import org.eclipse.jface.action.MenuManager;
import org.eclipse.jface.action.Separator;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.widgets.Canvas;

import sabot.controlml.payload.MissionTarget;
import sabot.workbench.fleet.RobotState;

/**
 * The Workspace's context menu: a right-click on a robot selects it; Go here (empty floor, a robot selected), New
 * Mission…, Stop and Centre act on the selected robot. While a mission is edited: the action of the target under the
 * pointer (else the selected one), its removal and place, and Start, Queue or Cancel the mission.
 */
final class WorkspaceMenu {

    private WorkspaceMenu() {
    }

    /** Puts the menu on the view's canvas. */
    static void install(WorkspaceView view, Canvas canvas, GoalGesture gesture) {
        MenuManager menu = new MenuManager();
        menu.setRemoveAllWhenShown(true);
        menu.addMenuListener(m -> {
            Point at = canvas.toControl(canvas.getDisplay().getCursorLocation());
            MissionEditor mission = view.missionEditor();
            if (mission != null) {
                missionItems(m, view, mission, mission.targetAt(view.viewport(), at.x, at.y));
                canvas.redraw(); // the target the menu acts on is ringed
                return;
            }
            String hit = view.robotAt(at.x, at.y);
            if (hit != null) {
                view.select(hit, true);
            }
            String robot = view.selectedRobot();
            RobotState known = robot == null ? null : view.robot(robot);
            m.add(action("&Go here", known != null && hit == null, () -> view.sendGoal(robot, gesture.goalFor(at, at,
                    GoalGesture.positionOf(view.robot(robot))))));
            m.add(action("New &Mission…", known != null, view::newMission));
            m.add(action("&Stop", known != null, () -> view.stopRobot(robot)));
            m.add(action("&Centre", known != null && known.pose() != null, () -> view.centreOn(robot)));
        });
        canvas.setMenu(menu.createContextMenu(canvas));
    }

    /** The edited mission's items: target {@code hit} (-1: the selected one) and the mission's commands. */
    private static void missionItems(IMenuManager m, WorkspaceView view, MissionEditor mission, int hit) {
        int i = hit >= 0 ? hit : mission.selected();
        if (i >= 0) {
            mission.select(i);
            MissionTarget t = mission.targets().get(i);
            String n = "Target " + (i + 1) + ": ";
            for (MissionTarget.Action a : MissionTarget.Action.values()) {
                String label = n + switch (a) {
                    case PASS -> "&Pass (drive through)";
                    case STOP -> "&Stop";
                    case WAIT -> "&Wait… " + (t.action() == a ? "(" + MissionEditor.describe(t) + ")" : "");
                    case DOCK -> "&Dock";
                };
                Action choice = new Action(label.strip(), IAction.AS_RADIO_BUTTON) {
                    @Override
                    public void run() {
                        if (isChecked()) { // a radio item runs when it is unchecked too
                            view.chooseAction(i, a);
                        }
                    }
                };
                choice.setChecked(t.action() == a);
                m.add(choice);
            }
            int count = mission.targets().size();
            m.add(action("Move &Earlier", i > 0, redrawn(view, () -> mission.move(i, -1))));
            m.add(action("Move &Later", i < count - 1, redrawn(view, () -> mission.move(i, 1))));
            m.add(action("&Remove Target " + (i + 1), true, redrawn(view, () -> mission.remove(i))));
            m.add(new Separator());
        }
        boolean any = !mission.targets().isEmpty();
        m.add(action("Start Mission\tEnter", any, () -> view.startMission(false)));
        m.add(action("&Queue Mission\tShift+Enter", any, () -> view.startMission(true)));
        m.add(action("Cancel Mission\tEsc", true, view::cancelMission));
    }

    /** @return {@code edit}, then the map drawn again */
    private static Runnable redrawn(WorkspaceView view, Runnable edit) {
        return () -> {
            edit.run();
            view.canvas().redraw();
        };
    }

    private static Action action(String text, boolean enabled, Runnable run) {
        Action a = new Action(text) {
            @Override
            public void run() {
                run.run();
            }
        };
        a.setEnabled(enabled);
        return a;
    }
}
