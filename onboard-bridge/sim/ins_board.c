#include "ins_board.h"

#include <math.h>
#include <string.h>

#define DEG (M_PI / 180.0)
#define G0 9.80665

void ins_error_model_default(ins_error_model_t *m)
{
    m->gyro_density = 0.01 * DEG;
    m->gyro_bias0 = 5.0 * DEG;
    m->gyro_bias_rw = 4e-5;               /* assumption: ~80 deg/h drift after 100 s */
    m->accel_density = 300e-6 * G0;
    m->accel_bias0_xy = 0.060 * G0;
    m->accel_bias0_z = 0.080 * G0;
    m->accel_bias_rw = 1e-4;              /* assumption */
    m->mag_noise = 0.3e-6;                /* assumption: 2 LSB of the 16-bit mode */
    m->mag_hard_iron = 3e-6;              /* assumption: motors 10 cm away */
    m->field_horizontal = 20e-6;          /* mid-latitude Europe, WMM order of magnitude */
    m->field_down = 44e-6;
    m->north = M_PI / 2.0;                /* map +y points north */
    m->temperature = 25.0;
}

/* Register scales from the map (MPU-9250 at +-250 deg/s, +-2 g; AK8963 16-bit). */
static const double GYRO_LSB = 1.0 / 131.0 * DEG;
static const double ACCEL_LSB = G0 / 16384.0;
static const double MAG_LSB = 0.15e-6;

static int16_t quantise(double value, double lsb)
{
    double q = nearbyint(value / lsb);
    return q > 32767.0 ? 32767 : q < -32768.0 ? -32768 : (int16_t)q;
}

static uint16_t ins_read(void *board, uint16_t file, uint16_t record)
{
    ins_board_t *b = board;
    if (file == MB_INS_FILE_SAMPLE)
        return (uint16_t)b->regs[record];
    return record == MB_INS_CONFIG_WHO_AM_I ? MB_INS_CONFIG_WHO_AM_I_DEFAULT : b->output_data_rate;
}

static mb_exception_t ins_check_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    (void)board, (void)file, (void)record, (void)value;
    return MB_OK;   /* the static bounds of the map are the rule */
}

static void ins_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    ins_board_t *b = board;
    if (file == MB_INS_FILE_CONFIG && record == MB_INS_CONFIG_OUTPUT_DATA_RATE)
        b->output_data_rate = value;
}

static const mb_board_ops_t ins_ops = { .read = ins_read, .check_write = ins_check_write, .write = ins_write };

void ins_init(ins_board_t *b, const ins_error_model_t *m, uint64_t seed, uint32_t baud)
{
    memset(b, 0, sizeof *b);
    b->model = *m;
    rng_seed(&b->rng, seed);
    for (int k = 0; k < 3; k++) {
        b->gyro_bias[k] = m->gyro_bias0 / 3.0 * rng_gauss(&b->rng);
        b->accel_bias[k] = (k == 2 ? m->accel_bias0_z : m->accel_bias0_xy) / 3.0 * rng_gauss(&b->rng);
        b->mag_offset[k] = m->mag_hard_iron / 3.0 * rng_gauss(&b->rng);
    }
    b->output_data_rate = MB_INS_CONFIG_OUTPUT_DATA_RATE_DEFAULT;
    b->regs[MB_INS_SAMPLE_ACCEL_Z] = MB_INS_SAMPLE_ACCEL_Z_DEFAULT;
    mb_slave_init(&b->modbus, &mb_ins_board, &ins_ops, b, baud);
}

void ins_update(ins_board_t *b, const body_state_t *body, uint64_t now_us)
{
    if (now_us < b->next_sample_us)
        return;
    const ins_error_model_t *m = &b->model;
    double period = 1.0 / b->output_data_rate;
    b->next_sample_us = now_us + (uint64_t)(1e6 * period);
    double root_bw = sqrt(b->output_data_rate / 2.0), root_dt = sqrt(period);

    /* Specific force in the body frame (x forward, y left, z up) on level ground:
     * tangential from the speed change over the sample, centripetal v w, and gravity. */
    double ax = (body->v - b->v_at_last_sample) / period;
    b->v_at_last_sample = body->v;
    double truth_accel[3] = { ax, body->v * body->omega, G0 };
    double truth_gyro[3] = { 0.0, 0.0, body->omega };
    double heading_to_north = m->north - body->theta;
    double truth_mag[3] = { m->field_horizontal * cos(heading_to_north),
                            m->field_horizontal * sin(heading_to_north), -m->field_down };

    b->regs[MB_INS_SAMPLE_SAMPLE_COUNTER] = (int16_t)++b->sample_counter;
    for (int k = 0; k < 3; k++) {
        b->gyro_bias[k] += m->gyro_bias_rw * root_dt * rng_gauss(&b->rng);
        b->accel_bias[k] += m->accel_bias_rw * root_dt * rng_gauss(&b->rng);
        double gyro = truth_gyro[k] + b->gyro_bias[k] + m->gyro_density * root_bw * rng_gauss(&b->rng);
        double accel = truth_accel[k] + b->accel_bias[k] + m->accel_density * root_bw * rng_gauss(&b->rng);
        double mag = truth_mag[k] + b->mag_offset[k] + m->mag_noise * rng_gauss(&b->rng);
        b->regs[MB_INS_SAMPLE_GYRO_X + k] = quantise(gyro, GYRO_LSB);
        b->regs[MB_INS_SAMPLE_ACCEL_X + k] = quantise(accel, ACCEL_LSB);
        b->regs[MB_INS_SAMPLE_MAG_X + k] = quantise(mag, MAG_LSB);
    }
    /* MPU-9250: TEMP_degC = (raw - RoomTemp_Offset) / 333.87 + 21 */
    b->regs[MB_INS_SAMPLE_TEMPERATURE] = quantise(m->temperature - 21.0 + 0.05 * rng_gauss(&b->rng), 1.0 / 333.87);
}
