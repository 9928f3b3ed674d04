package sabot.controlml;

import java.util.Objects;
import java.util.function.Function;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The result of a ControlML request, or of a handler serving one: a value or an error, never an exception.
 *
 * @param <T> the resource's payload type
 */
@ProviderType
public sealed interface Outcome<T> permits Outcome.Success, Outcome.Failure {

    /**
     * @param value the payload; null for a {@code set} acknowledged without a read-back
     */
    record Success<T>(T value) implements Outcome<T> {
    }

    /** @param error why it failed; never null */
    record Failure<T>(ControlMlError error) implements Outcome<T> {
        public Failure {
            Objects.requireNonNull(error, "error");
        }
    }

    /** @return a success carrying a value (null acknowledges a set without read-back) */
    static <T> Outcome<T> success(T value) {
        return new Success<>(value);
    }

    /** @return an acknowledgement without payload */
    static <T> Outcome<T> done() {
        return new Success<>(null);
    }

    /** @return a failure */
    static <T> Outcome<T> failure(ControlMlError error) {
        return new Failure<>(error);
    }

    /** @return a failure with the condition's usual RFC 6120 condition */
    static <T> Outcome<T> failure(ControlMlCondition condition, String text) {
        return new Failure<>(ControlMlError.of(condition, text));
    }

    /** @return true for a success */
    default boolean isSuccess() {
        return this instanceof Success;
    }

    /**
     * @return the value of a success (may be null for a set acknowledgement)
     * @throws IllegalStateException on a failure, with its error as message
     */
    default T orElseThrow() {
        if (this instanceof Success<T> s) {
            return s.value();
        }
        throw new IllegalStateException(((Failure<T>) this).error().toString());
    }

    /** @return the error of a failure, or null for a success */
    default ControlMlError errorOrNull() {
        return this instanceof Failure<T> f ? f.error() : null;
    }

    /** @return this outcome with its value mapped */
    default <U> Outcome<U> map(Function<? super T, ? extends U> f) {
        if (this instanceof Success<T> s) {
            return new Success<>(s.value() == null ? null : f.apply(s.value()));
        }
        return new Failure<>(((Failure<T>) this).error());
    }
}
