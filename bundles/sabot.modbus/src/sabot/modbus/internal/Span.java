package sabot.modbus.internal;

import java.util.List;

import sabot.modbus.internal.ModbusMap.Field;

/**
 * A run of records of one file that one sub-request reads: from the first field's record to the end of the last.
 *
 * @param file   file number
 * @param record first record
 * @param count  registers
 */
record Span(int file, int record, int count) {

    /** @return the span covering {@code fields} (all of one file) */
    static Span of(List<Field> fields) {
        int first = Integer.MAX_VALUE;
        int end = Integer.MIN_VALUE;
        int file = fields.get(0).file();
        for (Field f : fields) {
            if (f.file() != file) {
                throw new IllegalArgumentException("fields of files " + file + " and " + f.file() + " in one span");
            }
            first = Math.min(first, f.record());
            end = Math.max(end, f.record() + f.registers());
        }
        return new Span(file, first, end - first);
    }

    /** @return the span covering {@code fields} */
    static Span of(Field... fields) {
        return of(List.of(fields));
    }

    /** @return the raw value of {@code f} in registers read for this span */
    long raw(Field f, short[] regs) {
        int offset = f.record() - record;
        if (offset < 0 || offset + f.width() > count) {
            throw new IllegalArgumentException(f.name() + " is not in " + this);
        }
        return f.decode(regs, offset);
    }

    /** @return the SI value of {@code f} in registers read for this span */
    double si(Field f, short[] regs) {
        return f.si(raw(f, regs));
    }
}
