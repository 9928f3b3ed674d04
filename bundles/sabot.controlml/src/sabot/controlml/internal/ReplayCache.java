package sabot.controlml.internal;

import java.util.LinkedHashMap;
import java.util.Map;

import org.jxmpp.jid.Jid;

import sabot.controlml.ControlMlElement;
import sabot.controlml.RequestId;

/**
 * The answers to the most recent sets, by requester full JID and request id: a retransmitted set (same requester,
 * same id, e.g. resent after a reconnection) is answered again from here instead of being applied twice. Ids are
 * unique per requester per day, so a bounded least-recently-used map is enough: the protocol promises replay for the
 * {@link #CAPACITY} most recent sets of all requesters together, with no time limit, and not across a restart of the
 * device (docs/CONTROLML.md section 1). The endpoint does not keep {@code busy} refusals. Thread-safe.
 */
public final class ReplayCache {

    /** How many answers a device keeps at least (the protocol's figure, docs/CONTROLML.md section 1). */
    public static final int CAPACITY = 4096;

    private final Map<String, ControlMlElement> answers;

    /** @param capacity how many answers are kept */
    public ReplayCache(int capacity) {
        this.answers = new LinkedHashMap<>(Math.min(capacity, 1024), 0.75f, true) {
            private static final long serialVersionUID = 1L;

            @Override
            protected boolean removeEldestEntry(Map.Entry<String, ControlMlElement> eldest) {
                return size() > capacity;
            }
        };
    }

    private static String key(Jid requester, RequestId id) {
        return requester + " " + id;
    }

    /** @return the answer given to this requester's request, or null */
    public synchronized ControlMlElement get(Jid requester, RequestId id) {
        return answers.get(key(requester, id));
    }

    /** Remembers an answer. */
    public synchronized void put(Jid requester, RequestId id, ControlMlElement answer) {
        if (answer != null) {
            answers.put(key(requester, id), answer);
        }
    }
}
