package sabot.control;

import org.osgi.annotation.versioning.ProviderType;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.path.TrajectorySample;

/**
 * The controller SPI: turns a pose estimate and a reference sample into a twist, once per control period.
 * <p>
 * Contract shared by every implementation:
 * <ul>
 * <li>the returned twist is always finite; bad input (NaN/infinite pose or reference, time that is not finite or
 * goes backwards) yields a {@linkplain ControlCommand#stop stop} whose status names the cause;</li>
 * <li>limits are not the controller's job: the caller passes the output through a {@link VelocitySmoother} and
 * reports what was really applied with {@link #commandApplied}, so that dynamic controllers keep their internal
 * state consistent with the robot (anti-windup);</li>
 * <li>an instance is stateful and single-threaded: one per robot.</li>
 * </ul>
 * Implementations: {@link Controllers#pseudoinverse}, {@link Controllers#dynamicFeedbackLinearization},
 * {@link Controllers#dflPointStabilization}.
 */
@ProviderType
public interface TrackingController {

    /**
     * @param time      seconds on the caller's monotonic clock; must not decrease between calls
     * @param estimate  the robot's pose estimate, map frame
     * @param reference the reference at {@code time}; a stabilizing controller reads only its pose (the goal)
     * @return the command to apply until the next update
     */
    ControlCommand update(double time, Pose2D estimate, TrajectorySample reference);

    /**
     * Tells the controller the twist really applied after limiting (default: ignored). Non-finite values are ignored.
     */
    default void commandApplied(Twist2D applied) {
    }

    /** Forgets all internal state (compensator, last time); the next update starts afresh. */
    void reset();

    /** @return a short name for logs and reports, e.g. {@code "dfl"} */
    String name();
}
