package sabot.onboard.motion.loop;

import java.util.ArrayDeque;
import java.util.Deque;
import java.util.List;

import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;

/**
 * The books of the robot's missions, kept on the loop's thread: the status the operator reads ({@code cm.mission}),
 * the mission of targets being run ({@link MissionRun}; after it ended, the last one, whose targets' states stay
 * reported; none for a single goal or an imposed trajectory) and the missions queued after it. The control loop decides
 * what the robot does and says so here; the ledger composes the status (targets, current target, queue length) and
 * tells the host of each change. Plain bookkeeping: no clock, no boards.
 */
final class MissionLedger {

    private final LoopHost host;
    private MissionStatus status = new MissionStatus(MissionState.IDLE, false, 0, "idle");
    private MissionRun run;
    private final Deque<List<MissionTarget>> queue = new ArrayDeque<>();

    /** @param host told of every change of the status but progress within a tenth */
    MissionLedger(LoopHost host) {
        this.host = host;
    }

    /** @return the status now */
    MissionStatus status() {
        return status;
    }

    /** @return the mission of targets being run, or the last one; null for a goal */
    MissionRun run() {
        return run;
    }

    /** @return true while a mission of targets has a target the robot is on its way to */
    boolean onTarget() {
        return run != null && run.hasCurrent();
    }

    /** A single goal or an imposed trajectory replaces the mission of targets (the queue stays). */
    void single() {
        run = null;
    }

    /** A mission of targets replaces the one before (the queue stays). @return its run */
    MissionRun start(List<MissionTarget> targets) {
        run = new MissionRun(targets);
        return run;
    }

    /** The mission ends short of its targets (failed or aborted): its current target failed. */
    void endShort() {
        if (run != null) {
            run.failed();
        }
    }

    /**
     * Queues a mission of targets after the queued ones.
     *
     * @return false when the queue is full ({@link MissionStatus#MAX_QUEUED}): nothing changed
     */
    boolean enqueue(List<MissionTarget> targets) {
        if (queue.size() >= MissionStatus.MAX_QUEUED) {
            return false;
        }
        queue.add(List.copyOf(targets));
        report(status.state(), status.progress(), status.detail());
        return true;
    }

    /** @return the missions waiting in the queue */
    int queued() {
        return queue.size();
    }

    /** @return the first queued mission, taken from the queue; null when none waits */
    List<MissionTarget> nextQueued() {
        return queue.poll();
    }

    /** Empties the queue: @return what the operator reads about it, "" when it was empty */
    String dropQueue() {
        int n = queue.size();
        queue.clear();
        return n == 0 ? "" : "; " + n + " queued mission" + (n == 1 ? "" : "s") + " dropped";
    }

    /** The status becomes {@code state}, maintenance as it was; the host hears of it. */
    void report(MissionState state, double progress, String detail) {
        report(state, status.maintenance(), progress, detail);
    }

    /** The status becomes {@code state} with the maintenance switch {@code maintenance}; the host hears of it. */
    void report(MissionState state, boolean maintenance, double progress, String detail) {
        status = run == null ? new MissionStatus(state, maintenance, progress, detail, List.of(), 0, queue.size())
                : new MissionStatus(state, maintenance, progress, detail, run.targets(), run.current(), queue
                        .size());
        host.missionChanged(status);
    }

    /** The progress becomes {@code progress}, percent; the host hears of whole tenths only (the snapshot has all). */
    void progress(double progress) {
        boolean step = Math.floor(progress / 10) != Math.floor(status.progress() / 10);
        status = status.with(status.state(), progress, status.detail());
        if (step) {
            host.missionChanged(status);
        }
    }

    /** @return the mission's progress for the fraction {@code leg} of the current leg's trajectory done, percent */
    double legProgress(double leg) {
        return run == null ? 100 * leg : run.progress(leg);
    }
}
