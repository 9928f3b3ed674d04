package sabot.localization;

import org.ejml.data.DMatrixRMaj;
import org.ejml.dense.row.CommonOps_DDRM;

import sabot.model.geometry.Pose2D;

/**
 * Extended Kalman filter over the planar pose and velocities of a differential-drive robot, with gyro and
 * accelerometer biases (Thrun, Burgard, Fox, <i>Probabilistic Robotics</i>, 2005, &sect;3.3, table 3.3).
 * <p>
 * State x = [x, y, &theta;, v, &omega;, a, b_g, b_a] (m, m, rad, m/s, rad/s, m/s&sup2;, rad/s, m/s&sup2;). Process
 * model between measurements (&Delta;t = t<sub>k</sub> &minus; t<sub>k&minus;1</sub>):
 * <pre>
 *   x += (v + a&Delta;t/2)&Delta;t cos(&theta; + &omega;&Delta;t/2),  y likewise with sin,  &theta; += &omega;&Delta;t,  v += a&Delta;t
 *   &omega;, a, b_g, b_a: random walks driven by the densities of {@link EkfNoise}
 * </pre>
 * Measurements, each time-stamped; the filter first predicts to that time:
 * <ul>
 * <li>wheel odometry over an interval T: h = [v &minus; aT/2, &omega;] (the interval's mean speed), noise growing
 * with speed because slip does;</li>
 * <li>gyro: h = &omega; + b_g; accelerometer (longitudinal): h = a + b_a; magnetometer heading: h = &theta;;</li>
 * <li>ceiling landmark range/bearing: h = [&radic;(&Delta;x&sup2;+&Delta;y&sup2;), atan2(&Delta;y, &Delta;x) &minus; &theta;];
 * absolute pose fix: h = [x, y, &theta;].</li>
 * </ul>
 * Every measurement passes a Mahalanobis gate d&sup2; = &nu;&#7488;S&#8315;&sup1;&nu; &le; &chi;&sup2;<sub>m</sub>(p); angle
 * innovations are wrapped into (&minus;&pi;, &pi;]. The covariance update uses the Joseph form for symmetry and
 * positive definiteness.
 * <p>
 * Not thread-safe; one instance per robot. Work matrices are pre-allocated: updates do not allocate.
 */
public final class PoseEkf {

    public static final int N = 8;
    public static final int X = 0, Y = 1, THETA = 2, V = 3, OMEGA = 4, ACCEL = 5, GYRO_BIAS = 6, ACCEL_BIAS = 7;
    /** Marks a scalar sensor without a bias state. */
    private static final int NO_BIAS = -1;

    private final EkfNoise noise;
    private final double odometryTimeout;
    private final double[] gate = new double[4];

    private final DMatrixRMaj x = new DMatrixRMaj(N, 1);
    private final DMatrixRMaj p = new DMatrixRMaj(N, N);
    private final DMatrixRMaj f = new DMatrixRMaj(N, N);
    private final DMatrixRMaj fp = new DMatrixRMaj(N, N);
    private final DMatrixRMaj tmp = new DMatrixRMaj(N, N);
    private final DMatrixRMaj ikh = new DMatrixRMaj(N, N);
    private final Correction[] corrections = { null, new Correction(1), new Correction(2), new Correction(3) };

    private double time = Double.NaN;
    private double lastOdometryTime = Double.NaN;

    /**
     * @param start           initial pose
     * @param poseSigma       initial standard deviations of x, y (m) and &theta; (rad)
     * @param noise           noise model
     * @param odometryTimeout seconds without odometry after which {@link #isStale} reports the estimate stale
     */
    public PoseEkf(Pose2D start, double[] poseSigma, EkfNoise noise, double odometryTimeout) {
        if (start == null || !start.isFinite() || poseSigma == null || poseSigma.length != 3) {
            throw new IllegalArgumentException("EKF needs a finite start pose and three pose sigmas");
        }
        for (double s : poseSigma) {
            if (!(s > 0) || !Double.isFinite(s)) {
                throw new IllegalArgumentException("pose sigmas must be finite and > 0");
            }
        }
        this.noise = noise;
        this.odometryTimeout = odometryTimeout;
        gate[1] = ChiSquare.quantile(1, noise.gateProbability());
        gate[2] = ChiSquare.quantile(2, noise.gateProbability());
        gate[3] = ChiSquare.quantile(3, noise.gateProbability());
        x.set(X, 0, start.x());
        x.set(Y, 0, start.y());
        x.set(THETA, 0, start.theta());
        p.set(X, X, poseSigma[0] * poseSigma[0]);
        p.set(Y, Y, poseSigma[1] * poseSigma[1]);
        p.set(THETA, THETA, poseSigma[2] * poseSigma[2]);
        p.set(V, V, 0.01);
        p.set(OMEGA, OMEGA, 0.01);
        p.set(ACCEL, ACCEL, 0.25);
        // BMI088-class turn-on offsets: gyro up to ~1 deg/s, accelerometer up to ~20 mg.
        p.set(GYRO_BIAS, GYRO_BIAS, Math.pow(Math.toRadians(1), 2));
        p.set(ACCEL_BIAS, ACCEL_BIAS, Math.pow(0.2, 2));
    }

    /** Starts the filter's clock; measurements before this time are rejected. */
    public void start(double t) {
        if (!Double.isFinite(t)) {
            throw new IllegalArgumentException("start time must be finite");
        }
        time = t;
    }

    /**
     * Propagates the state to {@code t}.
     *
     * @return false when {@code t} is not finite or earlier than the filter's time (nothing is done)
     */
    public boolean predict(double t) {
        if (!Double.isFinite(t)) {
            return false;
        }
        if (Double.isNaN(time)) {
            time = t;
            return true;
        }
        double dt = t - time;
        if (dt < 0) {
            return false;
        }
        if (dt == 0) {
            return true;
        }
        double th = x.get(THETA, 0);
        double v = x.get(V, 0);
        double w = x.get(OMEGA, 0);
        double a = x.get(ACCEL, 0);
        double mid = th + w * dt / 2;
        double c = Math.cos(mid);
        double s = Math.sin(mid);
        double dist = (v + a * dt / 2) * dt;
        x.set(X, 0, x.get(X, 0) + dist * c);
        x.set(Y, 0, x.get(Y, 0) + dist * s);
        x.set(THETA, 0, th + w * dt);
        x.set(V, 0, v + a * dt);

        CommonOps_DDRM.setIdentity(f);
        f.set(X, THETA, -dist * s);
        f.set(X, V, dt * c);
        f.set(X, OMEGA, -dist * s * dt / 2);
        f.set(X, ACCEL, dt * dt / 2 * c);
        f.set(Y, THETA, dist * c);
        f.set(Y, V, dt * s);
        f.set(Y, OMEGA, dist * c * dt / 2);
        f.set(Y, ACCEL, dt * dt / 2 * s);
        f.set(THETA, OMEGA, dt);
        f.set(V, ACCEL, dt);
        CommonOps_DDRM.mult(f, p, fp);
        CommonOps_DDRM.multTransB(fp, f, p);
        p.add(OMEGA, OMEGA, noise.yawAccelerationPsd() * dt);
        p.add(ACCEL, ACCEL, noise.jerkPsd() * dt);
        p.add(GYRO_BIAS, GYRO_BIAS, noise.gyroBiasWalkPsd() * dt);
        p.add(ACCEL_BIAS, ACCEL_BIAS, noise.accelBiasWalkPsd() * dt);
        // No direct noise on theta and v: the gyro and odometry measure the rates every step, and the dt^3/3 terms of
        // the white-acceleration model would double-count that uncertainty (and let the magnetometer's noise in).
        time = t;
        return true;
    }

    /**
     * Wheel odometry over the interval ending at {@code t}.
     *
     * @param t        end of the interval, seconds
     * @param interval length of the interval, seconds (&gt; 0)
     * @param distance distance travelled by the centre, metres
     * @param rotation heading change, radians
     */
    public MeasurementResult updateOdometry(double t, double interval, double distance, double rotation) {
        if (!(interval > 0) || !Double.isFinite(interval) || !Double.isFinite(distance) || !Double.isFinite(rotation)) {
            return MeasurementResult.REJECTED_NOT_FINITE;
        }
        MeasurementResult pre = prepare(t);
        if (pre != null) {
            return pre;
        }
        Correction k = corrections[2];
        double speed = Math.abs(distance / interval);
        double sv = noise.odometrySpeedFloor() + noise.odometrySpeedSlip() * speed;
        double sw = noise.odometryYawRateFloor() + noise.odometryYawRateSlip() * speed;
        k.h.zero();
        k.h.set(0, V, 1);
        k.h.set(0, ACCEL, -interval / 2);
        k.h.set(1, OMEGA, 1);
        k.innovation.set(0, 0, distance / interval - (x.get(V, 0) - x.get(ACCEL, 0) * interval / 2));
        k.innovation.set(1, 0, rotation / interval - x.get(OMEGA, 0));
        k.r.zero();
        k.r.set(0, 0, sv * sv);
        k.r.set(1, 1, sw * sw);
        // Odometry is the reference for "stopped": it is never gated, or a robot pushed while the filter disagrees
        // would never be believed.
        MeasurementResult res = correct(k, Double.POSITIVE_INFINITY);
        lastOdometryTime = t;
        return res;
    }

    /** Gyro yaw rate sample, rad/s. */
    public MeasurementResult updateGyro(double t, double yawRate) {
        return updateScalar(t, yawRate, OMEGA, GYRO_BIAS, noise.gyroSigma(), false);
    }

    /** Longitudinal accelerometer sample (gravity already removed), m/s&sup2;. */
    public MeasurementResult updateAccelerometer(double t, double acceleration) {
        return updateScalar(t, acceleration, ACCEL, ACCEL_BIAS, noise.accelSigma(), false);
    }

    /** Magnetometer heading (map frame, declination and hard/soft iron already compensated), radians. */
    public MeasurementResult updateHeading(double t, double heading) {
        return updateScalar(t, heading, THETA, NO_BIAS, noise.magnetometerSigma(), true);
    }

    /**
     * One scalar sensor that reads a state component plus, optionally, its own bias state: z = x[state] + x[bias].
     *
     * @param bias  index of the sensor's bias state, or {@link #NO_BIAS}
     * @param angle true when z is an angle: the innovation is wrapped into (-pi, pi]
     */
    private MeasurementResult updateScalar(double t, double z, int state, int bias, double sigma, boolean angle) {
        if (!Double.isFinite(z)) {
            return MeasurementResult.REJECTED_NOT_FINITE;
        }
        MeasurementResult pre = prepare(t);
        if (pre != null) {
            return pre;
        }
        Correction k = corrections[1];
        k.h.zero();
        k.h.set(0, state, 1);
        double predicted = x.get(state, 0);
        if (bias != NO_BIAS) {
            k.h.set(0, bias, 1);
            predicted += x.get(bias, 0);
        }
        double innovation = z - predicted;
        k.innovation.set(0, 0, angle ? Pose2D.normalizeAngle(innovation) : innovation);
        k.r.set(0, 0, sigma * sigma);
        return correct(k, gate[1]);
    }

    /**
     * Range and bearing to a ceiling landmark, as a camera looking up measures them (bearing in the robot frame).
     *
     * @param range        metres (horizontal distance)
     * @param bearing      radians, counter-clockwise from the robot's heading
     * @param rangeSigma   metres
     * @param bearingSigma radians
     */
    public MeasurementResult updateLandmark(double t, Landmark landmark, double range, double bearing,
            double rangeSigma, double bearingSigma) {
        if (landmark == null || !Double.isFinite(range) || !Double.isFinite(bearing) || !(rangeSigma > 0)
                || !(bearingSigma > 0) || !Double.isFinite(rangeSigma) || !Double.isFinite(bearingSigma)) {
            return MeasurementResult.REJECTED_NOT_FINITE;
        }
        MeasurementResult pre = prepare(t);
        if (pre != null) {
            return pre;
        }
        double dx = landmark.x() - x.get(X, 0);
        double dy = landmark.y() - x.get(Y, 0);
        double q = dx * dx + dy * dy;
        double rho = Math.sqrt(q);
        if (rho < 1e-6) {
            return MeasurementResult.REJECTED_NOT_FINITE; // bearing undefined right under the landmark
        }
        Correction k = corrections[2];
        k.h.zero();
        k.h.set(0, X, -dx / rho);
        k.h.set(0, Y, -dy / rho);
        k.h.set(1, X, dy / q);
        k.h.set(1, Y, -dx / q);
        k.h.set(1, THETA, -1);
        k.innovation.set(0, 0, range - rho);
        k.innovation.set(1, 0, Pose2D.normalizeAngle(bearing - (Math.atan2(dy, dx) - x.get(THETA, 0))));
        k.r.zero();
        k.r.set(0, 0, rangeSigma * rangeSigma);
        k.r.set(1, 1, bearingSigma * bearingSigma);
        return correct(k, gate[2]);
    }

    /**
     * An absolute pose fix (e.g. from a landmark whose orientation is also decoded).
     *
     * @param sigmas standard deviations of x, y (m) and &theta; (rad)
     */
    public MeasurementResult updatePose(double t, Pose2D fix, double[] sigmas) {
        if (fix == null || !fix.isFinite() || sigmas == null || sigmas.length != 3) {
            return MeasurementResult.REJECTED_NOT_FINITE;
        }
        for (double s : sigmas) {
            if (!(s > 0) || !Double.isFinite(s)) {
                return MeasurementResult.REJECTED_NOT_FINITE;
            }
        }
        MeasurementResult pre = prepare(t);
        if (pre != null) {
            return pre;
        }
        Correction k = corrections[3];
        k.h.zero();
        k.h.set(0, X, 1);
        k.h.set(1, Y, 1);
        k.h.set(2, THETA, 1);
        k.innovation.set(0, 0, fix.x() - x.get(X, 0));
        k.innovation.set(1, 0, fix.y() - x.get(Y, 0));
        k.innovation.set(2, 0, Pose2D.normalizeAngle(fix.theta() - x.get(THETA, 0)));
        k.r.zero();
        for (int i = 0; i < 3; i++) {
            k.r.set(i, i, sigmas[i] * sigmas[i]);
        }
        return correct(k, gate[3]);
    }

    private MeasurementResult prepare(double t) {
        if (!Double.isFinite(t)) {
            return MeasurementResult.REJECTED_NOT_FINITE;
        }
        if (!Double.isNaN(time) && t < time) {
            return MeasurementResult.REJECTED_OUT_OF_ORDER;
        }
        predict(t);
        return null;
    }

    private MeasurementResult correct(Correction k, double gateValue) {
        int m = k.m;
        // S = H P H^T + R
        CommonOps_DDRM.mult(k.h, p, k.hp);
        CommonOps_DDRM.multTransB(k.hp, k.h, k.s);
        CommonOps_DDRM.addEquals(k.s, k.r);
        if (!CommonOps_DDRM.invert(k.s, k.sInv)) {
            return MeasurementResult.REJECTED_NOT_FINITE;
        }
        double d2 = 0;
        for (int i = 0; i < m; i++) {
            for (int j = 0; j < m; j++) {
                d2 += k.innovation.get(i, 0) * k.sInv.get(i, j) * k.innovation.get(j, 0);
            }
        }
        if (!Double.isFinite(d2)) {
            return MeasurementResult.REJECTED_NOT_FINITE;
        }
        k.lastMahalanobis = d2;
        if (d2 > gateValue) {
            return MeasurementResult.REJECTED_OUTLIER;
        }
        // K = P H^T S^-1 = (H P)^T S^-1
        CommonOps_DDRM.multTransA(k.hp, k.sInv, k.gain);
        CommonOps_DDRM.mult(k.gain, k.innovation, k.dx);
        CommonOps_DDRM.addEquals(x, k.dx);
        // Joseph form: P = (I - K H) P (I - K H)^T + K R K^T
        CommonOps_DDRM.mult(k.gain, k.h, ikh);
        CommonOps_DDRM.scale(-1, ikh);
        for (int i = 0; i < N; i++) {
            ikh.add(i, i, 1);
        }
        CommonOps_DDRM.mult(ikh, p, tmp);
        CommonOps_DDRM.multTransB(tmp, ikh, p);
        CommonOps_DDRM.mult(k.gain, k.r, k.kr);
        CommonOps_DDRM.multAddTransB(k.kr, k.gain, p);
        return MeasurementResult.ACCEPTED;
    }

    /** @return the filter's current time, NaN before the first prediction or {@link #start} */
    public double time() {
        return time;
    }

    /** @return the pose estimate (heading not wrapped) */
    public Pose2D pose() {
        return new Pose2D(x.get(X, 0), x.get(Y, 0), x.get(THETA, 0));
    }

    /** @return one state component; see the index constants */
    public double state(int index) {
        return x.get(index, 0);
    }

    /** @return a copy of the 8&times;8 state covariance, row-major, in the state's units squared */
    public double[][] covariance() {
        double[][] c = new double[N][N];
        for (int i = 0; i < N; i++) {
            for (int j = 0; j < N; j++) {
                c[i][j] = p.get(i, j);
            }
        }
        return c;
    }

    /** @return a copy of the 3&times;3 covariance of (x, y, &theta;) */
    public double[][] poseCovariance() {
        double[][] c = new double[3][3];
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) {
                c[i][j] = p.get(i, j);
            }
        }
        return c;
    }

    /** @return the squared Mahalanobis distance of the last measurement of dimension {@code m} (1..3) */
    public double lastMahalanobisSquared(int m) {
        return corrections[m].lastMahalanobis;
    }

    /**
     * @param now seconds
     * @return true when no odometry has arrived for longer than the odometry timeout (or ever): the estimate is then
     *         dead reckoning on a model, and a controller must stop the robot
     */
    public boolean isStale(double now) {
        return Double.isNaN(lastOdometryTime) || !Double.isFinite(now) || now - lastOdometryTime > odometryTimeout;
    }

    /** Pre-allocated work matrices for one measurement dimension. */
    private static final class Correction {
        final int m;
        final DMatrixRMaj h;
        final DMatrixRMaj hp;
        final DMatrixRMaj s;
        final DMatrixRMaj sInv;
        final DMatrixRMaj r;
        final DMatrixRMaj innovation;
        final DMatrixRMaj gain;
        final DMatrixRMaj dx;
        final DMatrixRMaj kr;
        double lastMahalanobis = Double.NaN;

        Correction(int m) {
            this.m = m;
            h = new DMatrixRMaj(m, N);
            hp = new DMatrixRMaj(m, N);
            s = new DMatrixRMaj(m, m);
            sInv = new DMatrixRMaj(m, m);
            r = new DMatrixRMaj(m, m);
            innovation = new DMatrixRMaj(m, 1);
            gain = new DMatrixRMaj(N, m);
            dx = new DMatrixRMaj(N, 1);
            kr = new DMatrixRMaj(N, m);
        }
    }
}
