package sabot.system;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resource;
import sabot.controlml.Role;
import sabot.controlml.payload.NoQuery;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.robot.OnboardProcess;

/**
 * One simulated robot as a lab runs it: {@code sabot-sim} on the lab map, the onboard product on the simulator's pty
 * with an account on the private server, and an operator's Smack client with its ControlML manager. Closed in reverse
 * order of start.
 * <p>
 * The rig of {@code ./sabot demo} and {@code ./sabot bench onboard} (product/bin/lib.sh, sabot_rig_start) from the same
 * pieces (the sabot-xmpp script behind {@link PrivateXmppServer}, the sabot-sim binary, the product started as
 * {@code ./sabot onboard} starts it), but in Java: each test sets its own start pose, simulator options and extra
 * configuration, talks to the simulator's control channel and waits on the product's console lines, and the rig comes
 * up without a shell, Python and a JDK probe per test.
 */
final class RobotRig implements AutoCloseable {

    static final String ROBOT = "sabot-01";
    static final String OPERATOR = "operator";
    /**
     * The rig's robots learn their gyro's bias at rest for 1 s, not for the product's 3 s: the tests here drive for
     * seconds, and each rig comes up 2 s sooner. A test whose extra configuration sets
     * {@code localizer.imuSettleTime} itself keeps it (LocalizationTest keeps the product's setting: the estimate is
     * what it measures).
     */
    static final String QUICK_SETTLE = "localizer.imuSettleTime = 1\n";

    final SimProcess sim;
    final OnboardProcess onboard;
    final XMPPTCPConnection operatorConnection;
    final ControlMlManager operator;
    final Jid robot;
    /** The enrolment token the robot started with ({@link #startEnrolling}), else null. */
    String token;

    private RobotRig(SimProcess sim, OnboardProcess onboard, XMPPTCPConnection connection, Jid robot) {
        this.sim = sim;
        this.onboard = onboard;
        this.operatorConnection = connection;
        this.operator = ControlMlManager.getInstanceFor(connection);
        this.operator.setRequestTimeout(Duration.ofSeconds(10));
        this.robot = robot;
    }

    /**
     * Starts the simulator with the robot at {@code start}, the onboard product (waiting until its ControlML session is
     * online) and the operator's client.
     *
     * @param simOptions extra sabot-sim options
     * @param extraConfig extra lines of the onboard configuration
     */
    static RobotRig start(PrivateXmppServer xmpp, Path dir, double[] start, String[] simOptions, String extraConfig)
            throws Exception {
        return start(xmpp, dir, start, start, simOptions, extraConfig);
    }

    /**
     * As {@link #start(PrivateXmppServer, Path, double[], String[], String)}, the robot standing at {@code start} but
     * its onboard product told it stands at {@code believed} (an operator's rough placement).
     */
    static RobotRig start(PrivateXmppServer xmpp, Path dir, double[] start, double[] believed, String[] simOptions,
            String extraConfig) throws Exception {
        return start(xmpp, xmpp.port(), dir, start, believed, simOptions, extraConfig);
    }

    /**
     * As {@link #start(PrivateXmppServer, Path, double[], String[], String)}, the robot reaching the server through
     * {@code robotPort} (a relay in front of it); the operator connects directly.
     */
    static RobotRig start(PrivateXmppServer xmpp, int robotPort, Path dir, double[] start, double[] believed,
            String[] simOptions, String extraConfig) throws Exception {
        xmpp.register(ROBOT, PrivateXmppServer.DOMAIN, "robot-pw");
        // as a lab's administrator: the robot in the robots' group
        xmpp.enrolRobot(JidCreate.bareFrom(ROBOT + "@" + PrivateXmppServer.DOMAIN));
        return start(xmpp, robotPort, dir, start, believed, simOptions, extraConfig, "robot-pw", "127.0.0.1", 1);
    }

    /**
     * As {@link #start(PrivateXmppServer, Path, double[], String[], String)} on a two-node cluster
     * ({@link PrivateXmppServer#ejabberdCluster()}): the robot configured with both nodes (it logs in through node 1),
     * the operator on node 2.
     */
    static RobotRig startOnCluster(PrivateXmppServer xmpp, Path dir, double[] start) throws Exception {
        xmpp.register(ROBOT, PrivateXmppServer.DOMAIN, "robot-pw");
        xmpp.enrolRobot(JidCreate.bareFrom(ROBOT + "@" + PrivateXmppServer.DOMAIN));
        return start(xmpp, xmpp.port(), dir, start, start, new String[0], "", "robot-pw", xmpp.address(1)
                .getHostAddress() + ", " + xmpp.address(2).getHostAddress(), 2);
    }

    /**
     * As {@link #start(PrivateXmppServer, Path, double[], String[], String)}, the robot new to the lab: enrolled with
     * a token in its password file ({@code sabot-xmpp enrol token}), online, and asking for access (not approved).
     *
     * @return the rig; {@link #token} the token the robot started with
     */
    static RobotRig startEnrolling(PrivateXmppServer xmpp, Path dir, double[] start) throws Exception {
        String token = xmpp.enrolToken(JidCreate.bareFrom(ROBOT + "@" + PrivateXmppServer.DOMAIN));
        RobotRig rig = start(xmpp, xmpp.port(), dir, start, start, new String[0], "", token, "127.0.0.1", 1);
        rig.token = token;
        return rig;
    }

    /**
     * @param servers      the robot's {@code controlml.server}
     * @param operatorNode the node the operator logs in through (1 but on a cluster)
     */
    private static RobotRig start(PrivateXmppServer xmpp, int robotPort, Path dir, double[] start, double[] believed,
            String[] simOptions, String extraConfig, String password, String servers, int operatorNode)
            throws Exception {
        // the operator's account a maintainer of the lab's robots
        xmpp.grant(JidCreate.bareFrom(OPERATOR + "@" + PrivateXmppServer.DOMAIN), Role.MAINTAINER);
        Files.createDirectories(dir);
        SimProcess sim = SimProcess.start(dir, start, simOptions);
        OnboardProcess onboard = null;
        try {
            String config = extraConfig.contains("localizer.imuSettleTime") ? extraConfig : QUICK_SETTLE + extraConfig;
            onboard = OnboardProcess.start(dir, new OnboardProcess.Robot(ROBOT, sim.link(1), believed, robotPort,
                    xmpp.caFile()), password, config, servers);
            onboard.await(l -> l.contains("task(s) loaded"), "listing the loaded tasks");
            onboard.await(l -> l.contains("XMPP session online"), "saying the XMPP session is online");
            onboard.await(l -> l.contains("ready to move"), "saying the inertial biases have settled");
            xmpp.register(OPERATOR, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
            XMPPTCPConnection c = xmpp.connect(xmpp.configuration(operatorNode, OPERATOR, PrivateXmppServer.DOMAIN,
                    PrivateXmppServer.DEFAULT_PASSWORD).build());
            return new RobotRig(sim, onboard, c, JidCreate.from(ROBOT + "@" + PrivateXmppServer.DOMAIN + "/onboard"));
        } catch (Exception | AssertionError e) {
            if (onboard != null) {
                onboard.close();
            }
            sim.close();
            throw e;
        }
    }

    /** A get that must succeed. */
    <T> T get(Resource<T, NoQuery> resource) {
        Outcome<T> o = operator.get(robot, resource);
        if (!o.isSuccess()) {
            throw new AssertionError("get " + resource.name() + " failed: " + o.errorOrNull() + "\n"
                    + onboard.output());
        }
        return o.orElseThrow();
    }

    @Override
    public void close() throws IOException {
        if (operatorConnection.isConnected()) {
            operatorConnection.instantShutdown();
        }
        onboard.close();
        sim.close();
    }
}
