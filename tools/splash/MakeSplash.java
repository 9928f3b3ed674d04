import java.awt.BasicStroke;
import java.awt.Color;
import java.awt.Font;
import java.awt.GradientPaint;
import java.awt.Graphics2D;
import java.awt.RenderingHints;
import java.awt.geom.Ellipse2D;
import java.awt.geom.Path2D;
import java.awt.image.BufferedImage;
import java.io.File;
import java.io.IOException;

import javax.imageio.ImageIO;

/**
 * Draws the Sabot Workbench splash image (bundles/sabot.workbench.splash/splash.bmp): the workspace grid, a robot
 * footprint with its heading and trail, the name. The bottom band is left plain for the progress bar and the message
 * line the splash handler draws there (SplashLayout in sabot.workbench.splash has the same rectangles).
 * Run: java tools/splash/MakeSplash.java bundles/sabot.workbench.splash/splash.bmp
 * (the launcher's native splash reads BMP; 24-bit, no alpha).
 */
public class MakeSplash {
    static final int W = 480, H = 300;

    public static void main(String[] args) throws IOException {
        System.setProperty("java.awt.headless", "true");
        BufferedImage img = new BufferedImage(W, H, BufferedImage.TYPE_3BYTE_BGR);
        Graphics2D g = img.createGraphics();
        g.setRenderingHint(RenderingHints.KEY_ANTIALIASING, RenderingHints.VALUE_ANTIALIAS_ON);
        g.setRenderingHint(RenderingHints.KEY_TEXT_ANTIALIASING, RenderingHints.VALUE_TEXT_ANTIALIAS_ON);
        g.setPaint(new GradientPaint(0, 0, new Color(0x0b, 0x1f, 0x3a), W, H, new Color(0x17, 0x3d, 0x6b)));
        g.fillRect(0, 0, W, H);

        // the workspace grid (0.5 m cells of the map view), fading to the right
        for (int x = 0; x <= W; x += 24) {
            g.setColor(new Color(255, 255, 255, Math.max(8, 40 - x / 16)));
            g.drawLine(x, 0, x, 228);
        }
        for (int y = 12; y <= 228; y += 24) {
            g.setColor(new Color(255, 255, 255, 24));
            g.drawLine(0, y, W, y);
        }

        // the robot's trail to where it is, then the robot: footprint, heading, covariance ellipse
        Path2D trail = new Path2D.Double();
        trail.moveTo(30, 200);
        trail.curveTo(90, 210, 110, 120, 170, 130);
        trail.curveTo(220, 138, 240, 90, 300, 84);
        g.setStroke(new BasicStroke(3f, BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND, 1f, new float[] {2f, 7f}, 0f));
        g.setColor(new Color(0x5f, 0xc8, 0xff));
        g.draw(trail);
        double rx = 330, ry = 80, r = 30;
        g.setStroke(new BasicStroke(1.5f));
        g.setColor(new Color(0xff, 0xc8, 0x3c, 110));
        g.draw(new Ellipse2D.Double(rx - 46, ry - 30, 92, 60));
        g.setColor(new Color(0x1f, 0x9d, 0xe0));
        g.fill(new Ellipse2D.Double(rx - r, ry - r, 2 * r, 2 * r));
        g.setColor(Color.WHITE);
        g.setStroke(new BasicStroke(3f));
        g.draw(new Ellipse2D.Double(rx - r, ry - r, 2 * r, 2 * r));
        Path2D heading = new Path2D.Double();
        heading.moveTo(rx - 8, ry - 14);
        heading.lineTo(rx + 22, ry);
        heading.lineTo(rx - 8, ry + 14);
        heading.closePath();
        g.fill(heading);
        // a goal marker ahead of it
        g.setColor(new Color(0xff, 0xc8, 0x3c));
        g.setStroke(new BasicStroke(2.5f));
        g.drawLine(420, 150, 440, 170);
        g.drawLine(440, 150, 420, 170);

        g.setColor(Color.WHITE);
        g.setFont(new Font("DejaVu Sans", Font.BOLD, 52));
        g.drawString("Sabot", 24, 168);
        g.setFont(new Font("DejaVu Sans", Font.PLAIN, 22));
        g.drawString("Workbench", 28, 198);
        g.setFont(new Font("DejaVu Sans", Font.PLAIN, 12));
        g.setColor(new Color(0xc8, 0xd8, 0xec));
        g.drawString("Operator console of the Sabot robot fleet", 28, 220);

        // the band of the progress bar and the message line
        g.setColor(new Color(0x08, 0x16, 0x2a));
        g.fillRect(0, 232, W, H - 232);
        g.setColor(new Color(0x5f, 0xc8, 0xff));
        g.fillRect(0, 232, W, 2);
        g.dispose();
        File out = new File(args.length > 0 ? args[0] : "splash.bmp");
        if (!ImageIO.write(img, "bmp", out)) {
            throw new IOException("no BMP writer");
        }
        System.out.println("wrote " + out + " (" + W + "x" + H + ")");
    }
}
