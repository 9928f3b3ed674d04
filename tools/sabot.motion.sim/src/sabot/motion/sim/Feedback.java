package sabot.motion.sim;

import java.util.Locale;

/** Which pose the controller is fed. */
public enum Feedback {
    /** The simulator's true pose. */
    TRUTH,
    /** Encoder odometry alone. */
    ODOMETRY,
    /** The EKF fusing odometry, gyro, accelerometer and magnetometer. */
    EKF;

    public String cliName() {
        return name().toLowerCase(Locale.ROOT);
    }

    public static Feedback parse(String s) {
        for (Feedback v : values()) {
            if (v.cliName().equals(s)) {
                return v;
            }
        }
        throw new IllegalArgumentException("unknown feedback '" + s + "' (expected truth|odometry|ekf)");
    }
}
