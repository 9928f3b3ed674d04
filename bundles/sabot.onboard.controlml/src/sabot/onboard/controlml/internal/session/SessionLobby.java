package sabot.onboard.controlml.internal.session;

import java.util.LinkedHashSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;

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
 * that cannot be joined is logged once, with the reason, until a join succeeds; the session goes on without it.
 */
final class SessionLobby {

    /** The session's logger: these are the session's console lines. */
    private static final Logger LOG = LoggerFactory.getLogger(ControlMlSession.class);

    private final XMPPConnection connection;
    private final EntityBareJid room;
    private final FleetLobby lobby;
    private final ExecutorService joiner = Executors.newSingleThreadExecutor(NamedThreads.daemon(
            "sabot-session-lobby"));
    /** True from a successful join until the connection is lost. */
    private volatile boolean joined;
    /** Joiner thread only: the last join failed (its warning logged), so a further failure goes to debug. */
    private boolean failing;
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
        run(this::join);
    }

    /** The connection was lost: the room is left on this side (its occupants are no longer known). */
    void lost() {
        joined = false;
        run(lobby::leave);
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
        if (!connection.isAuthenticated()) {
            return; // lost meanwhile: the next login joins
        }
        try {
            lobby.join();
        } catch (FleetException e) {
            if (!connection.isAuthenticated()) {
                return; // the loss is the session's to report
            }
            if (!failing) {
                LOG.warn("{}; the session goes on without the fleet lobby (tried again at the next login)", e
                        .getMessage());
            } else {
                LOG.debug("{}", e.getMessage());
            }
            failing = true;
            return;
        }
        joined = true;
        if (!everJoined || failing) {
            LOG.info("joined the fleet lobby {}", room);
        } else {
            LOG.debug("joined the fleet lobby {} again", room);
        }
        everJoined = true;
        failing = false;
    }

    private void run(Runnable action) {
        try {
            joiner.execute(action);
        } catch (RejectedExecutionException stopped) {
            // closed: the session stops
        }
    }
}
