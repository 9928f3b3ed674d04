package sabot.model.geometry;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;
import org.junit.jupiter.api.Test;

class PoseTest {

    @ParameterizedTest
    @CsvSource({ "0,0", "3.141592653589793,3.141592653589793", "-3.141592653589793,3.141592653589793",
            "6.283185307179586,0", "4.71238898038469,-1.5707963267948966", "-7.0,-0.7168146928204138" })
    void headingIsWrappedIntoHalfOpenPiInterval(double in, double expected) {
        assertEquals(expected, Pose2D.normalizeAngle(in), 1e-12);
    }

    @Test
    void nanOrInfiniteComponentsAreNotFinite() {
        assertFalse(new Pose2D(Double.NaN, 0, 0).isFinite());
        assertFalse(new Pose2D(0, 0, Double.POSITIVE_INFINITY).isFinite());
        assertFalse(new Twist2D(0, Double.NaN).isFinite());
        assertTrue(new Pose2D(1, 2, 3).isFinite());
    }

    @Test
    void distanceIsEuclidean() {
        assertEquals(5.0, new Point2D(1, 1).distanceTo(new Point2D(4, 5)), 1e-12);
    }
}
