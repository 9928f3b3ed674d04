package sabot.controlml;

import java.util.Objects;

import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.swe.DataRecord;
import sabot.controlml.swe.RecordTemplate;

/**
 * A ControlML resource: its name ({@code res}), the operations it allows, and the schema of its payloads.
 * The catalogue is {@link Resources}.
 *
 * @param <T> the resource's value: the payload of a set and of a get's result
 * @param <Q> the payload of a get (a query, e.g. which file to read), {@link NoQuery} when a get carries none
 */
public final class Resource<T, Q> {

    private final String name;
    private final PayloadCodec<T> codec;
    private final PayloadCodec<Q> queryCodec;
    private final boolean gettable;
    private final boolean settable;
    private final String description;
    private final String recordHref;
    private T recordPrototype;
    private volatile RecordTemplate recordTemplate;

    Resource(String name, PayloadCodec<T> codec, PayloadCodec<Q> queryCodec, boolean gettable, boolean settable,
            String description) {
        if (!ControlMlElement.RESOURCE_SYNTAX.matcher(name).matches()) {
            throw new IllegalArgumentException(name);
        }
        this.name = name;
        this.codec = Objects.requireNonNull(codec);
        this.queryCodec = queryCodec;
        this.gettable = gettable;
        this.settable = settable;
        this.description = description;
        this.recordHref = ControlMl.RECORD_STRUCTURE_PREFIX + name;
    }

    /** @return the {@code res} attribute value, e.g. {@code cm.position} */
    public String name() {
        return name;
    }

    /** @return the codec of the resource's value */
    public PayloadCodec<T> codec() {
        return codec;
    }

    /** @return the codec of a get's query, or null when a get carries no payload */
    public PayloadCodec<Q> queryCodec() {
        return queryCodec;
    }

    /** @return true when a get may be sent */
    public boolean isGettable() {
        return gettable;
    }

    /** @return true when a set may be sent */
    public boolean isSettable() {
        return settable;
    }

    /**
     * Gives the resource a record structure, so that its values may travel in the text form (see
     * {@link RecordTemplate}).
     *
     * @param prototype any value; its encoding fixes the structure
     */
    Resource<T, Q> withRecordStructure(T prototype) {
        this.recordPrototype = Objects.requireNonNull(prototype);
        return this;
    }

    /**
     * @return the structure of the resource's values in the text form, or null when they always travel as XML
     *         (variable structure, or free text)
     */
    public RecordTemplate recordTemplate() {
        RecordTemplate template = recordTemplate;
        if (template == null && recordPrototype != null) {
            // built on first use: codecs may read catalogue constants that are initialised after the resources
            template = new RecordTemplate((DataRecord) codec.encode(recordPrototype));
            recordTemplate = template;
        }
        return template;
    }

    /** @return the {@code xlink:href} by which a text-form payload refers to {@link #recordTemplate()} */
    public String recordHref() {
        return recordHref;
    }

    /** @return a one-line description */
    public String description() {
        return description;
    }

    @Override
    public String toString() {
        return name;
    }
}
