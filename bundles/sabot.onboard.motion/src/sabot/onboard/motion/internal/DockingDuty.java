package sabot.onboard.motion.internal;

import java.time.Instant;
import java.util.List;
import java.util.Locale;
import java.util.Optional;
import java.util.concurrent.Executor;
import java.util.function.Supplier;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionTarget;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.robot.BatteryState;
import sabot.onboard.motion.loop.BatteryGuard;
import sabot.onboard.motion.loop.ControlLoop;
import sabot.onboard.robot.CommandRefused;

/**
 * The motion task's low-battery duty (docs/USER-GUIDE.md, "Battery"): each new reading of the power board goes to the
 * {@link BatteryGuard} on the notifier thread, and its decision is carried out through the task's own commands (abort
 * the mission, a mission to the dock, so that the loop's limits, obstacles and deadman apply); whoever listens to the
 * mission is told when the robot starts or stops charging (its presence follows).
 */
final class DockingDuty {

    private static final Logger LOG = LoggerFactory.getLogger("sabot.motion");

    /** What the duty asks of the motion task. */
    interface Task {
        /** Ends the running or paused mission (a {@code cm.mission} command). */
        void abort(String reason) throws CommandRefused;

        /** Starts a mission of these targets (not queued). */
        void startMission(List<MissionTarget> targets) throws CommandRefused;

        /** The charging state changed: tell the mission's listeners (already on the notifier thread). */
        void chargingChanged();
    }

    private final BatteryGuard guard;
    private final Executor notifier;
    private final Supplier<ControlLoop.Snapshot> snapshot;
    private final Task task;
    /** The stamp of the last reading handed to the guard; the loop's thread only. */
    private Instant lastReading;
    private volatile boolean charging;

    /**
     * @param notifier the motion task's event thread, where the guard runs
     * @param snapshot the loop's latest state
     */
    DockingDuty(BatteryGuard guard, Executor notifier, Supplier<ControlLoop.Snapshot> snapshot, Task task) {
        this.guard = guard;
        this.notifier = notifier;
        this.snapshot = snapshot;
        this.task = task;
    }

    /** Loop thread, after each period: a reading not seen yet goes to the guard. */
    void periodEnded(ControlLoop.Snapshot s) {
        Optional<BatteryState> b = s.battery();
        if (b.isPresent() && !b.get().measured().equals(lastReading)) {
            lastReading = b.get().measured();
            BatteryState reading = b.get();
            notifier.execute(() -> reading(reading));
        }
    }

    /** @return whether the robot stands on its dock charging after a low battery */
    boolean charging() {
        return charging;
    }

    private void reading(BatteryState b) {
        ControlLoop.Snapshot s = snapshot.get();
        BatteryGuard.Decision d = guard.update(b, s.pose().pose(), s.mission());
        if (!d.note().isEmpty()) {
            LOG.info("{}", d.note());
        }
        if (d.goToDock().isPresent()) {
            Point2D dock = d.goToDock().get();
            try {
                MissionState now = s.mission().state();
                if (now == MissionState.RUNNING || now == MissionState.PAUSED) {
                    task.abort("battery low");
                }
                task.startMission(List.of(new MissionTarget(new Goal(new Pose2D(dock.x(), dock.y(), 0),
                        BatteryGuard.DOCK_TOLERANCE, 2 * Math.PI), MissionTarget.Action.DOCK, 0,
                        MissionTarget.State.PENDING)));
            } catch (CommandRefused e) {
                LOG.warn("battery low, but the dock at ({}, {}) cannot be reached: {}", String.format(Locale.ROOT,
                        "%.3f", dock.x()), String.format(Locale.ROOT, "%.3f", dock.y()), e.getMessage());
            }
        }
        boolean nowCharging = guard.charging();
        if (nowCharging != charging) {
            charging = nowCharging;
            task.chargingChanged();
        }
    }
}
