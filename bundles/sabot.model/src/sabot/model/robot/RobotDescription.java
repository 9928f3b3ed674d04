package sabot.model.robot;

import java.util.ArrayList;
import java.util.List;

/**
 * Physical constants and motion limits of one differential-drive robot.
 * <p>
 * Build it with {@link RobotDescriptions#parse} from the described properties format, or take
 * {@link RobotDescriptions#defaults()}; the canonical constructor validates every value and throws
 * {@link InvalidRobotDescriptionException} listing <em>all</em> problems at once.
 *
 * @param name                       free-form label (for logs and reports)
 * @param wheelRadius                drive wheel radius in metres
 * @param trackWidth                 distance between the two wheel contact points, in metres
 * @param gearRatio                  motor revolutions per wheel revolution (dimensionless, &gt; 1 for a reduction)
 * @param encoderLines               encoder lines per <em>motor</em> revolution (counts are lines &times; quadrature)
 * @param encoderQuadrature          edges counted per line: 4 for full quadrature decoding
 * @param motorNoLoadSpeedRpm        motor no-load speed at the supply voltage, in revolutions per minute
 * @param maxLinearSpeed             v_max, the largest forward/backward speed the controller may command, m/s
 * @param maxLinearAcceleration      a_max, largest linear acceleration, and largest acceleration of either wheel's
 *                                   rim speed, in m/s&sup2;
 * @param maxAngularSpeed            largest yaw rate the controller may command, rad/s
 * @param maxLateralAcceleration     largest centripetal acceleration v&middot;&omega; a trajectory may ask for, m/s&sup2;
 * @param controlPeriod              period of the control loop in seconds (SACT wheel-speed set-point period)
 */
public record RobotDescription(String name, double wheelRadius, double trackWidth, double gearRatio, int encoderLines,
        int encoderQuadrature, double motorNoLoadSpeedRpm, double maxLinearSpeed, double maxLinearAcceleration,
        double maxAngularSpeed, double maxLateralAcceleration, double controlPeriod) {

    public RobotDescription {
        List<String> problems = new ArrayList<>();
        if (name == null || name.isBlank()) {
            problems.add("name must not be blank");
        }
        positive(problems, "wheel radius (m)", wheelRadius);
        positive(problems, "track width (m)", trackWidth);
        positive(problems, "gear ratio", gearRatio);
        if (encoderLines <= 0) {
            problems.add("encoder lines must be > 0, was " + encoderLines);
        }
        if (encoderQuadrature != 1 && encoderQuadrature != 2 && encoderQuadrature != 4) {
            problems.add("encoder quadrature must be 1, 2 or 4, was " + encoderQuadrature);
        }
        positive(problems, "motor no-load speed (rpm)", motorNoLoadSpeedRpm);
        positive(problems, "v_max (m/s)", maxLinearSpeed);
        positive(problems, "a_max (m/s^2)", maxLinearAcceleration);
        positive(problems, "max angular speed (rad/s)", maxAngularSpeed);
        positive(problems, "max lateral acceleration (m/s^2)", maxLateralAcceleration);
        positive(problems, "control period (s)", controlPeriod);
        if (problems.isEmpty()) {
            double wheelLimit = motorNoLoadSpeedRpm * 2 * Math.PI / 60.0 / gearRatio * wheelRadius;
            if (maxLinearSpeed > wheelLimit) {
                problems.add(String.format(
                        "v_max %.3f m/s exceeds what the wheels can reach at the motor's no-load speed (%.3f m/s)",
                        maxLinearSpeed, wheelLimit));
            }
            if (trackWidth <= 2 * wheelRadius * 0.5) {
                problems.add("track width " + trackWidth + " m is implausibly small for wheel radius " + wheelRadius);
            }
        }
        if (!problems.isEmpty()) {
            throw new InvalidRobotDescriptionException(problems);
        }
    }

    private static void positive(List<String> problems, String what, double value) {
        if (!Double.isFinite(value) || value <= 0) {
            problems.add(what + " must be a finite number > 0, was " + value);
        }
    }

    /** @return encoder counts per wheel revolution: lines &times; quadrature &times; gear ratio */
    public double countsPerWheelRevolution() {
        return (double) encoderLines * encoderQuadrature * gearRatio;
    }

    /** @return distance a wheel rim travels per encoder count, in metres */
    public double metresPerCount() {
        return 2 * Math.PI * wheelRadius / countsPerWheelRevolution();
    }

    /** @return the wheel's angular speed at the motor's no-load speed, in rad/s (the hard wheel-speed limit) */
    public double maxWheelAngularSpeed() {
        return motorNoLoadSpeedRpm * 2 * Math.PI / 60.0 / gearRatio;
    }

    /** @return the wheel rim speed at the motor's no-load speed, in m/s */
    public double maxWheelRimSpeed() {
        return maxWheelAngularSpeed() * wheelRadius;
    }

    /** @return a copy with another wheel radius, track and name (used by calibration reports), validated */
    public RobotDescription withGeometry(String newName, double newWheelRadius, double newTrackWidth) {
        return new RobotDescription(newName, newWheelRadius, newTrackWidth, gearRatio, encoderLines, encoderQuadrature,
                motorNoLoadSpeedRpm, maxLinearSpeed, maxLinearAcceleration, maxAngularSpeed, maxLateralAcceleration,
                controlPeriod);
    }
}
