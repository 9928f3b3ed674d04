package sabot.identity;

import java.util.Objects;

import org.osgi.annotation.versioning.ProviderType;

/**
 * A value or the reason there is none; identity operations never throw for expected failures.
 *
 * @param <T> the value type
 */
@ProviderType
public sealed interface IdentityResult<T> permits IdentityResult.Ok, IdentityResult.Err {

    /** Why an identity operation failed. */
    enum Problem {
        /** the inventory does not fit a QR code even after compaction */
        TOO_LARGE_FOR_QR,
        /** the image holds no readable QR code */
        NO_QR_CODE,
        /** the QR code's text is not an inventory document (or its hash does not match) */
        NOT_AN_INVENTORY,
        /** the vCard is missing fields a device profile needs */
        NOT_A_DEVICE,
        /** the entity has no vCard */
        NO_VCARD,
        /** the server or the network failed */
        XMPP_FAILURE
    }

    /** @param value never null */
    record Ok<T>(T value) implements IdentityResult<T> {
        public Ok {
            Objects.requireNonNull(value, "value");
        }
    }

    /**
     * @param problem what went wrong
     * @param text    details for a human
     */
    record Err<T>(Problem problem, String text) implements IdentityResult<T> {
        public Err {
            Objects.requireNonNull(problem, "problem");
            Objects.requireNonNull(text, "text");
        }
    }

    /** @return the value @throws IllegalStateException with the problem when there is none */
    default T orElseThrow() {
        if (this instanceof Ok<T> ok) {
            return ok.value();
        }
        Err<T> e = (Err<T>) this;
        throw new IllegalStateException(e.problem() + ": " + e.text());
    }

    /** @return the problem, or null for a value */
    default Problem problemOrNull() {
        return this instanceof Err<T> e ? e.problem() : null;
    }

    /** @return an error result */
    static <T> IdentityResult<T> err(Problem problem, String text) {
        return new Err<>(problem, text);
    }
}
