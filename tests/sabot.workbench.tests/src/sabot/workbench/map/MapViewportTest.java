package sabot.workbench.map;

import static org.junit.jupiter.api.Assertions.assertEquals;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

class MapViewportTest {

    private static MapViewport viewport() {
        MapViewport v = new MapViewport(50, 0, 0);
        v.setCanvasSize(800, 600);
        return v;
    }

    @Test
    void mapYGoesUpWhileScreenYGoesDown() {
        MapViewport v = viewport();
        assertEquals(400, v.toScreenX(0), 1e-9);
        assertEquals(300, v.toScreenY(0), 1e-9);
        assertEquals(250, v.toScreenY(1), 1e-9);
        assertEquals(450, v.toScreenX(1), 1e-9);
        assertEquals(1.0, v.toMapY(250), 1e-9);
    }

    @Test
    void dragMovesTheMapWithThePointer() {
        MapViewport v = viewport();
        double before = v.toScreenX(2);
        v.panByPixels(30, -20);
        assertEquals(before + 30, v.toScreenX(2), 1e-9);
        assertEquals(300 - 20, v.toScreenY(0), 1e-9);
    }

    @Test
    void zoomKeepsThePointUnderTheCursor() {
        MapViewport v = viewport();
        double mx = v.toMapX(123);
        double my = v.toMapY(456);
        v.zoomAt(1.2, 123, 456);
        assertEquals(60, v.scale(), 1e-9);
        assertEquals(mx, v.toMapX(123), 1e-9);
        assertEquals(my, v.toMapY(456), 1e-9);
    }

    @Test
    void zoomIsClampedAndIgnoresNonsense() {
        MapViewport v = viewport();
        v.zoomAt(1e9, 0, 0);
        assertEquals(MapViewport.MAX_SCALE, v.scale(), 1e-9);
        double cx = v.centerX();
        v.zoomAt(Double.NaN, 0, 0);
        v.zoomAt(-2, 0, 0);
        v.zoomAt(0, 0, 0);
        v.panByPixels(Double.POSITIVE_INFINITY, 0);
        assertEquals(MapViewport.MAX_SCALE, v.scale(), 1e-9);
        assertEquals(cx, v.centerX(), 1e-9);
        v.zoomAt(1e-12, 0, 0);
        assertEquals(MapViewport.MIN_SCALE, v.scale(), 1e-9);
    }

    @Test
    void fitShowsTheWholeRectangle() {
        MapViewport v = viewport();
        v.fit(-1, -1, 11, 11, 20);
        assertEquals(5, v.centerX(), 1e-9);
        assertEquals((600 - 40) / 12.0, v.scale(), 1e-9);
        assertEquals(true, v.toScreenY(-1) <= 600 - 20 + 1e-9 && v.toScreenY(11) >= 20 - 1e-9);
    }

    @ParameterizedTest
    @CsvSource({ "50, 40, 1", "50, 100, 2", "10, 100, 10", "250, 25, 0.1", "0.5, 100, 200", "500, 40, 0.1" })
    void gridAndScaleBarUseOneTwoFiveSteps(double scale, double minPixels, double expected) {
        MapViewport v = new MapViewport(scale, 0, 0);
        assertEquals(expected, v.niceStep(minPixels), expected * 1e-9);
    }

    @ParameterizedTest
    @CsvSource({ "2000, 2 km", "5, 5 m", "0.2, 20 cm", "0.005, 5 mm", "1, 1 m" })
    void scaleBarLabelsUseReadableUnits(double metres, String label) {
        assertEquals(label, MapViewport.formatLength(metres));
    }
}
