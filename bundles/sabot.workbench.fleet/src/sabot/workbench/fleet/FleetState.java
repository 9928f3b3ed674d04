package sabot.workbench.fleet;

import java.time.Duration;
import java.util.List;
import java.util.Optional;
import java.util.Map;
import java.util.concurrent.CompletableFuture;

import org.osgi.annotation.versioning.ProviderType;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.payload.FileQuery;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.TelemetryRates;
import sabot.fleet.ArchivedCommand;
import sabot.fleet.CommandHistory;
import sabot.fleet.ServerFigures;
import sabot.fleet.ServerStatistics;
import sabot.model.geometry.Twist2D;

/**
 * The fleet the workbench follows, and the way to command it: the subject of thesis rule 1, published as an OSGi
 * service by the faceless ControlML plug-in ({@code sabot.workbench.controlml}) and observed by the core's views and
 * every other plug-in.
 * <p>
 * Robots are named by their bare JID ({@code sabot-01@sabot.local}). Reads return immutable snapshots at once.
 * Commands never block: they return a future completed on the plug-in's own threads (never the UI thread) with the
 * robot's answer, or exceptionally with a {@link FleetCommandException} carrying the ControlML condition and the
 * robot's text (also for "not connected", "unknown robot", "robot offline" and timeouts). Units are SI: metres,
 * radians, seconds, m/s, rad/s.
 */
@ProviderType
public interface FleetState {

    /** @return the state of the workbench's XMPP connection; never null */
    ConnectionStatus connection();

    /** @return the robots followed, sorted by JID; empty when none (or not connected yet) */
    List<RobotState> robots();

    /** @return the robot with this bare JID, if followed */
    Optional<RobotState> robot(String jid);

    /**
     * The robots asking for access (docs/SECURITY.md, "Enrolment"): enrolled by the lab and not yet approved, the
     * accounts its server holds in the quarantine group. They are not in {@link #robots()} and obey nobody; their
     * {@link #identity} can be fetched. A default for providers written before this method: none.
     *
     * @return their bare JIDs, sorted; empty when none
     */
    default List<String> accessRequests() {
        return List.of();
    }

    /**
     * Registers an observer. It first receives the present state (the connection, then every robot), then every
     * change, on the fleet's notification thread. Adding the same listener twice has no effect.
     */
    void addListener(FleetListener listener);

    /** Unregisters an observer; nothing happens when it was not registered. */
    void removeListener(FleetListener listener);

    /**
     * Connects anew with the account stored in the preferences (after the operator changed it). The plug-in also
     * does so by itself when the account's preferences change; this covers a new password alone.
     */
    void reconnect();

    /**
     * Sends the robot to a goal ({@code cm.goal} set): the robot plans, presence goes busy, and the mission's progress
     * comes with its telemetry. The planned path is fetched once the robot has taken the goal.
     *
     * @param robot bare JID
     * @param goal  target pose in the map frame (m, m, rad) and its tolerances (m, rad)
     * @return completes when the robot took the goal (not when it arrives)
     */
    CompletableFuture<Void> goTo(String robot, Goal goal);

    /**
     * Sends the robot to a goal when it comes online: a stored command (docs/CONTROLML.md section 5) that waits at the
     * server while the robot is offline, listed in {@link #queuedCommands()} until the robot answers. The robot judges
     * it by its age when it arrives (older than its stale limit, default 5 s: refused as {@code stale-command}). A
     * default for providers written before this method: it refuses with
     * {@link sabot.controlml.ControlMlCondition#UNSUPPORTED_OPERATION}.
     *
     * @param robot bare JID
     * @return completes when the robot took the goal, exceptionally with its refusal; may take as long as the robot
     *         stays offline
     */
    default CompletableFuture<Void> goToWhenOnline(String robot, Goal goal) {
        return CompletableFuture.failedFuture(new FleetCommandException(
                sabot.controlml.ControlMlCondition.UNSUPPORTED_OPERATION,
                "this workbench's ControlML plug-in cannot queue commands for offline robots"));
    }

    /**
     * Sends the robot a mission of several targets ({@code cm.mission} set with targets, docs/CONTROLML.md section 4):
     * with {@code queue} false it starts now, replacing the mission that runs (the robot's queue stays); with
     * {@code queue} true it waits in the robot's queue after the missions there (and starts at once when the robot is
     * idle). Its progress comes with the robot's telemetry: {@link RobotState#mission()} carries the targets with their
     * states, the index of the current one and the number of missions queued. The planned path of each leg is fetched
     * as the robot starts it. A default for providers written before this method: it refuses with
     * {@link ControlMlCondition#UNSUPPORTED_OPERATION}.
     *
     * @param robot   bare JID
     * @param targets the targets in order, 1..{@link sabot.controlml.payload.MissionStatus#MAX_TARGETS} (poses in the
     *                map frame, m, m, rad; tolerances m, rad; each its action and wait in s); their states are not
     *                sent (a new mission's targets are pending)
     * @param queue   true: after the robot's other missions; false: now
     * @return completes when the robot took the mission (not when it is done); exceptionally with a
     *         {@link FleetCommandException}: the robot's refusal, {@code invalid-value} for no targets or too many,
     *         not connected, robot offline, timeout
     * @since 0.6
     */
    default CompletableFuture<Void> startMission(String robot, List<MissionTarget> targets, boolean queue) {
        return CompletableFuture.failedFuture(new FleetCommandException(ControlMlCondition.UNSUPPORTED_OPERATION,
                "this workbench's ControlML plug-in cannot send missions of several targets"));
    }

    /** @return the commands waiting for offline robots ({@link #goToWhenOnline}), oldest first; empty when none */
    default List<QueuedCommand> queuedCommands() {
        return List.of();
    }

    /**
     * Stops the robot: aborts its mission when one is running or paused ({@code cm.mission} set aborted), otherwise
     * commands a zero twist ({@code cm.velocity}).
     *
     * @param robot bare JID
     */
    CompletableFuture<Void> stop(String robot);

    /**
     * Drives the robot by hand ({@code cm.velocity} set, within {@code cm.limits}; the robot stops by itself when
     * twists stop arriving).
     *
     * @param robot bare JID
     * @param twist linear m/s, angular rad/s
     */
    CompletableFuture<Void> drive(String robot, Twist2D twist);

    /**
     * Fetches the robot's map ({@code cm.map}; a map too large for one payload comes from the robot's remote files
     * instead, see the implementation). The result is cached per robot until the connection changes.
     *
     * @param robot bare JID
     */
    CompletableFuture<GridMap> map(String robot);

    /**
     * Reads any resource of a robot ({@code get}).
     *
     * @param robot    bare JID
     * @param resource e.g. {@code Resources.PID}, or a plug-in's own resource
     * @return the robot's value
     */
    <T> CompletableFuture<T> get(String robot, Resource<T, NoQuery> resource);

    /**
     * Reads a robot's latest commands from the server's archive of ControlML stanzas (docs/ARCHIVE.md): who sent
     * each, and its answer.
     *
     * @param max at most this many, 1..{@link CommandHistory#MAX}
     * @return completes with the commands, newest first; exceptionally with a {@link FleetCommandException} saying
     *         why not (the server keeps no archive, the account has no role of the lab, not connected)
     */
    default CompletableFuture<List<ArchivedCommand>> commandHistory(String robot, int max) {
        return CompletableFuture.failedFuture(new FleetCommandException(ControlMlCondition.UNSUPPORTED_OPERATION,
                "no command history here"));
    }

    /** Reads a resource that takes a query ({@code get} with a payload, e.g. {@code cm.fs.list}). */
    <T, Q> CompletableFuture<T> get(String robot, Resource<T, Q> resource, Q query);

    /**
     * Writes any resource of a robot ({@code set}).
     *
     * @return the robot's read-back when its answer carries one, else null
     */
    <T> CompletableFuture<T> set(String robot, Resource<T, ?> resource, T value);

    /**
     * Reads a whole file of the robot's remote files ({@code cm.fs.read}, docs/CONTROLML.md section 4) chunk after
     * chunk, each asked for once the previous one has been handed to {@code sink}: no thread waits between chunks, and
     * a sink that throws stops the download.
     *
     * @param robot      bare JID
     * @param path       the file's path in the robot's remote files
     * @param chunkBytes bytes asked for per chunk; 0: the robot's default
     * @param sink       takes the chunks in order, on the fleet's threads
     * @return completes after the last chunk was taken; exceptionally with a {@link FleetCommandException} (the
     *         robot's refusal; DEVICE_FAULT for a chunk out of place or an empty one before the end) or with what
     *         the sink threw
     */
    default CompletableFuture<Void> download(String robot, String path, int chunkBytes, FileChunkSink sink) {
        CompletableFuture<Void> done = new CompletableFuture<>();
        downloadFrom(robot, path, 0, chunkBytes, sink, done);
        return done;
    }

    private void downloadFrom(String robot, String path, long offset, int chunkBytes, FileChunkSink sink,
            CompletableFuture<Void> done) {
        get(robot, Resources.FS_READ, new FileQuery(path, offset, chunkBytes)).whenComplete((chunk, e) -> {
            try {
                if (e != null) {
                    throw e;
                }
                if (chunk.offset() != offset) {
                    throw new FleetCommandException(ControlMlCondition.DEVICE_FAULT, robot + " answered offset "
                            + chunk.offset() + " of " + path + " for " + offset);
                }
                if (!chunk.last() && chunk.data().length == 0) {
                    throw new FleetCommandException(ControlMlCondition.DEVICE_FAULT, robot + " sent an empty chunk of "
                            + path + " at " + offset);
                }
                sink.accept(chunk);
                if (chunk.last()) {
                    done.complete(null);
                } else {
                    downloadFrom(robot, path, offset + chunk.data().length, chunkBytes, sink, done);
                }
            } catch (Throwable failure) {
                done.completeExceptionally(failure instanceof java.util.concurrent.CompletionException c
                        && c.getCause() != null ? c.getCause() : failure);
            }
        });
    }

    /** The rate a view that draws robots asks of those it shows: as fast as each publishes (a robot caps a lease). */
    double SHOWN_HZ = TelemetryRates.MAX_RATE_HZ;
    /** The rate a view that lists robots asks: once a second. */
    double LISTED_HZ = 1;

    /**
     * Says which robots a view shows and how often it needs their telemetry (docs/CONTROLML.md section 6, "Leases"):
     * the fleet leases each robot's telemetry at the highest rate any view asks of it, renews the leases while the
     * views ask, and lets them end when none does (the robot falls back to its base rate). Views call it through
     * {@link FleetBinding#watch}. A default for providers written before this method: nothing (robots publish at the
     * rate they are configured for).
     *
     * @param viewer a name unique to the view; a later call replaces what it asked
     * @param rates  Hz &gt; 0 by robot (bare JID); empty: the view shows none
     */
    default void watch(String viewer, Map<String, Double> rates) {
    }

    /**
     * The workbench's own count of its traffic with a robot since the connection was made: stanzas and bytes in and
     * out, requests, errors by condition, round trips, telemetry ({@link TrafficStatistics}, docs/STATISTICS.md). A
     * default for providers written before this method: none.
     *
     * @param robot bare JID
     * @return a snapshot, computed when called (any thread); empty for a robot not followed or before a connection
     */
    default Optional<TrafficStatistics> traffic(String robot) {
        return Optional.empty();
    }

    /**
     * Reads a robot's figures from the server's archive of ControlML stanzas (docs/STATISTICS.md): what every client
     * sent it and what it sent, as the server archived it, over the last {@code window}.
     *
     * @param window whole seconds, 1 s..{@link ServerStatistics#MAX_WINDOW}
     * @return completes with the figures; exceptionally with a {@link FleetCommandException} saying why not (the
     *         server keeps no archive, the account has no role of the lab, not connected). A default for providers
     *         written before this method: UNSUPPORTED_OPERATION.
     */
    default CompletableFuture<ServerFigures> serverStatistics(String robot, Duration window) {
        return CompletableFuture.failedFuture(new FleetCommandException(ControlMlCondition.UNSUPPORTED_OPERATION,
                "no server statistics here"));
    }

    /**
     * Fetches the robot's identity from its vCard (JID, nickname, URL, location, UUID, the QR-code inventory image).
     * A default for providers written before this method: it refuses with
     * {@link sabot.controlml.ControlMlCondition#UNSUPPORTED_OPERATION}.
     *
     * @param robot bare JID
     * @return the robot's identity; exceptionally a {@link FleetCommandException} (no vCard, not connected, timeout)
     */
    default CompletableFuture<RobotIdentity> identity(String robot) {
        return CompletableFuture.failedFuture(new FleetCommandException(
                sabot.controlml.ControlMlCondition.UNSUPPORTED_OPERATION,
                "this workbench's ControlML plug-in cannot fetch vCards yet"));
    }
}
