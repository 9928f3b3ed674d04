package sabot.control;

import sabot.model.geometry.Twist2D;
import sabot.model.robot.RobotDescription;

/**
 * The differential-drive map between wheel speeds and the unicycle's inputs:
 * u1 = v = r(&omega;R + &omega;L)/2, u2 = &omega; = r(&omega;R &minus; &omega;L)/d
 * (Siciliano et al., <i>Robotics: Modelling, Planning and Control</i>, Springer 2009, &sect;11.2, eq. 11.13).
 *
 * @param wheelRadius r, metres
 * @param trackWidth  d, metres
 */
public record DifferentialDrive(double wheelRadius, double trackWidth) {

    public DifferentialDrive {
        if (!(wheelRadius > 0) || !(trackWidth > 0) || !Double.isFinite(wheelRadius) || !Double.isFinite(trackWidth)) {
            throw new IllegalArgumentException(
                    "wheel radius and track must be finite and > 0, were " + wheelRadius + ", " + trackWidth);
        }
    }

    /** @return the drive of the described robot (nominal geometry) */
    public static DifferentialDrive of(RobotDescription robot) {
        return new DifferentialDrive(robot.wheelRadius(), robot.trackWidth());
    }

    /** @return (v in m/s, &omega; in rad/s) produced by the given wheel speeds */
    public Twist2D toTwist(WheelSpeeds wheels) {
        return new Twist2D(wheelRadius * (wheels.right() + wheels.left()) / 2,
                wheelRadius * (wheels.right() - wheels.left()) / trackWidth);
    }

    /** @return the wheel speeds (rad/s) that produce {@code twist} */
    public WheelSpeeds toWheelSpeeds(Twist2D twist) {
        double half = twist.angular() * trackWidth / 2;
        return new WheelSpeeds((twist.linear() - half) / wheelRadius, (twist.linear() + half) / wheelRadius);
    }
}
