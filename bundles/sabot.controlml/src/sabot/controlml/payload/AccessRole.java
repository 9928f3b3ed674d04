package sabot.controlml.payload;

import java.util.Objects;
import java.util.Set;

import sabot.controlml.Role;
import sabot.controlml.swe.SweComponent;

/**
 * {@code cm.role} (get): the requester's own role on the device (docs/CONTROLML.md section 9), so that a client can
 * offer only what the device will accept. A requester without a role is answered {@code access-denied}, not a value.
 *
 * @param role observer, operator or maintainer; never {@link Role#NONE}
 */
public record AccessRole(Role role) {
    public AccessRole {
        Objects.requireNonNull(role, "role");
        if (role == Role.NONE) {
            throw new IllegalArgumentException("cm.role carries a role: observer, operator or maintainer");
        }
    }

    private static final Set<String> ROLES = Set.of(Role.OBSERVER.label(), Role.OPERATOR.label(), Role.MAINTAINER
            .label());

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}). */
    public static final PayloadCodec<AccessRole> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(AccessRole r) {
            return new RecordBuilder().category("role", r.role().label()).build();
        }

        @Override
        public AccessRole decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "role");
            return new AccessRole(Role.ofLabel(r.category("role", ROLES)));
        }
    };
}
