package sabot.identity;

import java.awt.image.BufferedImage;
import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.util.EnumMap;
import java.util.Map;
import java.util.zip.DataFormatException;
import java.util.zip.Deflater;
import java.util.zip.Inflater;

import javax.imageio.ImageIO;

import com.google.zxing.BarcodeFormat;
import com.google.zxing.BinaryBitmap;
import com.google.zxing.DecodeHintType;
import com.google.zxing.EncodeHintType;
import com.google.zxing.NotFoundException;
import com.google.zxing.RGBLuminanceSource;
import com.google.zxing.ReaderException;
import com.google.zxing.WriterException;
import com.google.zxing.common.BitMatrix;
import com.google.zxing.common.HybridBinarizer;
import com.google.zxing.qrcode.QRCodeReader;
import com.google.zxing.qrcode.QRCodeWriter;
import com.google.zxing.qrcode.decoder.ErrorCorrectionLevel;

/**
 * The inventory as a QR code in a PNG (ZXing), for the vCard's PHOTO.
 * <p>
 * Forms, tried in order (see {@code docs/IDENTITY.md}):
 * <ol>
 * <li>{@link Form#PLAIN}: the compact XML document as UTF-8, error correction M (15 % of the symbol restorable),
 * up to 2,331 bytes in a version-40 symbol; any QR reader shows the document itself;</li>
 * <li>{@link Form#PLAIN_LOW_ECC}: the same with error correction L (7 %), up to 2,953 bytes;</li>
 * <li>{@link Form#DEFLATED}: {@value #DEFLATED_PREFIX} followed by the Base45 (RFC 9285) text of the raw-DEFLATE
 * (RFC 1951) compressed document, error correction L, in alphanumeric mode (up to 4,296 characters, about 2,860
 * compressed bytes; the EU COVID certificate's {@code HC1:} scheme): what a runtime with a hundred bundles needs
 * (about 11 KB of XML). A generic reader shows the prefixed text; {@link #decode} (or Base45 + inflate) restores the
 * document.</li>
 * </ol>
 * When even the deflated form does not fit, {@link #encode} answers {@link IdentityResult.Problem#TOO_LARGE_FOR_QR}
 * with the sizes.
 */
public final class QrInventory {

    /** Prefix of the deflated form. */
    public static final String DEFLATED_PREFIX = "SABOTQR1:";
    /** Pixels per QR module in the PNG: 4 keeps the symbol readable by camera-based readers. */
    public static final int MODULE_PIXELS = 4;
    /** Quiet zone in modules (ISO/IEC 18004 requires 4). */
    public static final int QUIET_ZONE = 4;

    /** How the document was put into the symbol. */
    public enum Form {
        /** XML, error correction M */
        PLAIN,
        /** XML, error correction L */
        PLAIN_LOW_ECC,
        /** prefixed base64 of DEFLATE-compressed XML, error correction L */
        DEFLATED
    }

    /**
     * @param png       the PNG image
     * @param form      the form used
     * @param textBytes bytes of the text in the symbol
     * @param xmlBytes  bytes of the XML document
     * @param modules   symbol size in modules (21 for version 1 ... 177 for version 40)
     */
    public record Encoded(byte[] png, Form form, int textBytes, int xmlBytes, int modules) {
    }

    private QrInventory() {
    }

    /** @return the QR code of an inventory, or {@link IdentityResult.Problem#TOO_LARGE_FOR_QR} */
    public static IdentityResult<Encoded> encode(Inventory inventory) {
        String xml = InventoryXml.write(inventory);
        int xmlBytes = xml.getBytes(StandardCharsets.UTF_8).length;
        String deflated = DEFLATED_PREFIX + Base45.encode(deflate(xml));
        Object[][] attempts = { { Form.PLAIN, xml, ErrorCorrectionLevel.M }, { Form.PLAIN_LOW_ECC, xml,
            ErrorCorrectionLevel.L }, { Form.DEFLATED, deflated, ErrorCorrectionLevel.L } };
        for (Object[] a : attempts) {
            String text = (String) a[1];
            try {
                BitMatrix m = matrix(text, (ErrorCorrectionLevel) a[2]);
                int modules = m.getWidth() / MODULE_PIXELS - 2 * QUIET_ZONE;
                return new IdentityResult.Ok<>(new Encoded(png(m), (Form) a[0], text.getBytes(
                        StandardCharsets.UTF_8).length, xmlBytes, modules));
            } catch (WriterException tooBig) {
                // try the next, denser form
            }
        }
        return IdentityResult.err(IdentityResult.Problem.TOO_LARGE_FOR_QR, "the inventory is " + xmlBytes
                + " bytes of XML, " + deflated.length() + " characters deflated and Base45-encoded; a QR code holds at"
                + " most 2953 bytes or 4296 alphanumeric characters (version 40, error correction L). Leave libraries"
                + " out of the document or split it.");
    }

    private static BitMatrix matrix(String text, ErrorCorrectionLevel level) throws WriterException {
        Map<EncodeHintType, Object> hints = new EnumMap<>(EncodeHintType.class);
        hints.put(EncodeHintType.ERROR_CORRECTION, level);
        hints.put(EncodeHintType.CHARACTER_SET, "UTF-8");
        hints.put(EncodeHintType.MARGIN, QUIET_ZONE);
        BitMatrix unit = new QRCodeWriter().encode(text, BarcodeFormat.QR_CODE, 0, 0, hints);
        int size = unit.getWidth() * MODULE_PIXELS;
        return new QRCodeWriter().encode(text, BarcodeFormat.QR_CODE, size, size, hints);
    }

    private static byte[] png(BitMatrix m) {
        BufferedImage img = new BufferedImage(m.getWidth(), m.getHeight(), BufferedImage.TYPE_BYTE_BINARY);
        for (int y = 0; y < m.getHeight(); y++) {
            for (int x = 0; x < m.getWidth(); x++) {
                img.setRGB(x, y, m.get(x, y) ? 0xFF000000 : 0xFFFFFFFF);
            }
        }
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        try {
            ImageIO.write(img, "png", out);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
        return out.toByteArray();
    }

    /** @return the text in the QR code of an image (PNG or any format ImageIO reads) */
    public static IdentityResult<String> readText(byte[] image) {
        BufferedImage img;
        try {
            img = ImageIO.read(new ByteArrayInputStream(image));
        } catch (IOException e) {
            img = null;
        }
        if (img == null) {
            return IdentityResult.err(IdentityResult.Problem.NO_QR_CODE, "not an image");
        }
        int[] pixels = img.getRGB(0, 0, img.getWidth(), img.getHeight(), null, 0, img.getWidth());
        // First as a clean, axis-aligned symbol (what PHOTO carries): ZXing's general finder-pattern detector misses
        // some large symbols (measured: 3 of 57 random version 30-40 codes at 4 px per module), the pure-barcode
        // path reads them all. Then the general detector, for photographs and scans of the code.
        ReaderException last = null;
        for (boolean pure : new boolean[] { true, false }) {
            BinaryBitmap bitmap = new BinaryBitmap(new HybridBinarizer(new RGBLuminanceSource(img.getWidth(), img
                    .getHeight(), pixels)));
            Map<DecodeHintType, Object> hints = new EnumMap<>(DecodeHintType.class);
            hints.put(DecodeHintType.CHARACTER_SET, "UTF-8");
            hints.put(DecodeHintType.TRY_HARDER, Boolean.TRUE);
            if (pure) {
                hints.put(DecodeHintType.PURE_BARCODE, Boolean.TRUE);
            }
            try {
                return new IdentityResult.Ok<>(new QRCodeReader().decode(bitmap, hints).getText());
            } catch (ReaderException e) {
                last = e;
            }
        }
        if (last instanceof NotFoundException) {
            return IdentityResult.err(IdentityResult.Problem.NO_QR_CODE, "no QR code in the image");
        }
        return IdentityResult.err(IdentityResult.Problem.NO_QR_CODE, "unreadable QR code: " + last);
    }

    /** @return the inventory in a QR code image (either form) */
    public static IdentityResult<Inventory> decode(byte[] image) {
        IdentityResult<String> text = readText(image);
        if (text instanceof IdentityResult.Err<String> e) {
            return IdentityResult.err(e.problem(), e.text());
        }
        return fromText(text.orElseThrow());
    }

    /** @return the inventory in a QR code's text (either form) */
    public static IdentityResult<Inventory> fromText(String text) {
        if (text.startsWith(DEFLATED_PREFIX)) {
            try {
                return InventoryXml.read(inflate(Base45.decode(text.substring(DEFLATED_PREFIX.length()))));
            } catch (IllegalArgumentException | DataFormatException e) {
                return IdentityResult.err(IdentityResult.Problem.NOT_AN_INVENTORY, "bad deflated form: " + e);
            }
        }
        return InventoryXml.read(text);
    }

    private static byte[] deflate(String xml) {
        Deflater d = new Deflater(Deflater.BEST_COMPRESSION, true);
        d.setInput(xml.getBytes(StandardCharsets.UTF_8));
        d.finish();
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        byte[] buf = new byte[4096];
        while (!d.finished()) {
            out.write(buf, 0, d.deflate(buf));
        }
        d.end();
        return out.toByteArray();
    }

    private static String inflate(byte[] data) throws DataFormatException {
        Inflater inf = new Inflater(true);
        inf.setInput(data);
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        byte[] buf = new byte[4096];
        while (!inf.finished()) {
            int n = inf.inflate(buf);
            if (n == 0 && (inf.needsInput() || inf.needsDictionary())) {
                break;
            }
            out.write(buf, 0, n);
            if (out.size() > 1 << 20) {
                throw new DataFormatException("inflates to more than 1 MiB");
            }
        }
        inf.end();
        return out.toString(StandardCharsets.UTF_8);
    }
}
