package sabot.workbench.views;

import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.PaletteData;
import org.eclipse.swt.graphics.Pattern;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Display;

/**
 * An opaque image in the workbench's memory (made from an {@link ImageData}: a cairo image surface on GTK, drawn into
 * by this process rather than by the X server) and a pattern on it, to copy it onto another surface with a fill.
 * <p>
 * Not with {@link GC#drawImage}: SWT 3.135's GTK {@code drawImage} reads every source image back into a new
 * {@link ImageData} to learn its size before it draws (eclipse-platform/eclipse.platform.swt#3507, fixed by #3510
 * after that release): for the Workspace's frame a 2.3 MB copy and conversion a paint, and as much garbage. A
 * {@link Pattern} on the image draws from its surface directly.
 */
final class MemoryImage implements AutoCloseable {

    private final Image image;
    private final Pattern pattern;
    private final int width;
    private final int height;

    private MemoryImage(Display display, int width, int height) {
        this.width = width;
        this.height = height;
        this.image = new Image(display, new ImageData(width, height, 24, new PaletteData(0xFF0000, 0x00FF00,
                0x0000FF)));
        this.pattern = new Pattern(display, image);
    }

    /** @return a new image of the area's size, or {@code old} when it already has that size (else {@code old} is closed) */
    static MemoryImage sized(MemoryImage old, Display display, Rectangle area) {
        if (old != null && old.width == area.width && old.height == area.height) {
            return old;
        }
        if (old != null) {
            old.close();
        }
        return new MemoryImage(display, area.width, area.height);
    }

    /** @return the image, to draw into with a {@link GC} */
    Image image() {
        return image;
    }

    /** Copies the whole image onto {@code gc} with its top-left corner at the origin; leaves the background colour on. */
    void drawOnto(GC gc) {
        gc.setBackgroundPattern(pattern);
        gc.fillRectangle(0, 0, width, height);
        gc.setBackgroundPattern(null);
    }

    @Override
    public void close() {
        pattern.dispose();
        image.dispose();
    }
}
