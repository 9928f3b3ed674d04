package sabot.tools.render;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.awt.image.BufferedImage;
import java.io.IOException;
import java.nio.file.Path;

import javax.imageio.ImageIO;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.planner.PlanResult;
import sabot.planner.Planners;

class PlanImageTest {

    @TempDir
    Path folder;

    @Test
    void pngShowsObstaclesTopRowFirstAndThePathInRed() throws IOException {
        Costmap costmap = Costmap.filled(new GridGeometry(30, 20, 1.0, Pose2D.ORIGIN), Costmap.FREE);
        costmap.fill(new CellRegion(0, 19, 3, 19), Costmap.LETHAL);
        PlanResult.Found found = assertInstanceOf(PlanResult.Found.class,
                Planners.lpn().plan(costmap, new Point2D(2.5, 10.5), new Point2D(27.5, 10.5)));
        Path file = folder.resolve("plan.png");
        PlanImage.of(costmap).scale(4).withField(found.field()).withPath(found.path().waypoints()).writePng(file);
        BufferedImage image = ImageIO.read(file.toFile());
        assertEquals(120, image.getWidth());
        assertEquals(80, image.getHeight());
        assertEquals(0x000000, image.getRGB(2, 2) & 0xFFFFFF, "map row 19 is the image's top row");
        int onPath = image.getRGB(15 * 4, (20 - 10) * 4 - 2) & 0xFFFFFF;
        assertTrue((onPath >> 16 & 0xFF) > 150 && (onPath >> 8 & 0xFF) < 90, "red path, got " + Integer.toHexString(onPath));
    }
}
