package sabot.model.map;

import java.io.IOException;
import java.io.OutputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;

/**
 * An 8-bit greyscale Netpbm image (binary {@code P5} or plain {@code P2}; format spec: netpbm.sourceforge.net/doc/pgm.html),
 * the image format {@code map_saver} writes. Pixels are stored as in the file: top row first.
 */
public final class PgmImage {

    private final int width;
    private final int height;
    private final byte[] pixels;

    /**
     * @param width  columns, at least 1
     * @param height rows, at least 1
     * @param pixels {@code width * height} unsigned bytes, top row first; copied
     */
    public PgmImage(int width, int height, byte[] pixels) {
        if (width <= 0 || height <= 0) {
            throw new IllegalArgumentException("image must have at least one pixel, got " + width + " x " + height);
        }
        if ((long) width * height != pixels.length) {
            throw new IllegalArgumentException(
                    "expected " + (long) width * height + " pixels for " + width + " x " + height + ", got " + pixels.length);
        }
        this.width = width;
        this.height = height;
        this.pixels = pixels.clone();
    }

    /** @return columns */
    public int width() {
        return width;
    }

    /** @return rows */
    public int height() {
        return height;
    }

    /** @return the pixel value 0..255 at a column and an image row (row 0 at the top) */
    public int pixel(int column, int imageRow) {
        return pixels[imageRow * width + column] & 0xFF;
    }

    /** @return a copy of the pixels, top row first */
    public byte[] toArray() {
        return pixels.clone();
    }

    /**
     * Reads a P5 or P2 file with a maximum value of at most 255; values are rescaled to 0..255 when the file's
     * maximum is below 255.
     *
     * @throws MapFormatException naming the file and what is wrong (missing, not a PGM, bad header, truncated data)
     */
    public static PgmImage read(Path file) throws IOException {
        byte[] bytes;
        try {
            bytes = Files.readAllBytes(file);
        } catch (NoSuchFileException e) {
            throw new MapFormatException(file, "image file does not exist");
        }
        return parse(file, bytes);
    }

    /**
     * Reads a P5 or P2 image held in memory, as {@link #read(Path)}.
     *
     * @param file where the bytes came from, named in the errors
     */
    static PgmImage parse(Path file, byte[] bytes) throws MapFormatException {
        Header header = new Header(file, bytes);
        String magic = header.token("magic number");
        if (!magic.equals("P5") && !magic.equals("P2")) {
            throw new MapFormatException(file, "not a PGM image (magic number '" + printable(magic)
                    + "', expected P5 or P2)");
        }
        int width = header.positiveInt("width");
        int height = header.positiveInt("height");
        int maxValue = header.positiveInt("maximum value");
        if (maxValue > 255) {
            throw new MapFormatException(file, "16-bit PGM (maximum value " + maxValue + ") is not supported");
        }
        long count = (long) width * height;
        if (count > GridGeometry.MAX_CELLS) {
            throw new MapFormatException(file, "image of " + width + " x " + height + " pixels is too large");
        }
        byte[] pixels = new byte[(int) count];
        if (magic.equals("P5")) {
            int start = header.position + 1; // exactly one whitespace byte separates the header from the raster
            long available = bytes.length - (long) start;
            if (available < count) {
                throw new MapFormatException(file, "truncated PGM: expected " + count + " pixel bytes, found "
                        + Math.max(0, available));
            }
            System.arraycopy(bytes, start, pixels, 0, (int) count);
        } else {
            for (int i = 0; i < count; i++) {
                String token = header.tokenOrNull();
                if (token == null) {
                    throw new MapFormatException(file, "truncated PGM: expected " + count + " pixel values, found " + i);
                }
                int value = parseIntOr(token, -1);
                if (value < 0 || value > maxValue) {
                    throw new MapFormatException(file, "pixel " + i + " is '" + printable(token) + "', expected 0.."
                            + maxValue);
                }
                pixels[i] = (byte) value;
            }
        }
        if (maxValue != 255) {
            for (int i = 0; i < pixels.length; i++) {
                int v = pixels[i] & 0xFF;
                if (v > maxValue) {
                    throw new MapFormatException(file, "pixel " + i + " is " + v + ", above the maximum value " + maxValue);
                }
                pixels[i] = (byte) Math.round(v * 255.0 / maxValue);
            }
        }
        return new PgmImage(width, height, pixels);
    }

    /** Writes the image as binary P5 with maximum value 255. */
    public void write(Path file) throws IOException {
        try (OutputStream out = Files.newOutputStream(file)) {
            out.write(("P5\n" + width + " " + height + "\n255\n").getBytes(StandardCharsets.US_ASCII));
            out.write(pixels);
        }
    }

    private static int parseIntOr(String token, int fallback) {
        try {
            return Integer.parseInt(token);
        } catch (NumberFormatException e) {
            return fallback;
        }
    }

    private static String printable(String token) {
        String cut = token.length() > 16 ? token.substring(0, 16) + "..." : token;
        return cut.replaceAll("[^\\x20-\\x7e]", "?");
    }

    /** Whitespace-separated ASCII tokens with {@code #} comments, as in a Netpbm header. */
    private static final class Header {
        private final Path file;
        private final byte[] bytes;
        private int position;

        Header(Path file, byte[] bytes) {
            this.file = file;
            this.bytes = bytes;
        }

        String token(String what) throws MapFormatException {
            String token = tokenOrNull();
            if (token == null) {
                throw new MapFormatException(file, "truncated PGM header: missing " + what);
            }
            return token;
        }

        int positiveInt(String what) throws MapFormatException {
            String token = token(what);
            int value = parseIntOr(token, -1);
            if (value <= 0) {
                throw new MapFormatException(file, "PGM " + what + " is '" + printable(token) + "', expected a positive integer");
            }
            return value;
        }

        String tokenOrNull() {
            while (position < bytes.length) {
                byte b = bytes[position];
                if (b == '#') {
                    while (position < bytes.length && bytes[position] != '\n' && bytes[position] != '\r') {
                        position++;
                    }
                } else if (isSpace(b)) {
                    position++;
                } else {
                    break;
                }
            }
            if (position >= bytes.length) {
                return null;
            }
            int start = position;
            while (position < bytes.length && !isSpace(bytes[position]) && position - start < 64) {
                position++;
            }
            return new String(bytes, start, position - start, StandardCharsets.ISO_8859_1);
        }

        private static boolean isSpace(byte b) {
            return b == ' ' || b == '\t' || b == '\n' || b == '\r' || b == 0x0B || b == 0x0C;
        }
    }
}
