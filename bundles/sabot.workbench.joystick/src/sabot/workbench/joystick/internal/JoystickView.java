package sabot.workbench.joystick.internal;

import java.util.Locale;
import java.util.concurrent.atomic.AtomicInteger;

import org.eclipse.core.runtime.IProgressMonitor;
import org.eclipse.core.runtime.IStatus;
import org.eclipse.core.runtime.Status;
import org.eclipse.core.runtime.jobs.Job;
import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.layout.GridData;
import org.eclipse.swt.layout.GridLayout;
import org.eclipse.swt.widgets.Canvas;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Event;
import org.eclipse.swt.widgets.Label;

import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.LimitsPayload;
import sabot.controlml.payload.MissionStatus;
import sabot.model.geometry.Twist2D;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.robotview.RobotView;

/**
 * An on-screen joystick: while the operator holds the pad (mouse button down, or arrow/WASD keys held), the twist the
 * knob's position stands for is sent to the chosen robot ({@code cm.velocity} through {@link FleetState#drive}) every
 * {@link #PERIOD_MS} ms, scaled to the robot's own limits ({@code cm.limits}). Releasing the pad, losing the focus,
 * choosing another robot or losing the robot sends one zero twist; should the workbench stall instead, the twists stop
 * arriving and the robot stops by its own deadman timeout (the onboard teleop task).
 */
public final class JoystickView extends RobotView {

    public static final String ID = "sabot.workbench.joystick.view";
    /** Period of the twists while the pad is held: 10 Hz, the rate the robot's teleop deadman expects. */
    public static final long PERIOD_MS = 100;
    /** Deflection a held key stands for (of the full range): half speed, for fine moves. */
    static final double KEY_DEFLECTION = 0.5;
    private static final int MARGIN = 12;
    /** Share of the pad's radius around each axis that counts as on the axis (as a game controller's dead zone). */
    private static final double DEAD_ZONE = 0.03;

    private Canvas pad;
    private Label readout;
    /** What the robot says of its motion (its mission's detail): why it slows or stands, e.g. its collision guard. */
    private Label robotSays;
    private volatile LimitsPayload limits;
    private Job limitsRead;
    /** Knob deflection: x to the right, y up, each -1..1 (inside the unit circle). */
    private double knobX;
    private double knobY;
    private boolean mouseHeld;
    private int keysX;
    private int keysY;
    private volatile boolean held;
    private volatile Twist2D twist = Twist2D.ZERO;
    private volatile String driving;
    private final AtomicInteger sent = new AtomicInteger();
    private final Sender sender = new Sender();

    @Override
    protected void createContent(Composite parent) {
        parent.setLayout(new GridLayout(1, false));
        pad = new Canvas(parent, SWT.DOUBLE_BUFFERED | SWT.BORDER);
        GridData g = new GridData(SWT.FILL, SWT.FILL, true, true);
        g.widthHint = 220;
        g.heightHint = 220;
        pad.setLayoutData(g);
        pad.addListener(SWT.Paint, this::paint);
        pad.addListener(SWT.MouseDown, e -> {
            if (e.button == 1) {
                mouseHeld = true;
                pad.setFocus();
                moveKnob(e.x, e.y);
            }
        });
        pad.addListener(SWT.MouseMove, e -> {
            if (mouseHeld) {
                moveKnob(e.x, e.y);
            }
        });
        pad.addListener(SWT.MouseUp, e -> {
            if (e.button == 1 && mouseHeld) {
                mouseHeld = false;
                knobX = 0;
                knobY = 0;
                update();
            }
        });
        pad.addListener(SWT.KeyDown, e -> key(e, 1));
        pad.addListener(SWT.KeyUp, e -> key(e, 0));
        pad.addListener(SWT.FocusOut, e -> releaseAll("focus lost"));
        readout = new Label(parent, SWT.NONE);
        readout.setLayoutData(new GridData(SWT.FILL, SWT.BOTTOM, true, false));
        readout.setText("Hold the pad (or arrows / WASD) to drive; release to stop.");
        robotSays = new Label(parent, SWT.NONE);
        robotSays.setLayoutData(new GridData(SWT.FILL, SWT.BOTTOM, true, false));
    }

    /** @return the robot's own words under the pad ("robot: idle — stopped: obstacle 0.06 m ahead"), for tests */
    public String robotSays() {
        return robotSays.getText();
    }

    @Override
    protected void robotChanged(RobotState state, boolean newRobot) {
        gate(pad, Role.OPERATOR, "Driving with the joystick");
        MissionStatus m = state == null ? null : state.mission();
        String says = m == null ? "" : "robot: " + m.state().code() + (m.detail().isBlank() ? "" : " — " + m.detail());
        if (!says.equals(robotSays.getText())) {
            robotSays.setText(says);
        }
        if (newRobot) {
            releaseAll("another robot chosen");
            limits = null;
            limitsRead = null;
        } else if (held && (state == null || state.availability() == Availability.OFFLINE)) {
            releaseAll("robot offline");
        }
        // the pad is scaled to the robot's limits: read them once it is online (again after a failed read, e.g.
        // while the workbench was reconnecting)
        if (state != null && limits == null && state.availability() != Availability.OFFLINE && (limitsRead == null
                || limitsRead.getResult() != null)) {
            String jid = state.jid();
            limitsRead = request("read limits", (fleet, robot) -> fleet.get(robot, Resources.LIMITS), l -> {
                if (jid.equals(robot())) {
                    limits = l;
                    showMessage(String.format(Locale.ROOT, "%s: limits %.2f m/s, %.2f rad/s", jid, l
                            .maxLinearSpeed(), l.maxAngularSpeed()), false);
                }
            });
        }
    }

    private void key(Event e, int down) {
        int code = e.keyCode;
        char c = Character.toLowerCase(e.character);
        if (code == SWT.ARROW_UP || c == 'w') {
            keysY = down;
        } else if (code == SWT.ARROW_DOWN || c == 's') {
            keysY = -down;
        } else if (code == SWT.ARROW_LEFT || c == 'a') {
            keysX = -down;
        } else if (code == SWT.ARROW_RIGHT || c == 'd') {
            keysX = down;
        } else {
            return;
        }
        if (!mouseHeld) {
            knobX = keysX * KEY_DEFLECTION;
            knobY = keysY * KEY_DEFLECTION;
        }
        update();
    }

    private void moveKnob(int x, int y) {
        Point size = pad.getSize();
        double radius = radius(size);
        // from the pad's centre to the pointer's pixel centre; an axis within the dead zone is zero, so that a drag
        // along the cross drives straight (or turns in place) whatever half pixel the pad's size puts the centre on
        double dx = deadZone((x + 0.5 - size.x / 2.0) / radius);
        double dy = deadZone(-(y + 0.5 - size.y / 2.0) / radius);
        double r = Math.hypot(dx, dy);
        if (r > 1) {
            dx /= r;
            dy /= r;
        }
        knobX = dx;
        knobY = dy;
        update();
    }

    /** Turns the knob into a twist and starts or stops sending. */
    private void update() {
        boolean nowHeld = mouseHeld || keysX != 0 || keysY != 0;
        LimitsPayload l = limits;
        if (nowHeld && l == null) {
            showMessage("the robot's limits are not known yet: not driving", true);
            nowHeld = false;
        }
        if (nowHeld) {
            // up = forward; right = turn clockwise (negative angular, the map's counter-clockwise convention)
            twist = new Twist2D(knobY * l.maxLinearSpeed(), -knobX * l.maxAngularSpeed());
            if (!held) {
                held = true;
                driving = robot();
                sender.schedule();
            }
        } else if (held) {
            stop("released");
        }
        readout.setText(String.format(Locale.ROOT, "%s: linear %.2f m/s, angular %.2f rad/s", held ? "driving"
                : "released", twist.linear(), twist.angular()));
        pad.redraw();
    }

    private void releaseAll(String why) {
        mouseHeld = false;
        keysX = 0;
        keysY = 0;
        knobX = 0;
        knobY = 0;
        if (held) {
            stop(why);
        }
        if (pad != null && !pad.isDisposed()) {
            pad.redraw();
        }
    }

    /** Stops sending and sends one zero twist, so the robot stops at once rather than at its deadman timeout. */
    private void stop(String why) {
        held = false;
        twist = Twist2D.ZERO;
        sender.cancel();
        String jid = driving;
        FleetState fleet = fleet();
        if (jid != null && fleet != null) {
            JoystickPlugin.log().info("{}: joystick {}: stop", jid, why);
            Job.create(jid + ": joystick stop", monitor -> {
                fleet.drive(jid, Twist2D.ZERO).whenComplete((ok, failure) -> {
                    if (failure != null) {
                        showMessageLater(jid + ": stop: " + reason(failure), true);
                    }
                });
                return Status.OK_STATUS;
            }).schedule();
        }
    }

    /** Sends the held twist every period; a robot's refusal goes to the message line. */
    private final class Sender extends Job {
        private long next;

        Sender() {
            super("joystick");
            setSystem(true);
        }

        @Override
        protected IStatus run(IProgressMonitor monitor) {
            String jid = driving;
            FleetState fleet = fleet();
            if (!held || monitor.isCanceled() || jid == null) {
                return Status.CANCEL_STATUS;
            }
            if (fleet == null) {
                showMessageLater("no fleet: the ControlML plug-in is not installed or not running", true);
                return Status.OK_STATUS;
            }
            Twist2D t = twist;
            sent.incrementAndGet();
            fleet.drive(jid, t).whenComplete((ok, failure) -> {
                if (failure != null && held) {
                    showMessageLater(jid + ": drive: " + reason(failure), true);
                }
            });
            // fixed rate: the next twist is due one period after this one was due, not after this run ended
            long now = System.nanoTime();
            next = next == 0 || next < now - PERIOD_MS * 2_000_000 ? now + PERIOD_MS * 1_000_000 : next + PERIOD_MS
                    * 1_000_000;
            if (held) {
                schedule(Math.max(0, (next - System.nanoTime()) / 1_000_000));
            } else {
                next = 0;
            }
            return Status.OK_STATUS;
        }
    }

    private static double deadZone(double axis) {
        return Math.abs(axis) < DEAD_ZONE ? 0 : axis;
    }

    private static double radius(Point size) {
        return Math.max(10, Math.min(size.x, size.y) / 2.0 - MARGIN);
    }

    private void paint(Event e) {
        GC gc = e.gc;
        Point size = pad.getSize();
        double r = radius(size);
        int cx = size.x / 2;
        int cy = size.y / 2;
        gc.setAntialias(SWT.ON);
        gc.setBackground(pad.getDisplay().getSystemColor(SWT.COLOR_WIDGET_LIGHT_SHADOW));
        gc.fillOval((int) (cx - r), (int) (cy - r), (int) (2 * r), (int) (2 * r));
        gc.setForeground(pad.getDisplay().getSystemColor(SWT.COLOR_DARK_GRAY));
        gc.drawOval((int) (cx - r), (int) (cy - r), (int) (2 * r), (int) (2 * r));
        gc.drawLine((int) (cx - r), cy, (int) (cx + r), cy);
        gc.drawLine(cx, (int) (cy - r), cx, (int) (cy + r));
        int kx = (int) Math.round(cx + knobX * r);
        int ky = (int) Math.round(cy - knobY * r);
        int knob = (int) Math.max(8, r / 5);
        gc.setBackground(pad.getDisplay().getSystemColor(held ? SWT.COLOR_DARK_GREEN : SWT.COLOR_DARK_BLUE));
        gc.fillOval(kx - knob, ky - knob, 2 * knob, 2 * knob);
    }

    /** @return the pad (for tests: mouse events go there) */
    public Canvas pad() {
        return pad;
    }

    /** @return true while the pad is held and twists are being sent */
    public boolean held() {
        return held;
    }

    /** @return the twist being sent (zero when released) */
    public Twist2D twist() {
        return twist;
    }

    /** @return the robot's limits the pad is scaled to, or null until read */
    public LimitsPayload limits() {
        return limits;
    }

    /** @return how many twists were sent since the view opened */
    public int sentCount() {
        return sent.get();
    }

    @Override
    public void dispose() {
        releaseAll("view closed");
        super.dispose();
    }
}
