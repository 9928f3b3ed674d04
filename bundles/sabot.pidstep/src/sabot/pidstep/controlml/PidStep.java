package sabot.pidstep.controlml;

import sabot.controlml.Resource;
import sabot.controlml.payload.NoQuery;

/**
 * The {@code cm.pid.step} resource: not one of the protocol's (section 4), but registered by the robot that serves it
 * ({@code sabot.onboard}'s endpoint) in its connection's {@link sabot.controlml.ResourceRegistry}, and used by the
 * workbench's PID plug-in to ask for it.
 * <p>
 * <b>Set</b> (no get: a step test moves a wheel): the robot, in maintenance mode only, releases its brakes, steps the
 * position loop of {@link StepTest#motor()} by {@link StepTest#step()} with the gains on the motor board, lets the
 * board record the response, brakes again and answers with the samples. Refused, with nothing moved: not in
 * maintenance ({@code unexpected-request}/{@code invalid-state}), an unknown motor or a step over the robot's limit
 * ({@code not-acceptable}/{@code invalid-value}), a motor fault or a silent board ({@code device-fault}).
 */
public final class PidStep {

    /** {@code cm.pid.step}. */
    public static final Resource<StepTest, NoQuery> RESOURCE = Resource.builder("cm.pid.step", StepTest.CODEC)
            .settable().movesTheRobot().description("position step test of one wheel's motor loop, response sampled "
                    + "on the robot").build();

    private PidStep() {
    }
}
