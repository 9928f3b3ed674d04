package sabot.localization;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Pose2D;

class PoseEkfTest {

    private static PoseEkf filter(Pose2D start, double sigma) {
        PoseEkf f = new PoseEkf(start, new double[] { sigma, sigma, sigma }, EkfNoise.defaults(), 0.2);
        f.start(0);
        return f;
    }

    @Test
    void chiSquareGatesMatchTables() {
        assertEquals(10.828, ChiSquare.quantile(1, 0.999), 1e-3);
        assertEquals(13.816, ChiSquare.quantile(2, 0.999), 1e-3);
        assertEquals(16.266, ChiSquare.quantile(3, 0.999), 1e-3);
        assertEquals(3.841, ChiSquare.quantile(1, 0.95), 1e-3);
    }

    @Test
    void gyroBiasIsLearntWhileStandingStill() {
        PoseEkf f = filter(Pose2D.ORIGIN, 0.01);
        Random rng = new Random(3);
        double bias = Math.toRadians(0.8);
        for (int k = 1; k <= 150; k++) {
            double t = k * 0.02;
            f.updateOdometry(t, 0.02, 0, 0);
            f.updateGyro(t, bias + 1.7e-3 * rng.nextGaussian());
        }
        assertEquals(bias, f.state(PoseEkf.GYRO_BIAS), 3e-4);
        assertEquals(0, f.pose().theta(), 1e-3);
    }

    @Test
    void drivingStraightIntegratesOdometrySpeed() {
        PoseEkf f = filter(Pose2D.ORIGIN, 0.01);
        for (int k = 1; k <= 500; k++) {
            double t = k * 0.02;
            f.updateOdometry(t, 0.02, 0.3 * 0.02, 0);
            f.updateGyro(t, 0);
            f.updateAccelerometer(t, 0);
        }
        assertEquals(3.0, f.pose().x(), 0.02);
        assertEquals(0, f.pose().y(), 1e-6);
        assertEquals(0.3, f.state(PoseEkf.V), 1e-3);
    }

    @Test
    void landmarkFixesPullADriftedEstimateBack() {
        PoseEkf f = filter(new Pose2D(0.3, -0.2, 0.05), 0.5);
        Landmark a = new Landmark("A", 2, 1);
        Landmark b = new Landmark("B", -1, 2);
        Pose2D truth = Pose2D.ORIGIN;
        double[][] before = f.poseCovariance();
        for (int k = 1; k <= 20; k++) {
            double t = k * 0.1;
            f.updateOdometry(t, 0.1, 0, 0);
            for (Landmark l : new Landmark[] { a, b }) {
                double dx = l.x() - truth.x();
                double dy = l.y() - truth.y();
                assertEquals(MeasurementResult.ACCEPTED,
                        f.updateLandmark(t, l, Math.hypot(dx, dy), Math.atan2(dy, dx) - truth.theta(), 0.02, 0.01));
            }
        }
        assertEquals(0, f.pose().x(), 0.01);
        assertEquals(0, f.pose().y(), 0.01);
        assertEquals(0, f.pose().theta(), 0.01);
        assertTrue(f.poseCovariance()[0][0] < before[0][0] / 100, "covariance shrinks");
    }

    @Test
    void outlierLandmarkIsRejectedByTheMahalanobisGate() {
        PoseEkf f = filter(Pose2D.ORIGIN, 0.01);
        Landmark a = new Landmark("A", 2, 0);
        f.updateOdometry(0.02, 0.02, 0, 0);
        Pose2D before = f.pose();
        MeasurementResult r = f.updateLandmark(0.04, a, 3.5, 0.4, 0.02, 0.01);
        assertEquals(MeasurementResult.REJECTED_OUTLIER, r);
        assertEquals(before.x(), f.pose().x(), 1e-9);
        assertTrue(f.lastMahalanobisSquared(2) > 13.8);
        assertEquals(MeasurementResult.ACCEPTED, f.updateLandmark(0.06, a, 2.0, 0.0, 0.02, 0.01));
    }

    @Test
    void poseFixOutlierIsRejectedAndGoodFixAccepted() {
        PoseEkf f = filter(Pose2D.ORIGIN, 0.02);
        assertEquals(MeasurementResult.REJECTED_OUTLIER, f.updatePose(0.1, new Pose2D(1, 1, 0), new double[] { 0.01, 0.01, 0.01 }));
        assertEquals(MeasurementResult.ACCEPTED, f.updatePose(0.2, new Pose2D(0.01, 0, 0), new double[] { 0.01, 0.01, 0.01 }));
    }

    @Test
    void nonFiniteMeasurementsAreRejectedAndLeaveTheStateFinite() {
        PoseEkf f = filter(Pose2D.ORIGIN, 0.01);
        assertEquals(MeasurementResult.REJECTED_NOT_FINITE, f.updateGyro(0.02, Double.NaN));
        assertEquals(MeasurementResult.REJECTED_NOT_FINITE, f.updateOdometry(0.02, 0.02, Double.POSITIVE_INFINITY, 0));
        assertEquals(MeasurementResult.REJECTED_NOT_FINITE, f.updateHeading(Double.NaN, 0));
        assertEquals(MeasurementResult.REJECTED_NOT_FINITE, f.updateAccelerometer(0.02, Double.NaN));
        assertEquals(MeasurementResult.REJECTED_NOT_FINITE,
                f.updateLandmark(0.02, new Landmark("A", 1, 1), 1, Double.NaN, 0.01, 0.01));
        assertEquals(MeasurementResult.REJECTED_NOT_FINITE, f.updatePose(0.02, new Pose2D(0, Double.NaN, 0), new double[] { 1, 1, 1 }));
        assertTrue(f.pose().isFinite());
    }

    @Test
    void measurementsOlderThanTheFilterAreRejected() {
        PoseEkf f = filter(Pose2D.ORIGIN, 0.01);
        f.updateGyro(1.0, 0);
        assertEquals(MeasurementResult.REJECTED_OUT_OF_ORDER, f.updateGyro(0.5, 0));
        assertFalse(f.predict(0.9));
    }

    @Test
    void estimateGoesStaleWhenOdometryStopsReporting() {
        PoseEkf f = filter(Pose2D.ORIGIN, 0.01);
        assertTrue(f.isStale(0), "no odometry yet");
        f.updateOdometry(1.0, 0.02, 0, 0);
        assertFalse(f.isStale(1.1));
        f.updateGyro(1.3, 0);
        assertTrue(f.isStale(1.3), "gyro alone does not keep the estimate fresh");
    }

    @Test
    void covarianceStaysSymmetricAndPositive() {
        PoseEkf f = filter(Pose2D.ORIGIN, 0.05);
        Random rng = new Random(9);
        for (int k = 1; k <= 1000; k++) {
            double t = k * 0.02;
            f.updateOdometry(t, 0.02, 0.006 * (1 + 0.01 * rng.nextGaussian()), 0.002 + 1e-4 * rng.nextGaussian());
            f.updateGyro(t, 0.1 + 1.7e-3 * rng.nextGaussian());
            if (k % 5 == 0) {
                f.updateHeading(t, 0.1 * t + 0.03 * rng.nextGaussian());
            }
        }
        double[][] p = f.covariance();
        for (int i = 0; i < PoseEkf.N; i++) {
            assertTrue(p[i][i] > 0, "variance " + i);
            for (int j = 0; j < PoseEkf.N; j++) {
                assertEquals(p[i][j], p[j][i], 1e-12 + 1e-9 * Math.abs(p[i][j]));
            }
        }
    }
}
