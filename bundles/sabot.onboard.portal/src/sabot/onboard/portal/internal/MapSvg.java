package sabot.onboard.portal.internal;

import java.util.Locale;

import sabot.controlml.payload.GridMap;

/**
 * The robot's map as SVG for the status page, in metres of the map frame: the y axis flipped (SVG's points down),
 * occupied cells (ROS map_server's threshold, 65) drawn as one rectangle per run of a row, unknown cells grey; the
 * robot, its goal and its path are elements the page's script moves ({@code #robot}, {@code #goal}, {@code #path}).
 */
final class MapSvg {

    /** ROS map_server's {@code occupied_thresh} 0.65, on the 0..100 scale of {@link GridMap#cells()}. */
    static final int OCCUPIED = 65;

    private MapSvg() {
    }

    static String of(GridMap map) {
        double r = map.resolution();
        double x0 = map.origin().x();
        double y0 = map.origin().y();
        double w = map.width() * r;
        double h = map.height() * r;
        byte[] cells = map.cells();
        StringBuilder sb = new StringBuilder(16384);
        sb.append(String.format(Locale.ROOT, "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"map\" viewBox=\"%.3f %.3f "
                + "%.3f %.3f\" preserveAspectRatio=\"xMidYMid meet\" role=\"img\" aria-label=\"map\">", x0, -(y0 + h), w,
                h));
        sb.append(String.format(Locale.ROOT, "<rect x=\"%.3f\" y=\"%.3f\" width=\"%.3f\" height=\"%.3f\" class=\"free\"/>",
                x0, -(y0 + h), w, h));
        sb.append("<g class=\"occupied\">");
        runs(sb, cells, map.width(), map.height(), r, x0, y0, true);
        sb.append("</g><g class=\"unknown\">");
        runs(sb, cells, map.width(), map.height(), r, x0, y0, false);
        sb.append("</g>");
        sb.append("<polyline id=\"path\" points=\"\"/>");
        sb.append("<circle id=\"goal\" r=\"0.12\" cx=\"0\" cy=\"0\" visibility=\"hidden\"/>");
        sb.append("<g id=\"robot\" visibility=\"hidden\"><circle r=\"0.2\"/><line x1=\"0\" y1=\"0\" x2=\"0.3\" "
                + "y2=\"0\"/></g>");
        sb.append("</svg>");
        return sb.toString();
    }

    private static void runs(StringBuilder sb, byte[] cells, int width, int height, double r, double x0, double y0,
            boolean occupied) {
        for (int row = 0; row < height; row++) {
            int col = 0;
            while (col < width) {
                if (!matches(cells[row * width + col], occupied)) {
                    col++;
                    continue;
                }
                int start = col;
                while (col < width && matches(cells[row * width + col], occupied)) {
                    col++;
                }
                sb.append(String.format(Locale.ROOT, "<rect x=\"%.3f\" y=\"%.3f\" width=\"%.3f\" height=\"%.3f\"/>",
                        x0 + start * r, -(y0 + (row + 1) * r), (col - start) * r, r));
            }
        }
    }

    private static boolean matches(byte cell, boolean occupied) {
        return occupied ? cell >= OCCUPIED : cell < 0;
    }
}
