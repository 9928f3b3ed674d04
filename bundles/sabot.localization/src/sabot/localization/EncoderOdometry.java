package sabot.localization;

import sabot.model.geometry.Pose2D;
import sabot.model.robot.RobotDescription;

/**
 * Dead reckoning from the two wheels' encoder counters with the second-order Runge-Kutta update
 * (Siciliano et al., <i>Robotics: Modelling, Planning and Control</i>, 2009, &sect;11.7, eq. 11.75):
 * <pre>
 *   &Delta;s = (r_R &Delta;&phi;_R + r_L &Delta;&phi;_L)/2,  &Delta;&theta; = (r_R &Delta;&phi;_R &minus; r_L &Delta;&phi;_L)/d
 *   x += &Delta;s cos(&theta; + &Delta;&theta;/2),  y += &Delta;s sin(&theta; + &Delta;&theta;/2),  &theta; += &Delta;&theta;
 * </pre>
 * Counters are the SACT board's 32-bit registers: differences are taken modulo 2&sup3;&sup2;, so wrap-around is
 * harmless as long as fewer than 2&sup3;&sup1; counts pass between two updates.
 */
public final class EncoderOdometry {

    private final double radiansPerCount;
    private OdometryCalibration calibration;
    private Pose2D pose;
    private boolean primed;
    private int lastLeft;
    private int lastRight;
    private double lastDs;
    private double lastDtheta;

    /**
     * @param robot       encoder resolution (lines &times; quadrature &times; gear ratio per wheel turn)
     * @param calibration wheel radii and track to use
     * @param start       initial pose
     */
    public EncoderOdometry(RobotDescription robot, OdometryCalibration calibration, Pose2D start) {
        this.radiansPerCount = 2 * Math.PI / robot.countsPerWheelRevolution();
        this.calibration = calibration;
        reset(start);
    }

    /** Restarts integration at {@code start}; the next counter reading only primes the counters. */
    public void reset(Pose2D start) {
        if (start == null || !start.isFinite()) {
            throw new IllegalArgumentException("odometry needs a finite start pose, got " + start);
        }
        pose = start;
        primed = false;
        lastDs = 0;
        lastDtheta = 0;
    }

    /** Applies a new calibration to all later increments. */
    public void setCalibration(OdometryCalibration calibration) {
        this.calibration = calibration;
    }

    public OdometryCalibration calibration() {
        return calibration;
    }

    /**
     * Integrates the counts accumulated since the previous call.
     *
     * @param leftCount  left encoder counter (raw register value, forward positive)
     * @param rightCount right encoder counter
     * @return the pose after the increment
     */
    public Pose2D update(int leftCount, int rightCount) {
        if (!primed) {
            lastLeft = leftCount;
            lastRight = rightCount;
            primed = true;
            lastDs = 0;
            lastDtheta = 0;
            return pose;
        }
        int dl = leftCount - lastLeft; // modulo 2^32 by Java int arithmetic
        int dr = rightCount - lastRight;
        lastLeft = leftCount;
        lastRight = rightCount;
        double sl = calibration.leftWheelRadius() * dl * radiansPerCount;
        double sr = calibration.rightWheelRadius() * dr * radiansPerCount;
        double ds = (sr + sl) / 2;
        double dth = (sr - sl) / calibration.trackWidth();
        double mid = pose.theta() + dth / 2;
        pose = new Pose2D(pose.x() + ds * Math.cos(mid), pose.y() + ds * Math.sin(mid), pose.theta() + dth);
        lastDs = ds;
        lastDtheta = dth;
        return pose;
    }

    /** @return the current pose estimate (heading not wrapped) */
    public Pose2D pose() {
        return pose;
    }

    /** @return distance travelled by the centre in the last increment, metres */
    public double lastDistance() {
        return lastDs;
    }

    /** @return heading change in the last increment, radians */
    public double lastRotation() {
        return lastDtheta;
    }
}
