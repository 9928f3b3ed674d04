package sabot.controlml.payload;

import org.osgi.annotation.versioning.ConsumerType;

import sabot.controlml.swe.SweComponent;

/**
 * Maps a resource's payload type to and from its SWE Common form (its schema, documented in
 * {@code docs/CONTROLML.md}).
 *
 * @param <T> the payload type
 */
@ConsumerType
public interface PayloadCodec<T> {

    /** @return the SWE form of a value, with canonical units; never null */
    SweComponent encode(T value);

    /**
     * @return the value of a SWE payload, converted to canonical units
     * @throws PayloadException when the structure, a unit or a value does not fit the schema (NaN and infinities
     *                          never do)
     */
    T decode(SweComponent payload) throws PayloadException;
}
