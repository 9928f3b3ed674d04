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
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.ControlMlManager;
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
 * their footprints ever touching. The sonar alone would see the other robot only once it is in its cone.
 */
class PeersTest extends RigTest {

    /** The robots' footprint radius, m (the planner's default). */
    static final double RADIUS = 0.25;
    /** The lower corridor (y 0.15–2.2 m), past the partition: robot 1 facing east, robot 2 3.5 m east of it. */
    static final Pose2D WEST = new Pose2D(4.5, 1.0, 0), EAST = new Pose2D(8.0, 1.0, Math.PI);
    /** Goal tolerance, m, judged on the truth. */
    static final double TOLERANCE = 0.15;
    static final String LOBBY = "fleet@conference." + PrivateXmppServer.DOMAIN;

    @Test
    void twoRobotsMeetingHeadOnInTheCorridorPassEachOtherWithoutContact(@TempDir Path dir) throws Exception {
        String[] names = { "sabot-01", "sabot-02" };
        Pose2D[] starts = { WEST, EAST };
        for (String name : names) {
            BareJid jid = JidCreate.bareFrom(name + "@" + PrivateXmppServer.DOMAIN);
            xmpp.register(name, PrivateXmppServer.DOMAIN, "robot-pw");
            xmpp.enrolRobot(jid);
        }
        xmpp.grant(JidCreate.bareFrom(RobotRig.OPERATOR + "@" + PrivateXmppServer.DOMAIN), Role.OPERATOR);
        try (SimProcess sim = SimProcess.start(dir, "--starts", pose(WEST) + "/" + pose(EAST))) {
            List<OnboardProcess> robots = new ArrayList<>();
            try {
                for (int i = 0; i < 2; i++) {
                    Path robotDir = Files.createDirectories(dir.resolve(names[i]));
                    Pose2D s = starts[i];
                    robots.add(OnboardProcess.startWithOwnArea(robotDir, new OnboardProcess.Robot(names[i], sim.link(i
                            + 1), new double[] { s.x(), s.y(), s.theta() }, xmpp.port(), xmpp.caFile()), "robot-pw",
                            RobotRig.QUICK_SETTLE + "tasks = " + OnboardProcess.TASKS + ", peers\ncontrolml.lobby = "
                                    + LOBBY + "\n"));
                }
                for (int i = 0; i < 2; i++) {
                    OnboardProcess p = robots.get(i);
                    String other = names[1 - i] + "@" + PrivateXmppServer.DOMAIN;
                    p.await(l -> l.contains("ready to move"), "saying it is ready to move");
                    p.await(l -> l.contains("following") && l.contains(other), "following " + other);
                }
                xmpp.register(RobotRig.OPERATOR, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
                XMPPTCPConnection c = xmpp.connect(xmpp.configuration(1, RobotRig.OPERATOR, PrivateXmppServer.DOMAIN,
                        PrivateXmppServer.DEFAULT_PASSWORD).build());
                try {
                    ControlMlManager operator = ControlMlManager.getInstanceFor(c);
                    operator.setRequestTimeout(Duration.ofSeconds(10));
                    double startTime = sim.truth().t();
                    for (int i = 0; i < 2; i++) {
                        Pose2D goal = starts[1 - i];
                        Goal g = new Goal(new Pose2D(goal.x(), goal.y(), starts[i].theta()), TOLERANCE, 0.3);
                        assertTrue(operator.set(jid(names[i]), Resources.GOAL, g).isSuccess(), robots.get(i)
                                .output());
                    }
                    for (int i = 0; i < 2; i++) {
                        robots.get(i).await(l -> l.contains("goal reached"), "saying the goal is reached", 120);
                        MissionStatus m = operator.get(jid(names[i]), Resources.MISSION).orElseThrow();
                        assertEquals(MissionState.DONE, m.state(), m + "\n" + robots.get(i).output());
                    }
                    double took = sim.truth().t() - startTime;
                    for (int i = 0; i < 2; i++) {
                        SimProcess.Truth t = sim.truth(i + 1);
                        Pose2D goal = starts[1 - i];
                        assertTrue(t.distanceTo(goal.x(), goal.y()) <= TOLERANCE, names[i] + " at " + t);
                        assertEquals(0, t.contacts(), names[i] + " touched something: " + t);
                    }
                    double closest = closestApproach(sim);
                    System.out.printf(Locale.ROOT, "[figure] two robots swapping places head-on along the lower "
                            + "corridor (3.5 m): closest centres %.3f m (footprints touch at %.2f m), both done after "
                            + "%.1f s%n", closest, 2 * RADIUS, took);
                    assertTrue(closest >= 2 * RADIUS, "the footprints overlapped: centres " + closest + " m apart");
                    // each starts straight at the other (standing on its goal), and stops for it on the way
                    assertTrue(robots.stream().anyMatch(p -> p.output().contains(" on the path ahead: stopping to "
                            + "replan") && p.output().contains("robot sabot-0")), "neither robot stopped for the other");
                } finally {
                    c.instantShutdown();
                }
            } finally {
                for (OnboardProcess p : robots) {
                    p.close();
                }
            }
        }
    }

    private static Jid jid(String name) throws Exception {
        return JidCreate.from(name + "@" + PrivateXmppServer.DOMAIN + "/onboard");
    }

    private static String pose(Pose2D p) {
        return String.format(Locale.ROOT, "%.3f,%.3f,%.4f", p.x(), p.y(), p.theta());
    }

    /** @return the smallest distance between the two robots' true centres at one instant, from the truth file */
    private static double closestApproach(SimProcess sim) throws Exception {
        Map<String, double[]> first = new HashMap<>();
        double closest = Double.POSITIVE_INFINITY;
        for (String[] row : sim.truthRows()) {
            String t = row[0];
            double x = Double.parseDouble(row[2]);
            double y = Double.parseDouble(row[3]);
            double[] other = first.remove(t);
            if (other == null) {
                first.put(t, new double[] { x, y });
            } else {
                closest = Math.min(closest, Math.hypot(x - other[0], y - other[1]));
            }
        }
        return closest;
    }
}
