package sabot.controlml;

import java.time.DateTimeException;
import java.time.LocalDate;
import java.util.Objects;

/**
 * A ControlML request id, {@code YYYYMMDD:UINT32}: the requester's UTC date and a 32-bit unsigned counter. It is
 * unique per requester (full JID) per day, which lets a robot recognise a retransmitted command and answer it
 * again without applying it twice.
 *
 * @param date    the UTC day the requester issued it; never null, years 0000-9999
 * @param counter 0 to 4,294,967,295
 */
public record RequestId(LocalDate date, long counter) implements Comparable<RequestId> {

    /** Largest counter value (2^32 - 1). */
    public static final long MAX_COUNTER = 0xFFFF_FFFFL;

    public RequestId {
        Objects.requireNonNull(date, "date");
        if (date.getYear() < 0 || date.getYear() > 9999) {
            throw new IllegalArgumentException("year out of range: " + date);
        }
        if (counter < 0 || counter > MAX_COUNTER) {
            throw new IllegalArgumentException("counter out of range: " + counter);
        }
    }

    /**
     * Parses the wire form strictly: eight digits forming a valid date, a colon, and a decimal UINT32 without sign
     * or leading zeros.
     *
     * @return the id, or null when {@code text} is not a valid id
     */
    public static RequestId parse(String text) {
        if (text == null || text.length() < 10 || text.length() > 19 || text.charAt(8) != ':') {
            return null;
        }
        for (int i = 0; i < text.length(); i++) {
            if (i != 8 && (text.charAt(i) < '0' || text.charAt(i) > '9')) {
                return null;
            }
        }
        String counterText = text.substring(9);
        if (counterText.length() > 10 || (counterText.length() > 1 && counterText.charAt(0) == '0')) {
            return null;
        }
        long counter = Long.parseLong(counterText);
        if (counter > MAX_COUNTER) {
            return null;
        }
        try {
            LocalDate date = LocalDate.of(Integer.parseInt(text.substring(0, 4)), Integer.parseInt(text.substring(4,
                    6)), Integer.parseInt(text.substring(6, 8)));
            return new RequestId(date, counter);
        } catch (DateTimeException e) {
            return null;
        }
    }

    /** @return the wire form, e.g. {@code 20261121:42} */
    @Override
    public String toString() {
        StringBuilder sb = new StringBuilder(19);
        int y = date.getYear();
        sb.append((char) ('0' + y / 1000)).append((char) ('0' + y / 100 % 10)).append((char) ('0' + y / 10 % 10))
                .append((char) ('0' + y % 10));
        int m = date.getMonthValue();
        sb.append((char) ('0' + m / 10)).append((char) ('0' + m % 10));
        int d = date.getDayOfMonth();
        sb.append((char) ('0' + d / 10)).append((char) ('0' + d % 10));
        return sb.append(':').append(counter).toString();
    }

    @Override
    public int compareTo(RequestId o) {
        int c = date.compareTo(o.date);
        return c != 0 ? c : Long.compare(counter, o.counter);
    }
}
