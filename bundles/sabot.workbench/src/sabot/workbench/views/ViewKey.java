package sabot.workbench.views;

/**
 * The view on the map a frame is drawn for: the canvas's size, the scale and the map point at its centre; what is kept
 * from frame to frame (the static layers, the trails' paths) is kept for one view.
 */
record ViewKey(int width, int height, double scale, double centerX, double centerY) {
}
