package sabot.workbench.controlml.internal;

import java.util.HashMap;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Set;
import java.util.function.Supplier;

import org.jivesoftware.smack.packet.Presence;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.stringprep.XmppStringprepException;

import sabot.controlml.Resource;
import sabot.controlml.TelemetryWatcher;

/**
 * The telemetry the views look at (docs/CONTROLML.md section 6, "Leases"): each view says which robots it shows and
 * at what rate ({@link sabot.workbench.fleet.FleetState#watch}); each robot is leased the highest rate any view asks
 * of it, through the current session's {@link TelemetryWatcher}, and asked again when it comes online (a robot that
 * restarted has forgotten its leases). Robots no view shows are let go: they fall back to their base rate.
 */
final class FleetWatch {

    /** The lease asked of robots; renewed at half of what each grants. */
    static final double LEASE_S = 30;

    private final Supplier<FleetSession> current;
    /** What each view asked: Hz by robot. */
    private final Map<String, Map<String, Double>> viewers = new HashMap<>(); // guarded by this
    /** Robot (bare JID) → the full JID its lease was sent to. */
    private final Map<String, Jid> leasedAt = new HashMap<>(); // guarded by this
    private FleetSession session; // guarded by this: the session the watcher belongs to
    private TelemetryWatcher watcher; // guarded by this

    FleetWatch(Supplier<FleetSession> current) {
        this.current = current;
    }

    /** A view's robots and rates (Hz by robot), replacing what it said before (empty: none). */
    synchronized void watch(String viewer, Map<String, Double> rates) {
        Map<String, Double> before = viewers.get(viewer);
        Set<String> touched = new HashSet<>(rates.keySet());
        if (before != null) {
            touched.addAll(before.keySet());
        }
        Map<String, Double> was = new HashMap<>();
        touched.forEach(r -> was.put(r, wanted(r)));
        if (rates.isEmpty()) {
            viewers.remove(viewer);
        } else {
            viewers.put(viewer, Map.copyOf(rates));
        }
        for (String robot : touched) {
            if (wanted(robot) != was.get(robot)) { // a pan that moves nobody's rate costs no lookup
                apply(robot);
            }
        }
    }

    /** A robot came online (on session {@code s}): its lease is sent again, to its present full JID. */
    synchronized void online(FleetSession s, String robot) {
        if (current.get() == s) {
            apply(robot);
            if (watcher != null && leasedAt.get(robot) != null) {
                watcher.renew(leasedAt.get(robot));
            }
        }
    }

    /** The session ended: its watcher's leases end with the robots' lease times. */
    synchronized void sessionClosed() {
        if (watcher != null) {
            watcher.close();
        }
        watcher = null;
        session = null;
        leasedAt.clear();
    }

    private double wanted(String robot) {
        double hz = 0;
        for (Map<String, Double> asked : viewers.values()) {
            hz = Math.max(hz, asked.getOrDefault(robot, 0.0));
        }
        return hz;
    }

    /** Brings one robot's lease to what the views ask. */
    private void apply(String robot) {
        FleetSession s = current.get();
        if (s == null) {
            return;
        }
        if (s != session) {
            sessionClosed();
            session = s;
            watcher = s.manager().telemetry().watcher(LEASE_S);
        }
        double hz = wanted(robot);
        Jid now = fullJid(s, robot);
        Jid before = leasedAt.get(robot);
        if (before != null && (hz == 0 || !before.equals(now))) {
            watcher.watch(before, Map.of()); // let go (a robot at another full JID has a new session)
            leasedAt.remove(robot);
        }
        if (hz > 0 && now != null) {
            Map<Resource<?, ?>, Double> rates = new LinkedHashMap<>();
            for (Resource<?, ?> r : FleetTelemetry.TELEMETRY) {
                rates.put(r, hz); // the robot caps each at its own rate
            }
            watcher.watch(now, rates);
            leasedAt.put(robot, now);
        }
    }

    /** @return the robot's available full JID, or null while it is offline */
    private static Jid fullJid(FleetSession s, String robot) {
        try {
            Presence p = s.roster().getPresence(JidCreate.entityBareFrom(robot));
            return p.isAvailable() && p.getFrom().hasResource() ? p.getFrom() : null;
        } catch (XmppStringprepException e) {
            return null;
        }
    }
}
