package sabot.workbench.views;

import org.eclipse.jface.action.Action;
import org.eclipse.jface.action.MenuManager;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.widgets.Canvas;

import sabot.workbench.fleet.RobotState;

/**
 * The Workspace's context menu: a right-click on a robot selects it; Go here (empty floor, a robot selected), Stop and
 * Centre act on the selected robot.
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
            String hit = view.robotAt(at.x, at.y);
            if (hit != null) {
                view.select(hit, true);
            }
            String robot = view.selectedRobot();
            RobotState known = robot == null ? null : view.robot(robot);
            m.add(action("&Go here", known != null && hit == null, () -> view.sendGoal(robot, gesture.goalFor(at, at,
                    view.robot(robot)))));
            m.add(action("&Stop", known != null, () -> view.stopRobot(robot)));
            m.add(action("&Centre", known != null && known.pose() != null, () -> view.centreOn(robot)));
        });
        canvas.setMenu(menu.createContextMenu(canvas));
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
