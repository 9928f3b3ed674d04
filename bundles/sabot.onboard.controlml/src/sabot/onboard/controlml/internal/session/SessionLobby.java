package sabot.onboard.controlml.internal.session;

import java.time.Duration;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.XMPPConnection;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.fleet.FleetException;
import sabot.fleet.FleetLobby;
import sabot.onboard.task.NamedThreads;

/**
 * The fleet lobby of the robot's session (roster rule 11, {@code controlml.lobby}): joined after each login, so that
 * workbenches and the other robots find this one online there, and its occupants offered to the session's users
 * ({@link sabot.onboard.session.RobotSession#lobbyMembers}).
 * <p>
 * The room is joined and left on the thread {@code sabot-session-lobby}: a room that is slow to answer never delays
 * the session's presence or its reconnection. A loss leaves the room at once on this side (nothing is sent: Smack's
 * room would otherwise still count itself joined after a login that did not resume the stream, and refuse the next
 * join); the next login joins again, which a resumed stream, still in the room, takes as a plain re-entry. A lobby
 * that cannot be joined is logged once, with the reason, and tried again while the session is online, after
 * {@link #RETRY_MIN} doubling up to {@link #RETRY_MAX}; the session goes on without it meanwhile. (Devices that come
 * online together race to make the room after a server restart: those that find it made and not yet configured are
 * refused with {@code item-not-found} until it is.)
 */
final class SessionLobby {

    /** The session's logger: these are the session's console lines. */
    private static final Logger LOG = LoggerFactory.getLogger(ControlMlSession.class);
    /** First and longest delay before a join that failed is tried again. */
    static final Duration RETRY_MIN = Duration.ofSeconds(1), RETRY_MAX = Duration.ofSeconds(60);

    private final XMPPConnection connection;
    private final EntityBareJid room;
    private final FleetLobby lobby;
    private final ScheduledExecutorService joiner = Executors.newSingleThreadScheduledExecutor(NamedThreads.daemon(
            "sabot-session-lobby"));
    /** True from a successful join until the connection is lost. */
    private volatile boolean joined;
    /** Joiner thread only: joins failed since the last login or success (the first one's warning logged). */
    private int failures;
    /** Joiner thread only: the next attempt after a failed join, or null. */
    private ScheduledFuture<?> retry;
    /** Joiner thread only: the lobby has been joined once (later joins, after reconnections, go to debug). */
    private boolean everJoined;

    SessionLobby(XMPPConnection connection, EntityBareJid room) {
        this.connection = connection;
        this.room = room;
        this.lobby = new FleetLobby(connection, room);
    }

    /** @return the room's bare JID */
    EntityBareJid room() {
        return room;
    }

    /** The session logged in (a new stream or a resumed one): the room is joined on the lobby's thread. */
    void loggedIn() {
        run(() -> {
            cancelRetry();
            join();
        });
    }

    /** The connection was lost: the room is left on this side (its occupants are no longer known). */
    void lost() {
        joined = false;
        run(() -> {
            cancelRetry();
            lobby.leave();
        });
    }

    /**
     * @return the real JIDs (full) of the room's other occupants, as the room shows them; empty while the room is not
     *         joined
     */
    List<String> members() {
        if (!joined) {
            return List.of();
        }
        Set<String> out = new LinkedHashSet<>();
        for (Jid member : lobby.members()) {
            out.add(member.toString());
        }
        return List.copyOf(out);
    }

    /** Stops the lobby's thread (the session's unavailable presence takes it out of the room). */
    void close() {
        joined = false;
        joiner.shutdownNow();
    }

    private void join() {
        retry = null;
        if (!connection.isAuthenticated()) {
            return; // lost meanwhile: the next login joins
        }
        try {
            lobby.join();
        } catch (FleetException e) {
            if (!connection.isAuthenticated()) {
                return; // the loss is the session's to report
            }
            failures++;
            Duration delay = ControlMlSession.backoff(failures, RETRY_MIN, RETRY_MAX);
            if (failures == 1) {
                LOG.warn("{}; the session goes on without the fleet lobby and tries again (in {} s, then less and less"
                        + " often, every {} s at most)", e.getMessage(), delay.toMillis() / 1000.0, RETRY_MAX
                                .toSeconds());
            } else {
                LOG.debug("{} (attempt {}; again in {} s)", e.getMessage(), failures, delay.toMillis() / 1000.0);
            }
            try {
                retry = joiner.schedule(this::join, delay.toNanos(), TimeUnit.NANOSECONDS);
            } catch (RejectedExecutionException stopped) {
                // closed: the session stops
            }
            return;
        }
        joined = true;
        if (!everJoined || failures > 0) {
            LOG.info("joined the fleet lobby {}{}", room, failures > 0 ? " after " + (failures + 1) + " attempts" : "");
        } else {
            LOG.debug("joined the fleet lobby {} again", room);
        }
        everJoined = true;
        failures = 0;
    }

    private void cancelRetry() {
        if (retry != null) {
            retry.cancel(false);
            retry = null;
        }
        failures = 0;
    }

    private void run(Runnable action) {
        try {
            joiner.execute(action);
        } catch (RejectedExecutionException stopped) {
            // closed: the session stops
        }
    }
}
