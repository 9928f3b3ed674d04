package sabot.onboard.motion.internal;

import java.io.IOException;
import java.util.ArrayList;
import java.util.List;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.PidGains;
import sabot.onboard.motion.loop.RobotBoards;
import sabot.onboard.robot.CommandRefused;
import sabot.pidstep.StepFigures;
import sabot.pidstep.StepSample;
import sabot.pidstep.controlml.StepTest;

/**
 * The motor board's speed loops as an operator tunes them (cm.pid, the step test), beside the control loop: their
 * gains read and written, and a position step of one motor recorded, each failure a ControlML condition.
 */
final class MotorTuning {

    private static final Logger LOG = LoggerFactory.getLogger("sabot.motion");

    private final RobotBoards boards;
    /** One step test at a time: two would release and apply the brakes under each other. */
    private final Object stepTestLock = new Object();

    MotorTuning(RobotBoards boards) {
        this.boards = boards;
    }

    PidGains gains() throws CommandRefused {
        try {
            return boards.readGains();
        } catch (IOException e) {
            throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, "motor board: " + e.getMessage());
        }
    }

    PidGains setGains(PidGains gains) throws CommandRefused {
        try {
            return boards.writeGains(gains);
        } catch (IllegalArgumentException e) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, e.getMessage());
        } catch (IOException e) {
            throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, "motor board: " + e.getMessage());
        }
    }

    /** Judges a step before the board runs it (the collision guard: the board's step is beyond the loop's reach). */
    @FunctionalInterface
    interface StepGuard {
        /** @return why the step may not start from where the robot stands, or null */
        String blocked(int motor, double step) throws CommandRefused;
    }

    /**
     * @param now   the mission's status: the step test runs in maintenance only
     * @param guard refuses a step that would move the robot's footprint towards an obstacle
     */
    StepTest stepTest(int motor, double step, MissionStatus now, StepGuard guard) throws CommandRefused {
        synchronized (stepTestLock) {
            if (!now.maintenance()) {
                throw new CommandRefused(ControlMlCondition.INVALID_STATE, "the step test moves a wheel on its own: "
                        + "switch the robot to maintenance first (cm.mission maintenance=true); the mission is "
                        + now.state().code());
            }
            String blocked = guard.blocked(motor, step);
            if (blocked != null) {
                throw new CommandRefused(ControlMlCondition.INVALID_STATE, blocked);
            }
            RobotBoards.StepRecording r;
            try {
                r = boards.stepTest(motor, step);
            } catch (IllegalArgumentException e) {
                throw new CommandRefused(ControlMlCondition.INVALID_VALUE, e.getMessage());
            } catch (IOException e) {
                throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, "motor board: " + e.getMessage());
            }
            List<StepSample> samples = new ArrayList<>(r.measured().length);
            for (int i = 0; i < r.measured().length; i++) {
                samples.add(new StepSample(i * r.samplePeriod(), r.step(), r.measured()[i]));
            }
            LOG.info("step test of motor {}: {} m, {} samples, {}", motor, r.step(), samples.size(), StepFigures.of(
                    samples));
            return new StepTest(motor, r.step(), samples);
        }
    }
}
