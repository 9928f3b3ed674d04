package sabot.controlml.tests;

import java.time.Clock;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

import sabot.controlml.GetHandler;
import sabot.controlml.Outcome;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.SetHandler;
import sabot.controlml.internal.Endpoint;
import sabot.controlml.payload.AccessRole;

/**
 * A device whose state is one value per resource: gets return it, sets replace it and are recorded. Registers
 * handlers for every resource of the catalogue on an {@link Endpoint} or a manager.
 */
final class RecordingDevice {

    final Map<String, Object> state = new ConcurrentHashMap<>(Samples.VALUES.entrySet().stream().collect(
            java.util.stream.Collectors.toMap(e -> e.getKey().name(), Map.Entry::getValue)));
    final List<String> applied = Collections.synchronizedList(new ArrayList<>());

    interface Registry {
        <T, Q> void onGet(Resource<T, Q> resource, GetHandler<T, Q> handler);

        <T> void onSet(Resource<T, ?> resource, SetHandler<T> handler);
    }

    static Endpoint endpoint(Clock clock, RecordingDevice device) {
        Endpoint e = new Endpoint(clock, new sabot.controlml.ResourceRegistry());
        device.registerOn(new Registry() {
            @Override
            public <T, Q> void onGet(Resource<T, Q> resource, GetHandler<T, Q> handler) {
                e.onGet(resource, handler);
            }

            @Override
            public <T> void onSet(Resource<T, ?> resource, SetHandler<T> handler) {
                e.onSet(resource, handler);
            }
        });
        return e;
    }

    /** Registers the handlers on a connection's manager. */
    void registerOn(sabot.controlml.ControlMlManager manager) {
        registerOn(new Registry() {
            @Override
            public <T, Q> void onGet(Resource<T, Q> resource, GetHandler<T, Q> handler) {
                manager.onGet(resource, handler);
            }

            @Override
            public <T> void onSet(Resource<T, ?> resource, SetHandler<T> handler) {
                manager.onSet(resource, handler);
            }
        });
    }

    void registerOn(Registry registry) {
        for (Resource<?, ?> r : Resources.all()) {
            register(registry, r);
        }
    }

    @SuppressWarnings("unchecked")
    private <T, Q> void register(Registry registry, Resource<T, Q> r) {
        if (r == Resources.ROLE) {
            // what every device answers (ControlMlManager's own handler): the requester's role, not a stored value
            registry.onGet(r, (request, query) -> Outcome.success((T) new AccessRole(request.role())));
            return;
        }
        if (r.isGettable()) {
            registry.onGet(r, (request, query) -> Outcome.success((T) state.get(r.name())));
        }
        if (r.isSettable()) {
            registry.onSet(r, (request, value) -> {
                state.put(r.name(), value);
                applied.add(r.name() + " " + request.id());
                return Outcome.done();
            });
        }
    }
}
