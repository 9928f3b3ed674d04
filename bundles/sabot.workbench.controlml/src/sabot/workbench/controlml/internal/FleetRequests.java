package sabot.workbench.controlml.internal;

import java.time.Instant;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.RejectedExecutionException;
import java.util.function.Supplier;

import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smackx.vcardtemp.VCardManager;
import org.jivesoftware.smackx.vcardtemp.packet.VCard;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.stringprep.XmppStringprepException;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlManager;
import sabot.controlml.ControlMlType;
import sabot.controlml.Outcome;
import sabot.controlml.PendingCommand;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.NoQuery;
import sabot.fleet.ArchivedCommand;
import sabot.fleet.CommandHistory;
import sabot.fleet.ServerFigures;
import sabot.fleet.ServerStatistics;
import sabot.identity.DeviceProfile;
import sabot.identity.DeviceVCards;
import sabot.identity.IdentityResult;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.QueuedCommand;
import sabot.workbench.fleet.RobotIdentity;

/**
 * The operator's requests to robots, on a small pool of threads (each waits for its robot's answer): sent to the
 * robot's available full JID through the current session, every failure a {@link FleetCommandException} with the
 * robot's condition and text, or why the robot could not be asked.
 */
final class FleetRequests {

    private final ExecutorService pool;
    private final ExecutorService sender;
    private final Supplier<FleetSession> session;
    private final RobotRegistry registry;
    private final FleetTraffic traffic;
    /** The commands waiting for offline robots, by id: completed with the robot's answer. */
    private final Map<String, CompletableFuture<Void>> queued = new ConcurrentHashMap<>();

    /** A request through the robot's ControlML manager. */
    @FunctionalInterface
    interface Call<T> {
        Outcome<T> on(ControlMlManager manager, Jid robot);
    }

    /**
     * @param pool   the requests' threads (each waits for its robot's answer)
     * @param sender the thread that sends stored commands, which wait for no answer ({@link #goToWhenOnline})
     */
    FleetRequests(ExecutorService pool, ExecutorService sender, Supplier<FleetSession> session,
            RobotRegistry registry, FleetTraffic traffic) {
        this.traffic = traffic;
        this.pool = pool;
        this.sender = sender;
        this.session = session;
        this.registry = registry;
    }

    <T> CompletableFuture<T> get(String robot, Resource<T, NoQuery> resource) {
        return request(robot, (m, jid) -> m.get(jid, resource));
    }

    <T, Q> CompletableFuture<T> get(String robot, Resource<T, Q> resource, Q query) {
        return request(robot, (m, jid) -> m.get(jid, resource, query));
    }

    <T> CompletableFuture<T> set(String robot, Resource<T, ?> resource, T value) {
        return request(robot, (m, jid) -> m.set(jid, resource, value));
    }

    /**
     * A goal for a robot that is offline, as a stored command (docs/CONTROLML.md section 5): listed in the registry's
     * queued commands until the robot's answer comes, on this session or, when this one is lost meanwhile, on a later
     * one ({@link #unsolicited}).
     */
    CompletableFuture<Void> goToWhenOnline(String robot, Goal goal) {
        return on(sender, () -> {
            FleetSession s = sessionFor(robot);
            EntityBareJid device;
            try {
                device = JidCreate.entityBareFrom(robot);
            } catch (XmppStringprepException e) {
                throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, "'" + robot + "' is not a JID");
            }
            PendingCommand<Goal> sent = s.manager().sendCommandMessage(device, Resources.GOAL, goal);
            QueuedCommand q = new QueuedCommand(robot, sent.id().toString(), String.format(Locale.ROOT,
                    "go to (%.2f, %.2f, %.2f rad)", goal.pose().x(), goal.pose().y(), goal.pose().theta()), Instant
                            .now());
            CompletableFuture<Void> done = new CompletableFuture<>();
            queued.put(q.id(), done);
            registry.addQueued(q);
            sent.outcome().whenComplete((o, failure) -> answered(q.id(), o != null ? o : Outcome.failure(
                    ControlMlCondition.UNSPECIFIED, String.valueOf(failure))));
            return done;
        }).thenCompose(f -> f);
    }

    /** An answer that came to a later session than the one that sent the command (stored for the workbench). */
    void unsolicited(ControlMlElement answer) {
        if (answer.id() != null && queued.containsKey(answer.id().toString())) {
            answered(answer.id().toString(), answer.type() == ControlMlType.ERROR ? Outcome.failure(answer.failure())
                    : Outcome.done());
        }
    }

    private void answered(String id, Outcome<?> outcome) {
        CompletableFuture<Void> done = queued.remove(id);
        if (done == null) {
            return; // answered already (the answer came twice: to the old session and a new one)
        }
        registry.removeQueued(id);
        if (outcome instanceof Outcome.Failure<?> failure) {
            ControlMlError e = failure.error();
            done.completeExceptionally(new FleetCommandException(e.cmCondition() != null ? e.cmCondition()
                    : ControlMlCondition.UNSPECIFIED, e.text() == null ? String.valueOf(e.condition()) : e.text()));
        } else {
            done.complete(null);
        }
    }

    /** The robot's vCard, parsed with {@code sabot.identity}'s device profile. */
    CompletableFuture<RobotIdentity> identity(String robot) {
        return onPool(() -> fetchIdentity(robot));
    }

    /** Runs a request on the pool. */
    private <T> CompletableFuture<T> request(String robot, Call<T> call) {
        return onPool(() -> callNow(robot, call));
    }

    /**
     * Runs work on the pool; the future fails with a {@link FleetCommandException} (the robot's condition and text, or
     * why it could not be asked), any other failure as UNSPECIFIED.
     */
    <T> CompletableFuture<T> onPool(Supplier<T> work) {
        return on(pool, work);
    }

    /** As {@link #onPool}, on {@code threads}. */
    private static <T> CompletableFuture<T> on(ExecutorService threads, Supplier<T> work) {
        CompletableFuture<T> f = new CompletableFuture<>();
        try {
            threads.execute(() -> {
                try {
                    f.complete(work.get());
                } catch (FleetCommandException e) {
                    f.completeExceptionally(e);
                } catch (RuntimeException e) {
                    f.completeExceptionally(new FleetCommandException(ControlMlCondition.UNSPECIFIED, e.toString()));
                }
            });
        } catch (RejectedExecutionException stopped) {
            f.completeExceptionally(new FleetCommandException(ControlMlCondition.NOT_CONNECTED,
                    "the ControlML plug-in has stopped"));
        }
        return f;
    }

    /** @return the session to ask {@code robot} through; throws why it cannot be asked (NOT_CONNECTED) */
    private FleetSession sessionFor(String robot) {
        return sessionFor(robot, false);
    }

    /** @param orAsking also for a robot asking for access (its vCard: who asks) */
    private FleetSession sessionFor(String robot, boolean orAsking) {
        FleetSession s = session.get();
        if (s == null || !s.connection().isAuthenticated()) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, "the workbench is not connected ("
                    + registry.status().summary() + ")");
        }
        if (registry.robot(robot) == null && !(orAsking && registry.asking(robot))) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, robot
                    + " is not a robot of this workbench's fleet");
        }
        return s;
    }

    /**
     * Sends a request to the robot's available full JID and waits for the answer (calling thread).
     *
     * @throws FleetCommandException with the robot's condition and text, or why it could not be asked
     */
    private <T> T callNow(String robot, Call<T> call) {
        FleetSession s = sessionFor(robot);
        Presence p;
        try {
            p = s.roster().getPresence(JidCreate.entityBareFrom(robot));
        } catch (XmppStringprepException e) {
            throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, "'" + robot + "' is not a JID: " + e
                    .getMessage());
        }
        if (!p.isAvailable()) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, robot + " is offline");
        }
        long sent = traffic.requesting(robot);
        Outcome<T> o = call.on(s.manager(), p.getFrom());
        traffic.answered(robot, sent, o instanceof Outcome.Failure<T> f ? f.error().cmCondition() : null);
        if (o instanceof Outcome.Failure<T> failure) {
            ControlMlError e = failure.error();
            throw new FleetCommandException(e.cmCondition() != null ? e.cmCondition() : ControlMlCondition.UNSPECIFIED,
                    e.text() == null ? String.valueOf(e.condition()) : e.text());
        }
        return o.orElseThrow();
    }

    /** Pool thread: loads and parses the vCard; each failure as a {@link FleetCommandException} for the operator. */
    /** The robot's latest commands from the server's archive ({@link CommandHistory}), on the pool. */
    CompletableFuture<List<ArchivedCommand>> commandHistory(String robot, int max) {
        return onPool(() -> fetchHistory(robot, max));
    }

    private List<ArchivedCommand> fetchHistory(String robot, int max) {
        return fromArchive(robot, "command history", s -> CommandHistory.read(s.connection(), JidCreate.entityBareFrom(
                robot), max));
    }

    /** The robot's figures from the server's archive ({@link ServerStatistics}), on the pool. */
    CompletableFuture<ServerFigures> serverStatistics(String robot, java.time.Duration window) {
        return onPool(() -> fromArchive(robot, "server statistics", s -> ServerStatistics.read(s.connection(),
                JidCreate.entityBareFrom(robot), window)));
    }

    /** A read of the server's archive (urn:sabot:archive:1) through the session. */
    @FunctionalInterface
    private interface ArchiveRead<T> {
        T on(FleetSession s) throws XmppStringprepException, XMPPException.XMPPErrorException, SmackException,
                InterruptedException;
    }

    /** Runs a read of the archive; each failure as a {@link FleetCommandException} for the operator. */
    private <T> T fromArchive(String robot, String what, ArchiveRead<T> read) {
        FleetSession s = sessionFor(robot, false);
        try {
            return read.on(s);
        } catch (XmppStringprepException e) {
            throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, "'" + robot + "' is not a JID: " + e
                    .getMessage());
        } catch (XMPPException.XMPPErrorException e) {
            StanzaError error = e.getStanzaError();
            if (error.getCondition() == StanzaError.Condition.service_unavailable
                    || error.getCondition() == StanzaError.Condition.feature_not_implemented) {
                throw new FleetCommandException(ControlMlCondition.UNSUPPORTED_OPERATION, NO_ARCHIVE);
            }
            ControlMlCondition c = error.getCondition() == StanzaError.Condition.forbidden
                    ? ControlMlCondition.ACCESS_DENIED : ControlMlCondition.UNSPECIFIED;
            throw new FleetCommandException(c, "the server: " + (error.getDescriptiveText() != null ? error
                    .getDescriptiveText() : error.getCondition().toString()));
        } catch (SmackException.NoResponseException e) {
            throw new FleetCommandException(ControlMlCondition.TIMEOUT, "no " + what + " of " + robot + " within "
                    + s.connection().getReplyTimeout() + " ms");
        } catch (SmackException e) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, what + " of " + robot + ": " + e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new FleetCommandException(ControlMlCondition.UNSPECIFIED, what + " of " + robot + ": interrupted");
        } catch (IllegalArgumentException e) {
            throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, what + " of " + robot + ": " + e
                    .getMessage());
        }
    }

    /** What a server without the archive of ControlML stanzas makes of a history request. */
    static final String NO_ARCHIVE = "this server keeps no archive of commands (an ejabberd started with --archive sql "
            + "does: docs/ARCHIVE.md)";

    private RobotIdentity fetchIdentity(String robot) {
        FleetSession s = sessionFor(robot, true);
        VCard card;
        try {
            card = VCardManager.getInstanceFor(s.connection()).loadVCard(JidCreate.entityBareFrom(robot));
        } catch (XmppStringprepException e) {
            throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, "'" + robot + "' is not a JID: " + e
                    .getMessage());
        } catch (XMPPException.XMPPErrorException e) {
            StanzaError.Condition c = e.getStanzaError().getCondition();
            if (c == StanzaError.Condition.item_not_found || c == StanzaError.Condition.service_unavailable) {
                throw new FleetCommandException(ControlMlCondition.UNKNOWN_RESOURCE, robot + " has no vCard");
            }
            throw new FleetCommandException(ControlMlCondition.UNSPECIFIED, "vCard of " + robot + ": " + c);
        } catch (SmackException.NoResponseException e) {
            throw new FleetCommandException(ControlMlCondition.TIMEOUT, "no vCard of " + robot + " within "
                    + s.connection().getReplyTimeout() + " ms");
        } catch (SmackException e) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, "vCard of " + robot + ": " + e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new FleetCommandException(ControlMlCondition.UNSPECIFIED, "vCard of " + robot + ": interrupted");
        }
        IdentityResult<DeviceProfile> parsed = DeviceVCards.profileOf(card);
        if (parsed instanceof IdentityResult.Err<DeviceProfile> e) {
            ControlMlCondition c = e.problem() == IdentityResult.Problem.NO_VCARD ? ControlMlCondition.UNKNOWN_RESOURCE
                    : ControlMlCondition.INVALID_VALUE;
            throw new FleetCommandException(c, robot + "'s vCard: " + e.text());
        }
        DeviceProfile p = parsed.orElseThrow();
        return new RobotIdentity(p.jid(), p.nickname(), p.portal() == null ? null : p.portal().toString(), p
                .latitude(), p.longitude(), p.uid(), p.category(), p.manufacturer(), p.model(), card.getAvatar());
    }
}
