package sabot.onboard.internal.motion;

import java.util.List;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;

import sabot.model.geometry.Pose2D;
import sabot.model.map.MapLandmark;
import sabot.model.robot.RobotDescriptions;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code localizer}: the settings of the pose estimate (start pose, initial uncertainty, inertial fusion). The
 * control loop creates its {@link Localizer} from them. Settings: OSGI-INF/metatype/localizer.xml.
 */
@Component(name = "sabot.task.localizer", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, LocalizerTask.class })
public final class LocalizerTask implements OnboardTask {

    /** Settings (names match the Metatype description). */
    public @interface Config {
        /** @return start x in the map frame, m */
        double startX() default 0;

        /** @return start y in the map frame, m */
        double startY() default 0;

        /** @return start heading, rad */
        double startTheta() default 0;

        /** @return initial standard deviation of x and y, m */
        double initialSigmaXY() default 0.02;

        /** @return initial standard deviation of the heading, rad */
        double initialSigmaTheta() default 0.02;

        /** @return fuse the inertial board's gyro (yaw rate) */
        boolean useImu() default true;

        /** @return also fuse the inertial board's longitudinal accelerometer */
        boolean useAccelerometer() default true;

        /**
         * @return seconds the robot stays still after the start while the estimator learns the inertial board's biases
         *         (a MEMS gyro's turn-on offset is up to ±5 °/s; at rest odometry says the true rate is zero)
         */
        double imuSettleTime() default 3;

        /** @return seconds without odometry after which the estimate is stale (the robot stops) */
        double odometryTimeout() default 0.2;

        /** @return fuse sightings of the ceiling landmarks the map names (when the robot has the landmark board) */
        boolean useLandmarks() default true;

        /** @return standard deviation of a landmark's range, m (the board's 10 mm, plus the latency compensation's) */
        double landmarkRangeSigma() default 0.02;

        /** @return standard deviation of a landmark's bearing, rad (the board's 0.5°, plus the compensation's) */
        double landmarkBearingSigma() default 0.02;

        /** @return largest positional standard deviation, m, above which the robot stops (safety) */
        double maxPositionSigma() default 0.5;
    }

    private Config config;

    @Activate
    void activate(Config c) {
        this.config = c;
    }

    /**
     * @param landmarks the ceiling landmarks of the map (fused only when {@code useLandmarks})
     * @return a new estimator at the configured start pose
     */
    Localizer newLocalizer(List<MapLandmark> landmarks) {
        return new Localizer(RobotDescriptions.defaults(), config, config.useLandmarks() ? landmarks : List.of());
    }

    /** @return the configured settings */
    Config config() {
        return config;
    }

    /** @return the configured start pose */
    Pose2D start() {
        return new Pose2D(config.startX(), config.startY(), config.startTheta());
    }

    @Override
    public String name() {
        return "localizer";
    }

    @Override
    public String status() {
        return "odometry + EKF" + (config.useImu() ? " with the inertial board" : "")
                + (config.useLandmarks() ? " and ceiling landmarks" : "") + ", start " + start();
    }
}
