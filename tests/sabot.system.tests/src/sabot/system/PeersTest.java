package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.OnboardProcess;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * Robots that see each other over ControlML (docs/USER-GUIDE.md, "Other robots"), on the simulator with two real
 * onboard products, judged on the simulator's truth: two robots sent to swap their places along the lab's lower
 * corridor meet head-on; each follows the other (the peers task) and plans round it, so that both arrive without
 * their footprints ever touching. The sonar alone would see the other robot only once it is in its cone. Two robots
 * sent through one door at once take turns by the passage rule (docs/PASSAGES.md).
 */
class PeersTest extends RigTest {

    /** The robots' footprint radius, m (the planner's default). */
    static final double RADIUS = 0.25;
    /** The lower corridor (y 0.15–2.2 m), past the partition: robot 1 facing east, robot 2 3.5 m east of it. */
    static final Pose2D WEST = new Pose2D(4.5, 1.0, 0), EAST = new Pose2D(8.0, 1.0, Math.PI);
    /** Goal tolerance, m, judged on the truth. */
    static final double TOLERANCE = 0.15;
    static final String LOBBY = "fleet@conference." + PrivateXmppServer.DOMAIN;

    /** Two robots on the simulator, each with the peers task, and an operator; closed in reverse order. */
    private final class Pair implements AutoCloseable {
        final String[] names = { "sabot-01", "sabot-02" };
        final Pose2D[] starts;
        final SimProcess sim;
        final List<OnboardProcess> robots = new ArrayList<>();
        XMPPTCPConnection connection;
        ControlMlManager operator;

        Pair(Path dir, Path map, Pose2D first, Pose2D second) throws Exception {
            starts = new Pose2D[] { first, second };
            for (String name : names) {
                xmpp.register(name, PrivateXmppServer.DOMAIN, "robot-pw");
                xmpp.enrolRobot(JidCreate.bareFrom(name + "@" + PrivateXmppServer.DOMAIN));
            }
            xmpp.grant(JidCreate.bareFrom(RobotRig.OPERATOR + "@" + PrivateXmppServer.DOMAIN), Role.OPERATOR);
            sim = SimProcess.startOnMap(dir, map, "--starts", pose(first) + "/" + pose(second));
            try {
                for (int i = 0; i < 2; i++) {
                    Path robotDir = Files.createDirectories(dir.resolve(names[i]));
                    Pose2D s = starts[i];
                    robots.add(OnboardProcess.startWithOwnArea(robotDir, new OnboardProcess.Robot(names[i], sim.link(i
                            + 1), new double[] { s.x(), s.y(), s.theta() }, xmpp.port(), xmpp.caFile()), "robot-pw",
                            RobotRig.QUICK_SETTLE + "tasks = " + OnboardProcess.TASKS + ", peers\ncontrolml.lobby = "
                                    + LOBBY + "\nplanner.map = " + map + "\n"));
                }
                for (int i = 0; i < 2; i++) {
                    OnboardProcess p = robots.get(i);
                    String other = names[1 - i] + "@" + PrivateXmppServer.DOMAIN;
                    p.await(l -> l.contains("ready to move"), "saying it is ready to move");
                    p.await(l -> l.contains("following") && l.contains(other), "following " + other);
                }
                xmpp.register(RobotRig.OPERATOR, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
                connection = xmpp.connect(xmpp.configuration(1, RobotRig.OPERATOR, PrivateXmppServer.DOMAIN,
                        PrivateXmppServer.DEFAULT_PASSWORD).build());
                operator = ControlMlManager.getInstanceFor(connection);
                operator.setRequestTimeout(Duration.ofSeconds(10));
            } catch (Exception | AssertionError e) {
                close();
                throw e;
            }
        }

        /** Sends robot i to {@code goal}. */
        void send(int i, Pose2D goal) throws Exception {
            Outcome<Goal> o = operator.set(jid(names[i]), Resources.GOAL, new Goal(goal, TOLERANCE, 0.3));
            assertTrue(o.isSuccess(), names[i] + " refused the goal: " + o.errorOrNull() + "\n" + robots.get(i)
                    .output());
        }

        /** Waits until robot i says its goal is reached, and checks it is done there on the truth, untouched. */
        void awaitDone(int i, Pose2D goal) throws Exception {
            robots.get(i).await(l -> l.contains("goal reached"), "saying the goal is reached", 120);
            MissionStatus m = operator.get(jid(names[i]), Resources.MISSION).orElseThrow();
            assertEquals(MissionState.DONE, m.state(), m + "\n" + robots.get(i).output());
            SimProcess.Truth t = sim.truth(i + 1);
            assertTrue(t.distanceTo(goal.x(), goal.y()) <= TOLERANCE, names[i] + " at " + t);
            assertEquals(0, t.contacts(), names[i] + " touched something: " + t);
        }

        @Override
        public void close() throws java.io.IOException {
            if (connection != null) {
                connection.instantShutdown();
            }
            for (OnboardProcess p : robots) {
                p.close();
            }
            sim.close();
        }
    }

    @Test
    void twoRobotsMeetingHeadOnInTheCorridorPassEachOtherWithoutContact(@TempDir Path dir) throws Exception {
        try (Pair p = new Pair(dir, SimProcess.labMap(), WEST, EAST)) {
            double startTime = p.sim.truth().t();
            p.send(0, new Pose2D(EAST.x(), EAST.y(), WEST.theta()));
            p.send(1, new Pose2D(WEST.x(), WEST.y(), EAST.theta()));
            p.awaitDone(0, EAST);
            p.awaitDone(1, WEST);
            double took = p.sim.truth().t() - startTime;
            double closest = closestApproach(p.sim, null);
            System.out.printf(Locale.ROOT, "[figure] two robots swapping places head-on along the lower corridor "
                    + "(3.5 m): closest centres %.3f m (footprints touch at %.2f m), both done after %.1f s%n",
                    closest, 2 * RADIUS, took);
            assertTrue(closest >= 2 * RADIUS, "the footprints overlapped: centres " + closest + " m apart");
            // each starts straight at the other (standing on its goal), and stops for it on the way
            assertTrue(p.robots.stream().anyMatch(r -> r.output().contains(" on the path ahead: stopping to replan")
                    && r.output().contains("robot sabot-0")), "neither robot stopped for the other");
        }
    }

    /**
     * The two-rooms map's door (1 m: one robot at a time, docs/PASSAGES.md): two robots sent through it from opposite
     * rooms at once take turns: exactly one yields short of the door, both arrive, their footprints are never both in
     * the door and never touch, judged on the simulator's truth.
     */
    @Test
    void twoRobotsSentThroughOneDoorAtOnceTakeTurns(@TempDir Path dir) throws Exception {
        Path map = PrivateXmppServer.repositoryRoot().resolve("onboard-bridge/maps/two-rooms.yaml");
        // both start on the door's axis (y 2.2), so that each approaches it straight; past it, each turns away
        Pose2D westStart = new Pose2D(2.0, 2.2, 0), eastStart = new Pose2D(6.6, 2.2, Math.PI);
        Pose2D westGoal = new Pose2D(6.6, 3.3, 0), eastGoal = new Pose2D(2.0, 1.1, Math.PI);
        try (Pair p = new Pair(dir, map, westStart, eastStart)) {
            double startTime = p.sim.truth().t();
            p.send(0, westGoal);
            p.send(1, eastGoal);
            p.awaitDone(0, westGoal);
            p.awaitDone(1, eastGoal);
            double took = p.sim.truth().t() - startTime;
            double[] door = { 4.2, 1.7, 4.4, 2.7 };
            double closest = closestApproach(p.sim, door);
            long yielded = p.robots.stream().filter(r -> r.output().contains("yielding at passage 1")).count();
            System.out.printf(Locale.ROOT, "[figure] two robots through the two-rooms door at once: %d yielded, "
                    + "closest centres %.3f m, both done after %.1f s%n", yielded, closest, took);
            assertEquals(1, yielded, "exactly one robot yields");
            assertTrue(closest >= 2 * RADIUS, "the footprints overlapped: centres " + closest + " m apart");
        }
    }

    private static Jid jid(String name) throws Exception {
        return JidCreate.from(name + "@" + PrivateXmppServer.DOMAIN + "/onboard");
    }

    private static String pose(Pose2D p) {
        return String.format(Locale.ROOT, "%.3f,%.3f,%.4f", p.x(), p.y(), p.theta());
    }

    /**
     * @param door a passage's rectangle [minX, minY, maxX, maxY] that must never hold both footprints at once, or null
     * @return the smallest distance between the two robots' true centres at one instant, from the truth file
     */
    private static double closestApproach(SimProcess sim, double[] door) throws Exception {
        Map<String, double[]> first = new HashMap<>();
        double closest = Double.POSITIVE_INFINITY;
        for (String[] row : sim.truthRows()) {
            String t = row[0];
            double x = Double.parseDouble(row[2]);
            double y = Double.parseDouble(row[3]);
            double[] other = first.remove(t);
            if (other == null) {
                first.put(t, new double[] { x, y });
                continue;
            }
            closest = Math.min(closest, Math.hypot(x - other[0], y - other[1]));
            if (door != null) {
                assertTrue(!inside(door, x, y) || !inside(door, other[0], other[1]), "both footprints in the door at "
                        + "t = " + t + " s: (" + x + ", " + y + ") and (" + other[0] + ", " + other[1] + ")");
            }
        }
        return closest;
    }

    private static boolean inside(double[] r, double x, double y) {
        double dx = Math.max(0, Math.max(r[0] - x, x - r[2]));
        double dy = Math.max(0, Math.max(r[1] - y, y - r[3]));
        return Math.hypot(dx, dy) < RADIUS;
    }
}
