package sabot.controlml;

import java.util.Collection;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The resources one ControlML endpoint knows: those of the protocol (section 4, {@link Resources}), registered when the
 * registry is made, and those other bundles add with {@link #register}, each with its codecs (the pattern of Smack's
 * {@code ProviderManager}, but one registry per {@link ControlMlManager}, not one per process, so that two bundles in
 * one framework, or two robots in one test, never see each other's additions).
 * <p>
 * A request for a name of the right syntax that is in no registry is refused with
 * {@link ControlMlCondition#UNKNOWN_RESOURCE} (section 8). A name can be registered once: a second registration of it
 * is refused, so no bundle can replace another's codec by accident. Thread-safe.
 */
public final class ResourceRegistry {

    /** Copy on write: every request looks a name up, registrations are rare. */
    private volatile Map<String, Resource<?, ?>> byName;

    /** A registry holding the resources of section 4. */
    public ResourceRegistry() {
        Map<String, Resource<?, ?>> initial = new LinkedHashMap<>();
        for (Resource<?, ?> r : Resources.all()) {
            initial.put(r.name(), r);
        }
        byName = Collections.unmodifiableMap(initial);
    }

    /** Ends a registration made by {@link #register}. */
    @FunctionalInterface
    @ProviderType
    public interface Registration extends AutoCloseable {
        /** Removes the resource from the registry; a second call does nothing. */
        @Override
        void close();
    }

    /**
     * Adds a resource: from now on requests for it reach the handlers registered for it
     * ({@link ControlMlManager#onGet}, {@link ControlMlManager#onSet}) and are checked with its codecs.
     *
     * @param resource a resource made with {@link Resource#builder}
     * @return the registration; closing it removes the resource (a bundle closes it when it stops)
     * @throws IllegalArgumentException when a resource of that name is registered already (a protocol resource of
     *                                  section 4 included), naming it
     */
    public synchronized Registration register(Resource<?, ?> resource) {
        Objects.requireNonNull(resource, "resource");
        Resource<?, ?> existing = byName.get(resource.name());
        if (existing != null) {
            throw new IllegalArgumentException("resource " + resource.name() + " is already registered ("
                    + (Resources.byName(resource.name()) == existing ? "a ControlML resource of section 4"
                            : existing.description()) + "); one name, one resource");
        }
        Map<String, Resource<?, ?>> next = new LinkedHashMap<>(byName);
        next.put(resource.name(), resource);
        byName = Collections.unmodifiableMap(next);
        return new Registration() {
            private boolean closed;

            @Override
            public void close() {
                synchronized (ResourceRegistry.this) {
                    if (!closed) {
                        closed = true;
                        Map<String, Resource<?, ?>> next = new LinkedHashMap<>(byName);
                        next.remove(resource.name(), resource);
                        byName = Collections.unmodifiableMap(next);
                    }
                }
            }
        };
    }

    /** @return the resource of a {@code res} value, or null when none of that name is registered */
    public Resource<?, ?> byName(String name) {
        return byName.get(name);
    }

    /** @return a snapshot of the registered resources: section 4's first, then the others in registration order */
    public Collection<Resource<?, ?>> all() {
        return Collections.unmodifiableList(List.copyOf(byName.values()));
    }
}
