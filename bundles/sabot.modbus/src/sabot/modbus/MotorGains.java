package sabot.modbus;

/**
 * One motor's PID gains in the SACT board's own fixed-point units (docs/SACT-MODBUS.md, files 1/2 records 3–6);
 * each is checked against the register map's bounds before anything is written.
 *
 * @param kp            proportional gain: PWM LSB per 256 error LSB (error LSB = 1/16 count), 0–32767
 * @param ki            integral gain: PWM LSB per 65536 error-LSB-samples, 0–32767
 * @param kd            derivative gain on the error change over 16 samples: PWM LSB per 256 LSB, 0–32767
 * @param integralLimit clamp of the integral term, PWM LSB, 0–491
 */
public record MotorGains(int kp, int ki, int kd, int integralLimit) {
}
