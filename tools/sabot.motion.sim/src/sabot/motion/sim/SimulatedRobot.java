package sabot.motion.sim;

import java.util.Random;

import sabot.control.UnicycleModel;
import sabot.control.WheelSpeeds;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.RobotDescription;

/**
 * Ground truth: a differential-drive robot whose wheels follow the commanded speeds exactly (the SACT board's speed
 * loop is assumed ideal at 50 Hz) but whose ground travel slips.
 * <p>
 * Slip model, per control step and per wheel: travel = r&middot;&Delta;&phi;&middot;(1 + N(0, slipNoise))&middot;(1 &mp; slipBias/2),
 * minus for the left wheel, plus for the right (the systematic asymmetry of uncalibrated wheel radii). The body
 * motion of the step is the unicycle driven by the resulting constant twist, integrated with RK4 sub-steps.
 * Encoders count the wheel's rotation (not its ground travel), quantised to whole counts on a 32-bit register.
 */
public final class SimulatedRobot {

    private static final int SUBSTEPS = 4;

    private final RobotDescription robot;
    private final double slipNoise;
    private final double slipBias;
    private final Random rng;
    private final double countsPerRadian;
    private Pose2D pose;
    private double phiLeft;
    private double phiRight;
    private Twist2D lastTwist = Twist2D.ZERO;
    private double lastAcceleration;

    /**
     * @param robot     geometry and encoder resolution
     * @param start     true start pose
     * @param slipNoise standard deviation of the per-step travel multiplier (0.01 = 1 %)
     * @param slipBias  left/right travel asymmetry (0.002 = 0.2 %)
     * @param seed      seed of the slip generator
     */
    public SimulatedRobot(RobotDescription robot, Pose2D start, double slipNoise, double slipBias, long seed) {
        this.robot = robot;
        this.pose = start;
        this.slipNoise = slipNoise;
        this.slipBias = slipBias;
        this.rng = new Random(seed);
        this.countsPerRadian = robot.countsPerWheelRevolution() / (2 * Math.PI);
    }

    /** Drives for {@code dt} seconds with the wheels at {@code wheels}. */
    public void step(WheelSpeeds wheels, double dt) {
        double dphiL = wheels.left() * dt;
        double dphiR = wheels.right() * dt;
        phiLeft += dphiL;
        phiRight += dphiR;
        double r = robot.wheelRadius();
        double sl = r * dphiL * (1 + slipNoise * rng.nextGaussian()) * (1 - slipBias / 2);
        double sr = r * dphiR * (1 + slipNoise * rng.nextGaussian()) * (1 + slipBias / 2);
        Twist2D twist = new Twist2D((sr + sl) / 2 / dt, (sr - sl) / robot.trackWidth() / dt);
        lastAcceleration = (twist.linear() - lastTwist.linear()) / dt;
        lastTwist = twist;
        pose = UnicycleModel.integrate(pose, twist, dt, SUBSTEPS);
    }

    public Pose2D pose() {
        return pose;
    }

    /** @return the true body twist over the last step */
    public Twist2D lastTwist() {
        return lastTwist;
    }

    /** @return the true mean longitudinal acceleration over the last step, m/s&sup2; */
    public double lastAcceleration() {
        return lastAcceleration;
    }

    /** @return left encoder register: whole counts, wrapping at 32 bits */
    public int leftCount() {
        return (int) (long) Math.floor(phiLeft * countsPerRadian);
    }

    /** @return right encoder register */
    public int rightCount() {
        return (int) (long) Math.floor(phiRight * countsPerRadian);
    }
}
