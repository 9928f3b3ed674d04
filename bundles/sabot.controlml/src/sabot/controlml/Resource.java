package sabot.controlml;

import java.util.Objects;

import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.swe.DataRecord;
import sabot.controlml.swe.RecordTemplate;

/**
 * A ControlML resource: its name ({@code res}), the operations it allows, and the schema of its payloads (its
 * codecs). The protocol's resources are {@link Resources}; a bundle makes its own with {@link #builder} and adds it to
 * a {@link ResourceRegistry} ({@link ControlMlManager#resources()}).
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
    private boolean moving;
    /** Who may set it; the strictest until told otherwise (deny by default). */
    private Role setRole = Role.MAINTAINER;
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

    /**
     * Starts a resource of another bundle than this one (section 4's are {@link Resources}). Its values always travel
     * in the XML form: the text form's record structures are section 4's, known to every reader.
     *
     * @param name  the {@code res} value, {@code cm} and one to four dot-separated names
     *              ({@link ControlMlElement#RESOURCE_SYNTAX}), e.g. {@code cm.pid.step}
     * @param codec the codec of the resource's value (the payload of a set and of a result)
     * @return a builder; the resource allows neither get nor set until told
     * @throws IllegalArgumentException when the name is not of the syntax
     */
    public static <T> Builder<T, NoQuery> builder(String name, PayloadCodec<T> codec) {
        if (name == null || !ControlMlElement.RESOURCE_SYNTAX.matcher(name).matches()) {
            throw new IllegalArgumentException("'" + name + "' is not a resource name (cm.<name>, one to four names of"
                    + " a lower-case letter and up to 30 lower-case letters, digits or '-')");
        }
        return new Builder<>(name, Objects.requireNonNull(codec, "codec"), null);
    }

    /**
     * Builds a {@link Resource}.
     *
     * @param <T> the value
     * @param <Q> the query of a get
     */
    public static final class Builder<T, Q> {
        private final String name;
        private final PayloadCodec<T> codec;
        private final PayloadCodec<Q> queryCodec;
        private boolean get;
        private boolean set;
        private String description = "";
        private boolean moving;
        private Role setRole = Role.MAINTAINER;

        private Builder(String name, PayloadCodec<T> codec, PayloadCodec<Q> queryCodec) {
            this.name = name;
            this.codec = codec;
            this.queryCodec = queryCodec;
        }

        /** @return this builder; gets are allowed */
        public Builder<T, Q> gettable() {
            this.get = true;
            return this;
        }

        /** @return this builder; sets are allowed */
        public Builder<T, Q> settable() {
            this.set = true;
            return this;
        }

        /**
         * @param query the codec of a get's payload (e.g. which file to read)
         * @return a builder of a resource whose get carries that query (and is allowed)
         */
        public <R> Builder<T, R> query(PayloadCodec<R> query) {
            Builder<T, R> b = new Builder<>(name, codec, Objects.requireNonNull(query, "query"));
            b.get = true;
            b.set = set;
            b.description = description;
            b.moving = moving;
            b.setRole = setRole;
            return b;
        }

        /**
         * @return this builder; a set of the resource can start motion, so it carries its send time ({@code sent},
         *         section 1) and is judged by its age ({@link Resource#isMotionCommand()})
         */
        public Builder<T, Q> movesTheRobot() {
            this.moving = true;
            return this;
        }

        /**
         * @param role the least role whose holders may set the resource (default {@link Role#MAINTAINER}: a
         *             bundle's resource changes the robot unless it says otherwise); not {@link Role#NONE}
         * @return this builder
         */
        public Builder<T, Q> setBy(Role role) {
            this.setRole = checkedSetRole(name, role);
            return this;
        }

        /** @param text one line for people (logs, the resource's documentation); never null */
        public Builder<T, Q> description(String text) {
            this.description = Objects.requireNonNull(text);
            return this;
        }

        /**
         * @return the resource
         * @throws IllegalStateException when it allows neither get nor set
         */
        public Resource<T, Q> build() {
            if (!get && !set) {
                throw new IllegalStateException(name + " allows neither get nor set");
            }
            Resource<T, Q> r = new Resource<>(name, codec, queryCodec, get, set, description);
            r.moving = moving;
            r.setRole = setRole;
            return r;
        }
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
     * @return true when a set of this resource can start motion: such a set MUST carry its send time ({@code sent}),
     *         and a device refuses one without it ({@code bad-attributes}) or older than its limit
     *         ({@code stale-command})
     */
    public boolean isMotionCommand() {
        return moving;
    }

    /** @return the least role that may set the resource (a get needs {@link Role#OBSERVER}) */
    public Role setRole() {
        return setRole;
    }

    /** Gives a resource of section 4 the role its sets need (section 9's table). */
    Resource<T, Q> setBy(Role role) {
        this.setRole = checkedSetRole(name, role);
        return this;
    }

    /**
     * Lets observers set a resource of section 4: only {@code cm.telemetry}, whose set (a lease) asks for telemetry
     * and changes nothing on the robot (section 9's table).
     */
    Resource<T, Q> setByObservers() {
        this.setRole = Role.OBSERVER;
        return this;
    }

    private static Role checkedSetRole(String name, Role role) {
        if (role == null || role == Role.NONE || role == Role.OBSERVER) {
            throw new IllegalArgumentException(name + ": a set needs the operator or the maintainer role, not "
                    + role);
        }
        return role;
    }

    /** Marks a resource of section 4 whose set can start motion (see {@link #isMotionCommand()}). */
    Resource<T, Q> movingTheRobot() {
        this.moving = true;
        return this;
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
