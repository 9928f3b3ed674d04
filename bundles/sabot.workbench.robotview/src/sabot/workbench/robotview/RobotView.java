package sabot.workbench.robotview;

import java.util.List;
import java.util.Set;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.Consumer;
import java.util.function.Function;

import org.eclipse.core.runtime.Status;
import org.eclipse.core.runtime.jobs.Job;
import org.eclipse.jface.viewers.ISelection;
import org.eclipse.jface.viewers.IStructuredSelection;
import org.eclipse.swt.SWT;
import org.eclipse.swt.custom.CLabel;
import org.eclipse.swt.layout.GridData;
import org.eclipse.swt.layout.GridLayout;
import org.eclipse.swt.widgets.Combo;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Control;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Label;
import org.eclipse.ui.ISelectionListener;
import org.eclipse.ui.IWorkbenchPart;
import org.eclipse.ui.part.ViewPart;
import org.osgi.annotation.versioning.ConsumerType;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.fleet.FleetBinding;

/**
 * The base of a plug-in's view about one robot: a robot chooser on top (it follows the robot selected in the Fleet
 * view or on the map), the plug-in's content, and a message line at the bottom where the outcome of the last request
 * is shown, a robot's refusal with its own ControlML text. The view observes {@link FleetState} (thesis rule 1) and
 * never touches the connection; requests run as Eclipse Jobs, never on the UI thread.
 */
public abstract class RobotView extends ViewPart {

    /** Longest wait for an answer; the ControlML plug-in's own request timeout (10 s) answers first. */
    public static final long ANSWER_TIMEOUT_S = 30;

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench.plugins");

    private final ISelectionListener selectionListener = this::selectionChanged;
    private FleetBinding binding;
    private Combo chooser;
    private CLabel messageLine;
    private Composite content;
    private List<String> shownJids = List.of();
    private String robot;
    private volatile String message = "";
    private volatile boolean messageIsError;
    /** The account's role on the chosen robot as the robot last said it (cm.role), or null while not known. */
    private volatile Role role;
    /** Asks of cm.role sent and not answered yet (UI thread). */
    private int roleAsks;
    /** Whether the chosen robot was online at the last fleet event (UI thread): it is asked its role on coming online. */
    private boolean robotOnline;

    @Override
    public final void createPartControl(Composite parent) {
        parent.setLayout(new GridLayout(1, false));
        Composite top = new Composite(parent, SWT.NONE);
        top.setLayout(new GridLayout(2, false));
        top.setLayoutData(new GridData(SWT.FILL, SWT.TOP, true, false));
        new Label(top, SWT.NONE).setText("Robot:");
        chooser = new Combo(top, SWT.READ_ONLY | SWT.DROP_DOWN);
        chooser.setLayoutData(new GridData(SWT.FILL, SWT.CENTER, true, false));
        chooser.addListener(SWT.Selection, e -> {
            int i = chooser.getSelectionIndex();
            choose(i < 0 ? null : shownJids.get(i));
        });
        content = new Composite(parent, SWT.NONE);
        content.setLayoutData(new GridData(SWT.FILL, SWT.FILL, true, true));
        createContent(content);
        messageLine = new CLabel(parent, SWT.NONE);
        messageLine.setLayoutData(new GridData(SWT.FILL, SWT.BOTTOM, true, false));
        getSite().getPage().addSelectionListener(selectionListener);
        binding = new FleetBinding(parent.getDisplay()::asyncExec, this::fleetChanged);
        fleetChanged();
        ISelection current = getSite().getPage().getSelection();
        if (current != null) {
            selectionChanged(null, current);
        }
    }

    /** Builds the plug-in's controls into {@code parent} (its layout is the plug-in's). */
    protected abstract void createContent(Composite parent);

    /**
     * The chosen robot changed, or its state did (presence, telemetry): on the UI thread, at most once per burst of
     * fleet events.
     *
     * @param state the chosen robot's state, or null when none is chosen
     * @param newRobot true when another robot was chosen
     */
    protected abstract void robotChanged(RobotState state, boolean newRobot);

    /** @return the composite holding the plug-in's controls (its parent is the whole view, for screenshots) */
    public final Composite content() {
        return content;
    }

    /** @return the chosen robot's bare JID, or null */
    public final String robot() {
        return robot;
    }

    /** @return the chosen robot's state as last reported, or null */
    public final RobotState robotState() {
        return binding == null ? null : binding.robot(robot);
    }

    /** @return the fleet service, or null while no ControlML plug-in provides one */
    protected final FleetState fleet() {
        return binding == null ? null : binding.fleet();
    }

    /**
     * @return the account's role on the chosen robot as the robot said it ({@code cm.role}), {@link Role#NONE} when
     *         it refuses the account, null while not known (no robot, not asked yet, no answer)
     */
    public final Role role() {
        return role;
    }

    /** @return true while an ask of the chosen robot's {@code cm.role} is on its way */
    public final boolean roleAsked() {
        return roleAsks > 0;
    }

    /**
     * Enables a control when the account's role on the chosen robot includes {@code needed}, or while the role is not
     * known (the robot judges then); otherwise disables it, its tooltip saying why (UI thread; a plug-in calls it from
     * {@link #robotChanged}).
     *
     * @param what for the operator, e.g. "writing gains"
     */
    protected final void gate(Control control, Role needed, String what) {
        Role r = role;
        boolean allowed = r == null || r.includes(needed);
        control.setEnabled(allowed && robot != null);
        control.setToolTipText(allowed ? null : what + " needs the " + needed.label() + " role on " + robot + "; the "
                + "robot says this account is " + r.withArticle() + " there (roles are granted on the lab's XMPP "
                + "server)");
    }

    /** Asks the chosen robot for the account's role ({@code cm.role}); the answer re-runs {@link #robotChanged}. */
    public final void refreshRole() {
        String jid = robot;
        FleetState fleet = fleet();
        if (jid == null || fleet == null) {
            return;
        }
        Display display = getSite().getShell().getDisplay();
        roleAsks++;
        fleet.get(jid, Resources.ROLE).whenComplete((answer, failure) -> {
            FleetCommandException refusal = failure == null ? null : FleetCommandException.in(failure);
            Role said = answer != null ? answer.role() : refusal != null && refusal.condition()
                    == ControlMlCondition.ACCESS_DENIED ? Role.NONE : null;
            if (!display.isDisposed()) {
                display.asyncExec(() -> {
                    roleAsks--;
                    if (jid.equals(robot) && said != null && said != role) {
                        role = said;
                        LOG.info("{}: this account is {} there", jid, said.withArticle());
                        robotChanged(robotState(), false);
                    }
                });
            }
        });
    }

    /** Chooses a robot (as the operator does in the chooser); null chooses none. */
    public final void choose(String jid) {
        boolean changed = !Objects.equals(jid, robot);
        robot = jid;
        if (binding != null) {
            binding.watch(jid == null ? Set.of() : Set.of(jid), FleetState.SHOWN_HZ);
        }
        if (changed) {
            role = null;
            refreshRole();
        }
        int i = jid == null ? -1 : shownJids.indexOf(jid);
        if (chooser != null && !chooser.isDisposed() && chooser.getSelectionIndex() != i) {
            if (i < 0) {
                chooser.deselectAll();
            } else {
                chooser.select(i);
            }
        }
        robotChanged(robotState(), changed);
    }

    /** @return the text of the message line: the outcome of the last request */
    public final String message() {
        return message;
    }

    /** @return true when the message line shows a refusal or failure */
    public final boolean messageIsError() {
        return messageIsError;
    }

    /** Shows a message on the message line (UI thread). */
    protected final void showMessage(String text, boolean error) {
        message = text;
        messageIsError = error;
        if (error) {
            LOG.warn("{}", text);
        } else {
            LOG.info("{}", text);
        }
        if (messageLine != null && !messageLine.isDisposed()) {
            messageLine.setText(text);
            messageLine.setForeground(error ? messageLine.getDisplay().getSystemColor(SWT.COLOR_RED) : null);
        }
    }

    /** Shows a message from any thread. */
    protected final void showMessageLater(String text, boolean error) {
        Display d = getSite().getShell().getDisplay();
        if (!d.isDisposed()) {
            d.asyncExec(() -> showMessage(text, error));
        }
    }

    /**
     * Runs a request to the chosen robot as a job: waits for the answer off the UI thread, then runs
     * {@code onSuccess} on the UI thread, or shows the refusal.
     *
     * @param what      for the operator, e.g. "read gains"; the message line says "sabot-01: read gains: ..."
     * @param command   the request, given the fleet service and the robot's JID
     * @param onSuccess on the UI thread, with the answer (may be null for commands without one)
     * @return the scheduled job, or null when no robot is chosen (the message line says so)
     */
    protected final <T> Job request(String what, RobotCommand<T> command, Consumer<T> onSuccess) {
        String jid = robot;
        if (jid == null) {
            showMessage(what + ": choose a robot first", true);
            return null;
        }
        FleetState fleet = fleet();
        String label = jid + ": " + what;
        Display display = getSite().getShell().getDisplay();
        Job job = Job.create(label, monitor -> {
            T answer = null;
            String error;
            boolean roleRefused = false;
            if (fleet == null) {
                error = "no fleet: the ControlML plug-in is not installed or not running";
            } else {
                try {
                    answer = command.apply(fleet, jid).get(ANSWER_TIMEOUT_S, TimeUnit.SECONDS);
                    error = null;
                } catch (ExecutionException e) {
                    error = reason(e);
                    FleetCommandException refusal = FleetCommandException.in(e);
                    roleRefused = refusal != null && (refusal.condition() == ControlMlCondition.SET_NOT_PERMITTED
                            || refusal.condition() == ControlMlCondition.ACCESS_DENIED);
                } catch (TimeoutException e) {
                    error = "no answer within " + ANSWER_TIMEOUT_S + " s";
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    error = "cancelled";
                }
            }
            T result = answer;
            String failure = error;
            boolean askRole = roleRefused;
            if (!display.isDisposed()) {
                display.asyncExec(() -> {
                    if (failure != null) {
                        showMessage(label + ": " + failure, true);
                        if (askRole) {
                            refreshRole(); // the role may have changed on the server: ask again
                        }
                    } else {
                        showMessage(label + ": done", false);
                        onSuccess.accept(result);
                    }
                });
            }
            // the refusal is shown in the view, where the operator looks; an error status would add a dialog
            return Status.OK_STATUS;
        });
        job.schedule();
        return job;
    }

    /** A request to one robot. */
    @FunctionalInterface
    @ConsumerType
    public interface RobotCommand<T> {
        /**
         * @param fleet the fleet service; never null
         * @param robot the robot's bare JID
         */
        CompletableFuture<T> apply(FleetState fleet, String robot);
    }

    /**
     * @return for the operator: a robot's refusal as its ControlML text and condition, e.g.
     *         {@code path 'a/../b' is not allowed (invalid-value)}, or the failure's own message
     */
    public static String reason(Throwable thrown) {
        FleetCommandException refusal = FleetCommandException.in(thrown);
        if (refusal != null) {
            return refusal.text() + " (" + refusal.condition().element() + ")";
        }
        Throwable t = thrown instanceof ExecutionException && thrown.getCause() != null ? thrown.getCause() : thrown;
        return String.valueOf(t.getMessage() != null ? t.getMessage() : t);
    }

    private void fleetChanged() {
        if (chooser == null || chooser.isDisposed()) {
            return;
        }
        List<RobotState> robots = binding.robots();
        List<String> jids = robots.stream().map(RobotState::jid).toList();
        if (!jids.equals(shownJids)) {
            shownJids = jids;
            chooser.setItems(robots.stream().map(r -> r.name() + " (" + r.jid() + ")").toArray(String[]::new));
            chooser.getParent().layout();
        }
        // a view about one robot shows its telemetry as it comes (docs/CONTROLML.md section 6, "Leases")
        binding.watch(robot == null ? Set.of() : Set.of(robot), FleetState.SHOWN_HZ);
        RobotState chosen = robotState();
        boolean online = chosen != null && chosen.availability() != Availability.OFFLINE;
        if (online && !robotOnline && role == null) {
            refreshRole(); // chosen while it was offline, or back: ask now that it can answer
        }
        robotOnline = online;
        if (robot == null && !jids.isEmpty()) {
            choose(jids.get(0));
        } else if (robot != null && jids.contains(robot)) {
            chooser.select(jids.indexOf(robot));
            robotChanged(robotState(), false);
        } else {
            robotChanged(robotState(), false);
        }
    }

    private void selectionChanged(IWorkbenchPart part, ISelection selection) {
        if (part != this && selection instanceof IStructuredSelection s && s.getFirstElement() instanceof RobotState r
                && !r.jid().equals(robot)) {
            choose(r.jid());
        }
    }

    @Override
    public void setFocus() {
        chooser.setFocus();
    }

    @Override
    public void dispose() {
        getSite().getPage().removeSelectionListener(selectionListener);
        if (binding != null) {
            binding.dispose();
        }
        super.dispose();
    }
}
