package sabot.onboard.motion.internal;

import java.util.List;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;

import sabot.model.geometry.Pose2D;
import sabot.model.map.MapLandmark;
import sabot.model.robot.RobotDescriptions;
import sabot.onboard.motion.loop.Localizer;
import sabot.onboard.motion.loop.LocalizerSettings;
import sabot.onboard.motion.loop.LoopDefaults;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code localizer}: the settings of the pose estimate (start pose, initial uncertainty, inertial fusion). The
 * control loop creates its {@link Localizer} from them. Settings: {@link Config}.
 */
@Designate(ocd = LocalizerTask.Config.class, factory = false)
@Component(name = "sabot.task.localizer", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, LocalizerTask.class })
public final class LocalizerTask implements OnboardTask {

    /** The task's settings: its Metatype description, generated from these annotations. */
    @ObjectClassDefinition(id = "sabot.task.localizer", name = "Localizer task",
            description = "Pose estimate: wheel odometry fused with the inertial board in an EKF.")
    public @interface Config {
        @AttributeDefinition(name = "Start x", description = "Start x in the map frame, m.")
        double startX() default 0;

        @AttributeDefinition(name = "Start y", description = "Start y in the map frame, m.")
        double startY() default 0;

        @AttributeDefinition(name = "Start heading", description = "Start heading, rad.", min = "-3.1416",
                max = "3.1416")
        double startTheta() default 0;

        @AttributeDefinition(name = "Initial position sigma", description = "Initial standard deviation of x and y, m.",
                min = "0.001", max = "10")
        double initialSigmaXY() default LoopDefaults.INITIAL_SIGMA_XY;

        @AttributeDefinition(name = "Initial heading sigma", description = "Initial standard deviation of the "
                + "heading, rad.", min = "0.001", max = "3.1416")
        double initialSigmaTheta() default LoopDefaults.INITIAL_SIGMA_THETA;

        @AttributeDefinition(name = "Use the inertial board", description = "Fuse the gyro (yaw rate) of the "
                + "inertial board.")
        boolean useImu() default LoopDefaults.USE_IMU;

        @AttributeDefinition(name = "Use the accelerometer", description = "Also fuse the inertial board's "
                + "longitudinal accelerometer (with useImu).")
        boolean useAccelerometer() default LoopDefaults.USE_ACCELEROMETER;

        /** A MEMS gyro's turn-on offset is up to ±5 °/s; at rest odometry says the true rate is zero. */
        @AttributeDefinition(name = "IMU settle time", description = "Seconds the robot stays still after the start "
                + "while the estimator learns the inertial board's biases.", min = "0", max = "60")
        double imuSettleTime() default LoopDefaults.IMU_SETTLE_TIME;

        @AttributeDefinition(name = "Odometry timeout", description = "Seconds without encoder readings after which "
                + "the estimate is stale and the robot stops.", min = "0.02", max = "5")
        double odometryTimeout() default LoopDefaults.ODOMETRY_TIMEOUT;

        @AttributeDefinition(name = "Use landmarks", description = "Fuse sightings of the ceiling landmarks the map "
                + "names (sabot_landmarks) from the landmark board, when the robot has one.")
        boolean useLandmarks() default LoopDefaults.USE_LANDMARKS;

        /** The board's 10 mm, plus the latency compensation's. */
        @AttributeDefinition(name = "Landmark range sigma", description = "Standard deviation of a landmark's range, "
                + "m.", min = "0.001", max = "10")
        double landmarkRangeSigma() default LoopDefaults.LANDMARK_RANGE_SIGMA;

        /** The board's 0.5°, plus the compensation's. */
        @AttributeDefinition(name = "Landmark bearing sigma", description = "Standard deviation of a landmark's "
                + "bearing, rad.", min = "0.0001", max = "3.14")
        double landmarkBearingSigma() default LoopDefaults.LANDMARK_BEARING_SIGMA;

        @AttributeDefinition(name = "Largest position sigma", description = "Positional standard deviation, m, above "
                + "which the robot stops (safety).", min = "0.01", max = "100")
        double maxPositionSigma() default LoopDefaults.MAX_POSITION_SIGMA;
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
        return new Localizer(RobotDescriptions.defaults(), settings(), config.useLandmarks() ? landmarks : List.of());
    }

    /** @return the configured settings, as the control loop takes them */
    LocalizerSettings settings() {
        Config c = config;
        return new LocalizerSettings(start(), c.initialSigmaXY(), c.initialSigmaTheta(), c.useImu(),
                c.useAccelerometer(), c.imuSettleTime(), c.odometryTimeout(), c.landmarkRangeSigma(),
                c.landmarkBearingSigma(), c.maxPositionSigma());
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
