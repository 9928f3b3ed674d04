package sabot.identity;

import java.io.ByteArrayOutputStream;

/**
 * Base45 (RFC 9285): two bytes in three characters of the QR alphanumeric set, so that a QR code stores binary data
 * in alphanumeric mode at about 97 % of byte-mode density, as text any reader can show (the EU digital COVID
 * certificate's {@code HC1:} payload uses the same scheme).
 */
public final class Base45 {

    private static final String ALPHABET = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ $%*+-./:";

    private Base45() {
    }

    /** @return the Base45 text of bytes */
    public static String encode(byte[] data) {
        StringBuilder sb = new StringBuilder(data.length * 3 / 2 + 2);
        int i = 0;
        for (; i + 1 < data.length; i += 2) {
            int n = (data[i] & 0xff) * 256 + (data[i + 1] & 0xff);
            sb.append(ALPHABET.charAt(n % 45)).append(ALPHABET.charAt(n / 45 % 45)).append(ALPHABET.charAt(n / 2025));
        }
        if (i < data.length) {
            int n = data[i] & 0xff;
            sb.append(ALPHABET.charAt(n % 45)).append(ALPHABET.charAt(n / 45));
        }
        return sb.toString();
    }

    /** @return the bytes of Base45 text @throws IllegalArgumentException when it is not Base45 */
    public static byte[] decode(String text) {
        ByteArrayOutputStream out = new ByteArrayOutputStream(text.length() * 2 / 3 + 1);
        int i = 0;
        for (; i + 2 < text.length(); i += 3) {
            int n = digit(text, i) + digit(text, i + 1) * 45 + digit(text, i + 2) * 2025;
            if (n > 0xffff) {
                throw new IllegalArgumentException("not Base45 at " + i);
            }
            out.write(n >> 8);
            out.write(n & 0xff);
        }
        int rest = text.length() - i;
        if (rest == 2) {
            int n = digit(text, i) + digit(text, i + 1) * 45;
            if (n > 0xff) {
                throw new IllegalArgumentException("not Base45 at " + i);
            }
            out.write(n);
        } else if (rest == 1) {
            throw new IllegalArgumentException("Base45 text of length " + text.length());
        }
        return out.toByteArray();
    }

    private static int digit(String s, int i) {
        int d = ALPHABET.indexOf(s.charAt(i));
        if (d < 0) {
            throw new IllegalArgumentException("'" + s.charAt(i) + "' is not a Base45 character");
        }
        return d;
    }
}
