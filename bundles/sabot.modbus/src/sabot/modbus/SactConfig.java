package sabot.modbus;

import java.time.Duration;

/**
 * The SACT board's configuration file (file 3), in SI units.
 *
 * @param encoderLines     encoder lines per motor revolution (counts per revolution = 4 × lines)
 * @param gearRatio        gearhead reduction (motor turns per wheel turn)
 * @param noLoadSpeed      motor no-load speed at supply voltage, rad/s
 * @param wheelRadius      wheel radius, m
 * @param maxSpeed         wheel surface speed limit, m/s
 * @param maxAccel         wheel surface acceleration limit, m/s²
 * @param controlPeriod    the board's control period Ts
 * @param firmwareVersion  major &lt;&lt; 8 | minor
 * @param commandTimeout   the board's own deadman: no velocity write for this long zeroes both set-points
 *                         ({@link Duration#ZERO} = off)
 * @param quadrature       encoder counts per line (4)
 */
public record SactConfig(int encoderLines, double gearRatio, double noLoadSpeed, double wheelRadius, double maxSpeed,
        double maxAccel, Duration controlPeriod, int firmwareVersion, Duration commandTimeout, int quadrature) {

    /** @return encoder counts per radian of wheel rotation: lines × quadrature × gear ratio / 2π */
    public double countsPerWheelRadian() {
        return encoderLines * (double) quadrature * gearRatio / (2 * Math.PI);
    }

    /** @return encoder counts per metre of wheel travel */
    public double countsPerMetre() {
        return countsPerWheelRadian() / wheelRadius;
    }

    /** @return the wheel speed limit in rad/s (maxSpeed / wheelRadius) */
    public double maxWheelRate() {
        return maxSpeed / wheelRadius;
    }
}
