package sabot.tools.render;

import java.awt.BasicStroke;
import java.awt.Color;
import java.awt.Graphics2D;
import java.awt.RenderingHints;
import java.awt.geom.Path2D;
import java.awt.image.BufferedImage;
import java.io.IOException;
import java.nio.file.Path;
import java.util.List;
import java.util.Optional;

import javax.imageio.ImageIO;

import sabot.model.geometry.Point2D;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.planner.PotentialField;

/**
 * Renders a costmap, optionally a navigation function over it and a path, as an RGB image with the map's top row at
 * the top. Costmap: free near-white, graded cost in shades of blue-grey, inscribed slate, lethal black, unknown light
 * grey. Navigation function: reached cells tinted from yellow (near the goal) to purple (far), with a darker
 * iso-cost line every twentieth of the largest value. Path: red line, start green, goal blue.
 */
public final class PlanImage {

    private static final int ISO_LINES = 20;
    private static final float FIELD_OPACITY = 0.45f;

    private final Costmap costmap;
    private Optional<PotentialField> field = Optional.empty();
    private List<Point2D> path = List.of();
    private int scale = 1;

    private PlanImage(Costmap costmap) {
        this.costmap = costmap;
    }

    /** @return a renderer of that costmap */
    public static PlanImage of(Costmap costmap) {
        return new PlanImage(costmap);
    }

    /** @return this renderer, drawing the field (its geometry must be the costmap's) */
    public PlanImage withField(PotentialField potentialField) {
        if (!potentialField.geometry().equals(costmap.geometry())) {
            throw new IllegalArgumentException("field and costmap have different geometries");
        }
        this.field = Optional.of(potentialField);
        return this;
    }

    /** @return this renderer, drawing the path (map-frame metres) */
    public PlanImage withPath(List<Point2D> waypoints) {
        this.path = List.copyOf(waypoints);
        return this;
    }

    /** @return this renderer, drawing each cell as {@code pixels} x {@code pixels} (1..64) */
    public PlanImage scale(int pixels) {
        if (pixels < 1 || pixels > 64) {
            throw new IllegalArgumentException("scale must be 1..64 pixels per cell, got " + pixels);
        }
        this.scale = pixels;
        return this;
    }

    /** @return the picture, {@code width * scale} x {@code height * scale} pixels */
    public BufferedImage render() {
        GridGeometry geometry = costmap.geometry();
        int width = geometry.width();
        int height = geometry.height();
        double maxValue = 0;
        if (field.isPresent()) {
            for (int row = 0; row < height; row++) {
                for (int column = 0; column < width; column++) {
                    double v = field.get().value(column, row);
                    if (v != Double.POSITIVE_INFINITY && v > maxValue) {
                        maxValue = v;
                    }
                }
            }
        }
        BufferedImage cells = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        double band = maxValue > 0 ? maxValue / ISO_LINES : 1;
        for (int row = 0; row < height; row++) {
            for (int column = 0; column < width; column++) {
                int rgb = costColour(costmap.cost(column, row));
                if (field.isPresent()) {
                    double v = field.get().value(column, row);
                    if (v != Double.POSITIVE_INFINITY && maxValue > 0) {
                        rgb = blend(rgb, ramp(v / maxValue), FIELD_OPACITY);
                        if (crossesIsoLine(field.get(), column, row, v, band)) {
                            rgb = blend(rgb, 0x202020, 0.5f);
                        }
                    }
                }
                cells.setRGB(column, height - 1 - row, rgb);
            }
        }
        BufferedImage image = new BufferedImage(width * scale, height * scale, BufferedImage.TYPE_INT_RGB);
        Graphics2D g = image.createGraphics();
        try {
            g.drawImage(cells, 0, 0, width * scale, height * scale, null);
            drawPath(g, geometry);
        } finally {
            g.dispose();
        }
        return image;
    }

    /** Renders and writes a PNG file. */
    public void writePng(Path file) throws IOException {
        if (!ImageIO.write(render(), "png", file.toFile())) {
            throw new IOException("no PNG writer available in this runtime");
        }
    }

    private void drawPath(Graphics2D g, GridGeometry geometry) {
        if (path.isEmpty()) {
            return;
        }
        g.setRenderingHint(RenderingHints.KEY_ANTIALIASING, RenderingHints.VALUE_ANTIALIAS_ON);
        Path2D.Double line = new Path2D.Double();
        for (int i = 0; i < path.size(); i++) {
            double px = geometry.toGridX(path.get(i).x()) * scale;
            double py = (geometry.height() - geometry.toGridY(path.get(i).y())) * scale;
            if (i == 0) {
                line.moveTo(px, py);
            } else {
                line.lineTo(px, py);
            }
        }
        float stroke = Math.max(1.5f, scale * 0.6f);
        g.setStroke(new BasicStroke(stroke, BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND));
        g.setColor(new Color(0xD0, 0x10, 0x10));
        g.draw(line);
        dot(g, geometry, path.get(0), new Color(0x10, 0xA0, 0x10), stroke * 3);
        dot(g, geometry, path.get(path.size() - 1), new Color(0x10, 0x40, 0xE0), stroke * 3);
    }

    private void dot(Graphics2D g, GridGeometry geometry, Point2D p, Color colour, float diameter) {
        double px = geometry.toGridX(p.x()) * scale;
        double py = (geometry.height() - geometry.toGridY(p.y())) * scale;
        g.setColor(colour);
        g.fill(new java.awt.geom.Ellipse2D.Double(px - diameter / 2, py - diameter / 2, diameter, diameter));
    }

    private static boolean crossesIsoLine(PotentialField f, int column, int row, double v, double band) {
        double right = f.value(column + 1, row);
        double up = f.value(column, row + 1);
        long level = (long) (v / band);
        return right != Double.POSITIVE_INFINITY && (long) (right / band) != level
                || up != Double.POSITIVE_INFINITY && (long) (up / band) != level;
    }

    private static int costColour(int cost) {
        if (cost == Costmap.LETHAL) {
            return 0x000000;
        }
        if (cost == Costmap.INSCRIBED) {
            return 0x505A6E;
        }
        if (cost == Costmap.NO_INFORMATION) {
            return 0xC8C8C8;
        }
        int shade = 255 - cost * 150 / Costmap.MAX_GRADED;
        return (shade * 9 / 10) << 16 | (shade * 19 / 20) << 8 | 255;
    }

    /** Yellow (0) through orange and magenta to purple (1). */
    private static int ramp(double t) {
        double x = Math.max(0, Math.min(1, t));
        int r = (int) (250 - 130 * x);
        int g = (int) (230 * (1 - x) * (1 - x) + 20);
        int b = (int) (40 + 170 * x);
        return r << 16 | g << 8 | b;
    }

    private static int blend(int base, int over, float alpha) {
        int r = (int) (((base >> 16) & 0xFF) * (1 - alpha) + ((over >> 16) & 0xFF) * alpha);
        int g = (int) (((base >> 8) & 0xFF) * (1 - alpha) + ((over >> 8) & 0xFF) * alpha);
        int b = (int) ((base & 0xFF) * (1 - alpha) + (over & 0xFF) * alpha);
        return r << 16 | g << 8 | b;
    }
}
