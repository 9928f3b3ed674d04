package sabot.modbus;

/**
 * One motor's PID gains as the SACT board's registers hold them, in its own fixed-point units (docs/SACT-MODBUS.md,
 * files 1/2 records 3–6); each is checked against the register map's bounds before anything is written. What
 * ControlML carries ({@code cm.pid}: a motor index and the three gains, no integral limit) is another type, the
 * robot's motion task converts between the two.
 *
 * @param kp            proportional gain: PWM LSB per 256 error LSB (error LSB = 1/16 count), 0–32767
 * @param ki            integral gain: PWM LSB per 65536 error-LSB-samples, 0–32767
 * @param kd            derivative gain on the error change over 16 samples: PWM LSB per 256 LSB, 0–32767
 * @param integralLimit clamp of the integral term, PWM LSB, 0–491
 */
public record SactGains(int kp, int ki, int kd, int integralLimit) {
}
