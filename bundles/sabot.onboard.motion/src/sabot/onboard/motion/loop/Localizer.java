package sabot.onboard.motion.loop;

import java.util.HashMap;
import java.util.List;
import java.util.Map;

import sabot.localization.EkfNoise;
import sabot.localization.EncoderOdometry;
import sabot.localization.Landmark;
import sabot.localization.MeasurementResult;
import sabot.localization.OdometryCalibration;
import sabot.localization.PoseEkf;
import sabot.model.geometry.Pose2D;
import sabot.model.map.MapLandmark;
import sabot.model.robot.RobotDescription;

/**
 * The robot's pose estimate: wheel odometry (RK2 on encoder counts) fused with the inertial board's yaw rate and
 * longitudinal acceleration, and with sightings of the map's ceiling landmarks (absolute fixes), in an EKF. Used by
 * the control loop's thread only (not thread-safe).
 */
public final class Localizer {

    private final RobotDescription robot;
    private final LocalizerSettings config;
    private EncoderOdometry odometry;
    private PoseEkf ekf;
    private double lastOdometryTime = Double.NaN;
    private double firstReadingTime = Double.NaN;
    /** Where the next first encoder reading starts odometry (the start pose, or a re-localisation). */
    private Pose2D pendingPose;
    private final Map<Integer, Landmark> landmarks = new HashMap<>();
    private long landmarkFixes;
    private long landmarkOutliers;

    public Localizer(RobotDescription robot, LocalizerSettings config, List<MapLandmark> landmarks) {
        this.robot = robot;
        this.config = config;
        for (MapLandmark m : landmarks) {
            this.landmarks.put(m.id(), new Landmark(Integer.toString(m.id()), m.x(), m.y()));
        }
        reset(config.start(), Double.NaN);
    }

    /** Resets the estimate to {@code pose} with the configured initial uncertainty; the next counts start odometry. */
    void reset(Pose2D pose, double time) {
        odometry = null;
        ekf = new PoseEkf(pose, new double[] { config.initialSigmaXY(), config.initialSigmaXY(),
                config.initialSigmaTheta() }, EkfNoise.defaults(), config.odometryTimeout());
        if (Double.isFinite(time)) {
            ekf.start(time);
        }
        lastOdometryTime = Double.NaN;
        this.pendingPose = pose;
    }

    /** Feeds one encoder reading taken at {@code time} (seconds, loop clock). */
    void encoders(double time, int left, int right) {
        if (odometry == null) {
            odometry = new EncoderOdometry(robot, OdometryCalibration.nominal(robot), pendingPose);
            odometry.update(left, right);
            if (Double.isNaN(ekf.time())) {
                ekf.start(time);
            }
            if (Double.isNaN(firstReadingTime)) {
                firstReadingTime = time;
            }
            lastOdometryTime = time;
            return;
        }
        odometry.update(left, right);
        double interval = Double.isNaN(lastOdometryTime) ? 0 : time - lastOdometryTime;
        ekf.updateOdometry(time, interval, odometry.lastDistance(), odometry.lastRotation());
        lastOdometryTime = time;
    }

    /** Feeds one inertial sample taken at {@code time}. */
    void inertial(double time, double yawRate, double forwardAcceleration) {
        if (!config.useImu() || Double.isNaN(ekf.time())) {
            return;
        }
        ekf.updateGyro(time, yawRate);
        if (config.useAccelerometer()) {
            ekf.updateAccelerometer(time, forwardAcceleration);
        }
    }

    /** @return whether there are landmarks to fuse (the map names some and the settings use them) */
    boolean usesLandmarks() {
        return !landmarks.isEmpty();
    }

    /**
     * Fuses one sighting of a ceiling landmark, read at {@code time} and measured {@code age} seconds earlier. The
     * range and bearing are carried forward to {@code time} with the estimated speed and yaw rate (the robot moves
     * up to 0.05 m and turns up to 0.2 rad in a 100 ms old measurement), so that the EKF, which takes measurements in
     * time order, can apply it now.
     *
     * @return the EKF's verdict ({@code REJECTED_OUT_OF_ORDER} before the first encoder reading starts the
     *         estimate), or null when the id is not on the map
     */
    MeasurementResult landmark(double time, int id, double range, double bearing, double age) {
        Landmark l = landmarks.get(id);
        if (l == null) {
            return null;
        }
        if (Double.isNaN(ekf.time())) {
            return MeasurementResult.REJECTED_OUT_OF_ORDER;
        }
        double v = ekf.state(PoseEkf.V);
        double w = ekf.state(PoseEkf.OMEGA);
        double turned = w * age;
        double ahead = v * age;
        // the marker in the robot frame of the measurement, then in the robot frame now (moved ahead, then turned)
        double px = range * Math.cos(bearing) - ahead;
        double py = range * Math.sin(bearing);
        double c = Math.cos(turned);
        double s = Math.sin(turned);
        double qx = c * px + s * py;
        double qy = -s * px + c * py;
        MeasurementResult r = ekf.updateLandmark(time, l, Math.hypot(qx, qy), Math.atan2(qy, qx),
                config.landmarkRangeSigma(), config.landmarkBearingSigma());
        if (r == MeasurementResult.ACCEPTED) {
            landmarkFixes++;
        } else if (r == MeasurementResult.REJECTED_OUTLIER) {
            landmarkOutliers++;
        }
        return r;
    }

    /** @return landmark sightings fused and rejected by the gate since the start */
    long[] landmarkCounts() {
        return new long[] { landmarkFixes, landmarkOutliers };
    }

    /** @return the estimate predicted to {@code time} */
    Pose2D pose(double time) {
        if (!Double.isNaN(ekf.time()) && time > ekf.time()) {
            ekf.predict(time);
        }
        return ekf.pose();
    }

    /**
     * @return true while the robot must stay still so that the estimator learns the inertial board's biases: from the
     *         first encoder reading for the configured settle time (never when the inertial board is not used)
     */
    boolean isSettling(double time) {
        return config.useImu() && (Double.isNaN(firstReadingTime) || time - firstReadingTime < config.imuSettleTime());
    }

    /** @return x, y, θ covariance (3 × 3) */
    double[][] covariance() {
        return ekf.poseCovariance();
    }

    /** @return the largest positional standard deviation (m): the square root of the larger eigenvalue of Pxy */
    double positionSigma() {
        double[][] c = ekf.poseCovariance();
        double a = c[0][0], b = c[0][1], d = c[1][1];
        double mean = (a + d) / 2;
        double radius = Math.sqrt(((a - d) / 2) * ((a - d) / 2) + b * b);
        return Math.sqrt(Math.max(0, mean + radius));
    }

    /**
     * @return true when encoder readings have been missing for longer than the configured timeout (before the first
     *         reading a board that never answers is the bus's fault, not a stale estimate)
     */
    boolean isStale(double time) {
        return !Double.isNaN(lastOdometryTime) && time - lastOdometryTime > config.odometryTimeout();
    }

    /** @return measured forward speed and yaw rate (EKF state), m/s and rad/s */
    double[] velocity() {
        return new double[] { ekf.state(PoseEkf.V), ekf.state(PoseEkf.OMEGA) };
    }
}
