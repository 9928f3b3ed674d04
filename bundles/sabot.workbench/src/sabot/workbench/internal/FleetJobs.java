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

import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetState;

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
                    FleetCommandException refusal = FleetCommandException.in(e);
                    error = refusal != null ? refusal.text() + " (" + refusal.condition().element() + ")" : String
                            .valueOf(e.getCause());
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
