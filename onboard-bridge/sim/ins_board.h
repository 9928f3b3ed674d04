/*
 * Virtual inertial board (slave address 2): gyro, accelerometer and magnetometer
 * sampled at the output data rate from the simulated body's true motion.
 *
 * Error model per axis: y = truth + b0 + b(t) + n, quantised to the register LSB.
 *   n   white noise, sigma = density x sqrt(ODR / 2) (bandwidth ~ Nyquist)
 *   b0  turn-on bias, drawn once per seed with sigma = data-sheet tolerance / 3
 *   b(t) bias random walk, sigma grows as rw x sqrt(t)
 * Figures: InvenSense MPU-9250 product specification rev 1.1 (gyro noise 0.01 deg/s/rtHz,
 * initial ZRO +-5 deg/s; accelerometer noise 300 ug/rtHz, zero-g +-60 mg x/y, +-80 mg z;
 * AK8963 magnetometer 0.15 uT/LSB in 16-bit mode). The data sheet gives no bias
 * instability, so the random-walk figures are assumptions typical of consumer MEMS;
 * so is the magnetometer noise. All are in ins_error_model_default().
 */
#ifndef SIM_INS_BOARD_H
#define SIM_INS_BOARD_H

#include "drivetrain.h"
#include "modbus_rtu.h"
#include "rng.h"

typedef struct {
    double gyro_density;      /* rad/s/sqrt(Hz) */
    double gyro_bias0;        /* rad/s, 3-sigma turn-on bias */
    double gyro_bias_rw;      /* rad/s/sqrt(s) */
    double accel_density;     /* m/s^2/sqrt(Hz) */
    double accel_bias0_xy, accel_bias0_z; /* m/s^2, 3-sigma */
    double accel_bias_rw;     /* m/s^2/sqrt(s) */
    double mag_noise;         /* T per sample */
    double mag_hard_iron;     /* T, 3-sigma body-fixed offset (motor magnets) */
    double field_horizontal;  /* T, Earth field */
    double field_down;        /* T */
    double north;             /* rad: map direction of magnetic north */
    double temperature;       /* degC */
} ins_error_model_t;

void ins_error_model_default(ins_error_model_t *m);

typedef struct {
    ins_error_model_t model;
    sim_rng_t rng;
    double gyro_bias[3], accel_bias[3], mag_offset[3];
    uint16_t output_data_rate;
    uint64_t next_sample_us;
    double v_at_last_sample;
    uint16_t sample_counter;
    int16_t regs[11];         /* file 1 image, as the registers read */
    mb_slave_t modbus;
} ins_board_t;

void ins_init(ins_board_t *b, const ins_error_model_t *m, uint64_t seed, uint32_t baud);

/* Samples when the ODR period has elapsed. */
void ins_update(ins_board_t *b, const body_state_t *body, uint64_t now_us);

#endif
