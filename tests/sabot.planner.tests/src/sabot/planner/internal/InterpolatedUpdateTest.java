package sabot.planner.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;

import org.junit.jupiter.api.Test;

/**
 * The interpolated update of {@link LpnNavigationFunction}, whose selections are made on the float bits with integer
 * operations, against the formula of the class comment written with float comparisons: the least of
 * {@code N(a) + sqrt(c^2 - delta^2)} with delta = N(a) - N(d) clamped to [0, c / sqrt 2], and {@code N(d) + c sqrt 2}.
 */
class InterpolatedUpdateTest {

    private static final float SQRT2 = (float) Math.sqrt(2);

    /** The update as the class comment states it, with float selections. */
    private static float formula(float value, float corner, float c) {
        float limit = c * (float) (1 / Math.sqrt(2));
        float delta = Math.max(0f, Math.min(value - corner, limit));
        float interior = value + (float) Math.sqrt(c * c - delta * delta);
        float straight = corner + c * SQRT2;
        return Math.min(interior, straight);
    }

    @Test
    void theUpdateOnTheBitsIsTheFormula() {
        Random random = new Random(20261128);
        int nearTheLimit = 0;
        for (int i = 0; i < 1_000_000; i++) {
            float c = 50 + 200 * random.nextFloat();
            float value = 1e5f * random.nextFloat();
            // corners below, near and above the value, reaching past the limit c / sqrt 2 on both sides
            float corner = Math.max(0f, value + c * (2 * random.nextFloat() - 1.2f));
            float expected = formula(value, corner, c);
            float actual = InterpolatedUpdate.update(value, corner, c);
            float limit = c * (float) (1 / Math.sqrt(2));
            if (Math.abs(value - corner - limit) < 1e-3f * c) {
                // at the limit the crossing and the diagonal are equal: the choice by delta may round the other way
                nearTheLimit++;
                assertEquals(expected, actual, 2 * Math.ulp(expected), "value " + value + ", corner " + corner);
            } else {
                assertEquals(expected, actual, "value " + value + ", corner " + corner + ", c " + c);
            }
        }
        assertTrue(nearTheLimit > 100, "the draw reaches the limit: " + nearTheLimit);
    }

    @Test
    void aCornerAtOrAboveTheValueGivesTheAxisStepAndAFarLowerOneTheDiagonal() {
        assertEquals(100f + 50f, InterpolatedUpdate.update(100f, 100f, 50f));
        assertEquals(100f + 50f, InterpolatedUpdate.update(100f, 180f, 50f));
        assertEquals(100f + 50f, InterpolatedUpdate.update(100f, Float.POSITIVE_INFINITY, 50f),
                "an unreached corner");
        assertEquals(0f + 50f * SQRT2, InterpolatedUpdate.update(100f, 0f, 50f), "straight from the corner");
        assertEquals(Float.POSITIVE_INFINITY, InterpolatedUpdate.update(100f, 40f, Float.POSITIVE_INFINITY),
                "an impassable cell's density");
    }
}
