package sabot.model.path;

import org.osgi.annotation.versioning.ConsumerType;

import sabot.model.geometry.Pose2D;

/**
 * A reference motion defined on [0, {@link #duration()}] seconds. Outside that interval it holds still: before 0
 * it is the start pose at rest, after the end the end pose at rest, so a caller never receives an undefined sample.
 */
@ConsumerType
public interface Trajectory {

    /** @return the trajectory's length in seconds (&ge; 0) */
    double duration();

    /**
     * @param time seconds since the trajectory's start; must be finite
     * @return the reference at {@code time}, clamped to the trajectory's interval
     * @throws IllegalArgumentException when {@code time} is NaN or infinite
     */
    TrajectorySample sample(double time);

    /** @return the pose at time 0 */
    default Pose2D startPose() {
        return sample(0).pose();
    }

    /** @return the pose at {@link #duration()} */
    default Pose2D endPose() {
        return sample(duration()).pose();
    }

    /** @return the geometric length of the path travelled, in metres (turns in place count zero) */
    double length();
}
