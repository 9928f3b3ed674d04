package sabot.workbench.internal;

import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.BiConsumer;
import java.util.function.Function;

import org.eclipse.core.runtime.Status;
import org.eclipse.core.runtime.jobs.Job;
import org.eclipse.swt.widgets.Display;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;

/**
 * Operator commands run as Eclipse Jobs, never on the UI thread: the job waits for the robot's answer and reports
 * it back on the UI thread, a refusal with the robot's own ControlML text.
 */
public final class FleetJobs {

    /** Longest wait for an answer; the plug-in's own request timeout (10 s) answers first. */
    static final long ANSWER_TIMEOUT_S = 30;

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench");

    private FleetJobs() {
    }

    /**
     * Stops every robot of the fleet that is online ({@link FleetState#stop}: a running mission is aborted, otherwise a
     * zero twist), all requests at once, in one job; reports how many stopped and each refusal with the robot's text.
     *
     * @param fleet  the fleet service (null: no ControlML plug-in)
     * @param report on the UI thread: the text to show and whether some robot refused or failed
     * @return the scheduled job
     */
    public static Job stopAll(Display display, FleetState fleet, BiConsumer<String, Boolean> report) {
        Job job = Job.create(STOP_ALL, monitor -> {
            String text;
            boolean failed;
            if (fleet == null) {
                text = STOP_ALL + ": no fleet: the ControlML plug-in is not installed or not running";
                failed = true;
            } else {
                java.util.Map<RobotState, java.util.concurrent.CompletableFuture<Void>> sent =
                        new java.util.LinkedHashMap<>();
                int offline = 0;
                for (RobotState r : fleet.robots()) {
                    if (r.availability() == Availability.OFFLINE) {
                        offline++;
                    } else {
                        sent.put(r, fleet.stop(r.jid()));
                    }
                }
                java.util.List<String> refusals = new java.util.ArrayList<>();
                long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(ANSWER_TIMEOUT_S);
                for (var e : sent.entrySet()) {
                    String error = await(e.getValue(), deadline);
                    if (error != null) {
                        refusals.add(e.getKey().name() + ": " + error);
                    }
                }
                failed = !refusals.isEmpty();
                text = STOP_ALL + ": " + (sent.size() - refusals.size()) + " of " + sent.size() + " robot(s) stopped"
                        + (offline > 0 ? ", " + offline + " offline" : "") + (failed ? "; " + String.join("; ",
                                refusals) : "");
            }
            if (failed) {
                LOG.warn("{}", text);
            } else {
                LOG.info("{}", text);
            }
            if (!display.isDisposed()) {
                display.asyncExec(() -> report.accept(text, failed));
            }
            return Status.OK_STATUS;
        });
        job.setPriority(Job.INTERACTIVE); // ahead of other jobs: it is the operator's emergency command
        job.schedule();
        return job;
    }

    /** The command's name, also the start of its report. */
    public static final String STOP_ALL = "Stop all robots";

    /** @return null when the request succeeded by the deadline, else why not (a refusal with the robot's text) */
    private static String await(java.util.concurrent.CompletableFuture<?> f, long deadlineNanos) {
        try {
            f.get(Math.max(0, deadlineNanos - System.nanoTime()), TimeUnit.NANOSECONDS);
            return null;
        } catch (ExecutionException e) {
            FleetCommandException refusal = FleetCommandException.in(e);
            return refusal != null ? refusal.text() + " (" + refusal.condition().element() + ")" : String.valueOf(e
                    .getCause());
        } catch (TimeoutException e) {
            return "no answer within " + ANSWER_TIMEOUT_S + " s";
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return "cancelled";
        }
    }

    /** @return a command's failure for the operator: the robot's text and its ControlML reason, or the cause */
    public static String describe(Throwable failure) {
        FleetCommandException refusal = FleetCommandException.in(failure);
        return refusal != null ? refusal.text() + " (" + refusal.condition().element() + ")" : String.valueOf(
                failure instanceof ExecutionException || failure instanceof java.util.concurrent.CompletionException
                        ? failure.getCause() : failure);
    }

    /**
     * @param what    what the operator asked, e.g. "sabot-01: go to (1.50, 4.00)"
     * @param fleet   the fleet service (null: no ControlML plug-in)
     * @param command the request
     * @param report  on the UI thread: the text to show and whether it is a refusal or failure
     * @return the scheduled job
     */
    public static Job run(String what, Display display, FleetState fleet, Function<FleetState,
            java.util.concurrent.CompletableFuture<?>> command, BiConsumer<String, Boolean> report) {
        Job job = Job.create(what, monitor -> {
            String error = null;
            if (fleet == null) {
                error = "no fleet: the ControlML plug-in is not installed or not running";
            } else {
                try {
                    command.apply(fleet).get(ANSWER_TIMEOUT_S, TimeUnit.SECONDS);
                } catch (ExecutionException e) {
                    error = describe(e);
                } catch (TimeoutException e) {
                    error = "no answer within " + ANSWER_TIMEOUT_S + " s";
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    error = "cancelled";
                }
            }
            String text = error == null ? what + ": done" : what + ": " + error;
            if (error != null) {
                LOG.warn("{}", text);
            } else {
                LOG.info("{}", text);
            }
            boolean failed = error != null;
            if (!display.isDisposed()) {
                display.asyncExec(() -> report.accept(text, failed));
            }
            // the refusal is shown where the operator looks (status line, map); an error status would add a dialog
            return Status.OK_STATUS;
        });
        job.schedule();
        return job;
    }
}
