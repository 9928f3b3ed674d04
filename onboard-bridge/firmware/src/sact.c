#include "sact.h"

#include <string.h>

#define ST_FAULT     MB_SACT_MOTOR_STATUS_FAULT
#define ST_OVERCUR   MB_SACT_MOTOR_STATUS_OVER_CURRENT
#define ST_FOLLOWING MB_SACT_MOTOR_STATUS_FOLLOWING_ERROR
#define ST_BRAKING   MB_SACT_MOTOR_STATUS_BRAKING
#define ST_AT_SET    MB_SACT_MOTOR_STATUS_AT_SETPOINT

/* 355/113 approximates pi to 8.5e-8, enough for limits derived in integer arithmetic
 * (the target has no FPU). */
#define PI_NUM 355u
#define PI_DEN 113u

/* Arithmetic shift right with floor semantics for negative values: >> on a negative
 * signed value is implementation-defined in C11, this is not. */
static inline int32_t asr32(int32_t x, unsigned n)
{
    return x >= 0 ? x >> n : -(int32_t)(((uint32_t)(-(x + 1)) >> n)) - 1;
}

static inline int64_t asr64(int64_t x, unsigned n)
{
    return x >= 0 ? x >> n : -(int64_t)(((uint64_t)(-(x + 1)) >> n)) - 1;
}

/* Modular difference of two positions as a signed value (well-defined in C11). */
static inline int32_t mod_diff(uint32_t a, uint32_t b)
{
    uint32_t d = a - b;
    return d <= INT32_MAX ? (int32_t)d : -(int32_t)(~d) - 1;
}

static inline int16_t sat16(int32_t x)
{
    return x > INT16_MAX ? INT16_MAX : x < INT16_MIN ? INT16_MIN : (int16_t)x;
}

static inline int32_t clamp32(int32_t x, int32_t lo, int32_t hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

static const hal_pin_t brake_pin[HAL_MOTORS] = { HAL_PIN_BRAKE_M1, HAL_PIN_BRAKE_M2 };

/* Puts the loop into the braked state: bridge shorted, command collapsed onto the
 * measured position so releasing the brake does not jump. */
static void hold_braked(sact_board_t *b, unsigned m)
{
    sact_motor_t *M = &b->motor[m];
    M->commanded = M->position;
    M->commanded_frac = 0;
    M->commanded_velocity = 0;
    M->integrator = 0;
    M->error = 0;
    M->error_window[M->window_index] = 0;
    M->saturated = false;
    M->pwm = SACT_PWM_ZERO;
    M->status |= ST_BRAKING;
    hal_pwm_set(b->hal, m, SACT_PWM_ZERO);
    hal_gpio_write(b->hal, brake_pin[m], true);
}

static void latch_fault(sact_board_t *b, unsigned m, uint16_t cause)
{
    b->motor[m].status |= (uint16_t)(ST_FAULT | cause);
    b->motor[m].velocity_setpoint = 0;
    hold_braked(b, m);
    hal_gpio_write(b->hal, HAL_PIN_FAULT_LED, true);
}

void sact_motor_step(sact_board_t *b, unsigned m)
{
    sact_motor_t *M = &b->motor[m];
    const unsigned k = M->window_index;

    /* Measured position: the 16-bit counter moves at most ~5 counts per sample, so the
     * modular difference read as int16 is the true motion whatever the wrap. */
    uint16_t enc = hal_encoder_count(b->hal, m);
    uint16_t raw_delta = (uint16_t)(enc - M->last_encoder);
    int32_t delta = raw_delta < 0x8000u ? (int32_t)raw_delta : (int32_t)raw_delta - 0x10000;
    M->last_encoder = enc;
    M->position += (uint32_t)(delta * (1 << SACT_POS_FRAC_BITS));
    M->position_counts += (uint32_t)delta;
    M->encoder_window_sum += delta - M->encoder_window[k];
    M->encoder_window[k] = (int16_t)delta;

    int32_t ma = asr32(((int32_t)hal_adc_current(b->hal, m) - SACT_ADC_ZERO) * SACT_ADC_MA_NUM,
                       SACT_ADC_MA_SHIFT);
    M->current_sum += ma - M->current_window[M->current_index];
    M->current_window[M->current_index] = (int16_t)ma;
    M->current_index = (uint8_t)((M->current_index + 1u) & ((1u << SACT_CURRENT_AVG_LOG2) - 1u));
    int32_t mean_ma = asr32(M->current_sum, SACT_CURRENT_AVG_LOG2);

    if (mean_ma > M->current_limit_ma || mean_ma < -(int32_t)M->current_limit_ma)
        latch_fault(b, m, ST_OVERCUR);

    if ((M->status & ST_FAULT) || M->brake) {
        hold_braked(b, m);
    } else {
        M->status &= (uint16_t)~ST_BRAKING;

        /* Commanded velocity ramps toward the set-point by the acceleration parameter. */
        int32_t target = (int32_t)M->velocity_setpoint * (1 << (SACT_VCMD_FRAC_BITS - SACT_VSET_FRAC_BITS));
        int32_t v = M->commanded_velocity;
        if (v < target)
            v = (target - v > (int32_t)M->acceleration) ? v + M->acceleration : target;
        else if (v > target)
            v = (v - target > (int32_t)M->acceleration) ? v - M->acceleration : target;
        M->commanded_velocity = v;
        if (v == target)
            M->status |= ST_AT_SET;
        else
            M->status &= (uint16_t)~ST_AT_SET;

        /* Commanded position += v, exactly: whole 24.8 steps plus a 16-bit remainder. */
        M->commanded_frac += (uint32_t)v & 0xFFFFu;
        M->commanded += (uint32_t)asr32(v, 16) + (M->commanded_frac >> 16);
        M->commanded_frac &= 0xFFFFu;

        int32_t err = mod_diff(M->commanded, M->position);     /* 24.8 counts */
        if (err > (int32_t)M->following_error_limit << SACT_POS_FRAC_BITS ||
            err < -((int32_t)M->following_error_limit << SACT_POS_FRAC_BITS)) {
            latch_fault(b, m, ST_FOLLOWING);
        } else {
            int16_t e = sat16(asr32(err, SACT_POS_FRAC_BITS - SACT_ERR_FRAC_BITS));
            int32_t de = (int32_t)e - M->error_window[k];
            M->error_window[k] = e;
            M->error = e;

            /* Conditional integration: no growth while the output is pinned in the
             * error's direction; the clamp bounds the term to integral_limit. */
            bool pushing_further = M->saturated && ((e > 0) == (M->pwm > SACT_PWM_ZERO));
            if (!pushing_further)
                M->integrator = clamp32(M->integrator + e, -M->integrator_max, M->integrator_max);

            int32_t u = asr32((int32_t)M->kp * e, SACT_PD_SHIFT) +
                        asr32((int32_t)M->kd * sat16(de), SACT_PD_SHIFT) +
                        (int32_t)asr64((int64_t)M->ki * M->integrator, SACT_I_SHIFT) +
                        (int32_t)asr64((int64_t)asr32(v, 16) * b->feedforward_gain, 16);
            int32_t duty = SACT_PWM_ZERO + u;
            M->saturated = duty < SACT_PWM_MIN || duty > SACT_PWM_MAX;
            M->pwm = (uint16_t)clamp32(duty, SACT_PWM_MIN, SACT_PWM_MAX);
            hal_gpio_write(b->hal, brake_pin[m], false);
            hal_pwm_set(b->hal, m, M->pwm);
        }
    }
    M->window_index = (uint8_t)((k + 1u) & (SACT_WINDOW - 1u));
}

/* One sample of a step response every `decimation` periods, from the period after the
 * step on: the position measured at the start of this period, relative to the step's. */
static void capture_sample(sact_board_t *b)
{
    sact_capture_t *c = &b->capture;
    if (!c->active)
        return;
    if (c->phase == 0) {
        c->response[c->recorded++] = sat16(mod_diff(b->motor[c->motor].position_counts, c->start));
        if (c->recorded == SACT_CAPTURE_SAMPLES)
            c->active = false;
        c->phase = c->decimation;
    }
    c->phase--;
}

void sact_control_isr(sact_board_t *b)
{
    for (unsigned m = 0; m < HAL_MOTORS; m++)
        sact_motor_step(b, m);
    capture_sample(b);
}

void sact_uart_rx_isr(sact_board_t *b, uint8_t byte)
{
    mb_slave_on_byte(&b->modbus, byte, hal_time_us(b->hal));
}

void sact_poll(sact_board_t *b)
{
    uint32_t now = hal_time_us(b->hal);
    size_t n = mb_slave_poll(&b->modbus, now);
    if (n > 0)
        hal_uart_send(b->hal, b->modbus.tx, n);

    /* Deadman: a master that stops talking must not leave the robot driving. */
    uint32_t timeout_us = (uint32_t)b->config.command_timeout_ms * 1000u;
    if (timeout_us > 0 && !b->deadman_tripped && now - b->last_command_us > timeout_us) {
        uint32_t irq = hal_irq_save(b->hal);
        for (unsigned m = 0; m < HAL_MOTORS; m++)
            b->motor[m].velocity_setpoint = 0;
        hal_irq_restore(b->hal, irq);
        b->deadman_tripped = true;
    }
}

/* ---- limits derived from the robot configuration ------------------------------- */

/* counts per metre = 4 * lines * gear / (2 pi r); with gear in 1/100 and r in 0.1 mm. */
static void derive_limits(sact_board_t *b)
{
    const sact_robot_config_t *c = &b->config;
    if (c->wheel_radius_01mm == 0)
        return;   /* during reset, before the geometry is loaded */
    uint64_t counts_per_rev_x100 = (uint64_t)SACT_QUADRATURE * c->encoder_lines * c->gear_ratio_x100;
    uint64_t circumference_den = 2u * PI_NUM * (uint64_t)c->wheel_radius_01mm; /* x113 x1e4 */

    /* v[8.8 counts/Ts] = speed_mm/1e3 * cpr_x100/100 / (2 pi r_01mm/1e4) * Ts_us/1e6 * 256 */
    uint64_t num = (uint64_t)c->max_speed_mm_s * counts_per_rev_x100 * SACT_TS_US * 256u * PI_DEN;
    uint64_t den = circumference_den * 10000000u;
    uint64_t vmax = (num + den / 2u) / den;
    b->max_velocity_setpoint = vmax > INT16_MAX ? INT16_MAX : (int32_t)vmax;

    /* a[2^-24 counts/Ts^2] = counts/s^2 * Ts^2 * 2^24; counts/s^2 kept in 24.8 on the way. */
    uint64_t cps2_q8 = ((uint64_t)c->max_accel_mm_s2 * counts_per_rev_x100 * PI_DEN << 8) /
                       (circumference_den * 10u);
    /* x Ts_us^2 / 1e12 x 2^24 / 2^8  =  x Ts_us^2 x 16 / 244140625  (1e12 = 2^12 x 5^12) */
    uint64_t amax = cps2_q8 * SACT_TS_US * SACT_TS_US * 16u / 244140625u;
    b->max_acceleration = amax > UINT16_MAX ? UINT16_MAX : (amax < 1u ? 1 : (int32_t)amax);

    /* Feed-forward: at the no-load speed the bridge needs the full supply, u = 512. */
    uint64_t vnl = ((uint64_t)c->no_load_rpm * SACT_QUADRATURE * c->encoder_lines * SACT_TS_US * 256u) /
                   60000000u;
    b->feedforward_gain = vnl ? (int32_t)(((uint64_t)(SACT_PWM_PERIOD / 2u) << 16) / vnl) : 0;

    /* Tighter limits apply at once to what is already commanded. */
    for (unsigned m = 0; m < HAL_MOTORS; m++) {
        sact_motor_t *M = &b->motor[m];
        M->velocity_setpoint = (int16_t)clamp32(M->velocity_setpoint, -b->max_velocity_setpoint,
                                                b->max_velocity_setpoint);
        if (M->acceleration > b->max_acceleration)
            M->acceleration = (uint16_t)b->max_acceleration;
    }
}

static void derive_integrator_max(sact_motor_t *M)
{
    M->integrator_max = M->ki ? (int32_t)(((int64_t)M->integral_limit << SACT_I_SHIFT) / M->ki) : 0;
    M->integrator = clamp32(M->integrator, -M->integrator_max, M->integrator_max);
}

/* ---- register access ------------------------------------------------------------ */

static bool motor_file(uint16_t file, unsigned *m)
{
    if (file == MB_SACT_FILE_MOTOR_LEFT || file == MB_SACT_FILE_MOTOR_RIGHT) {
        *m = file == MB_SACT_FILE_MOTOR_LEFT ? 0u : 1u;
        return true;
    }
    return false;
}

uint16_t sact_read_register(sact_board_t *b, uint16_t file, uint16_t record)
{
    unsigned m;
    if (file == MB_SACT_FILE_DRIVE)
        return (uint16_t)b->motor[record == MB_SACT_DRIVE_VELOCITY_SETPOINT_RIGHT].velocity_setpoint;
    if (file == MB_SACT_FILE_CONFIG) {
        const sact_robot_config_t *c = &b->config;
        switch (record) {
        case MB_SACT_CONFIG_ENCODER_LINES: return c->encoder_lines;
        case MB_SACT_CONFIG_GEAR_RATIO: return c->gear_ratio_x100;
        case MB_SACT_CONFIG_NO_LOAD_SPEED: return c->no_load_rpm;
        case MB_SACT_CONFIG_WHEEL_RADIUS: return c->wheel_radius_01mm;
        case MB_SACT_CONFIG_MAX_SPEED: return c->max_speed_mm_s;
        case MB_SACT_CONFIG_MAX_ACCEL: return c->max_accel_mm_s2;
        case MB_SACT_CONFIG_CONTROL_PERIOD: return SACT_TS_US;
        case MB_SACT_CONFIG_FIRMWARE_VERSION: return SACT_FIRMWARE_VERSION;
        case MB_SACT_CONFIG_COMMAND_TIMEOUT: return c->command_timeout_ms;
        case MB_SACT_CONFIG_COMMAND_SEQUENCE: return b->last_sequence;
        default: return 0;
        }
    }
    if (file == MB_SACT_FILE_STEP_CAPTURE) {
        const sact_capture_t *c = &b->capture;
        switch (record) {
        case MB_SACT_STEP_CAPTURE_MOTOR: return (uint16_t)(c->motor == 0 ? MB_SACT_FILE_MOTOR_LEFT
                                                                         : MB_SACT_FILE_MOTOR_RIGHT);
        case MB_SACT_STEP_CAPTURE_DECIMATION: return c->decimation;
        case MB_SACT_STEP_CAPTURE_RECORDED: return c->recorded;
        default:
            if (record >= MB_SACT_STEP_CAPTURE_RESPONSE &&
                record < MB_SACT_STEP_CAPTURE_RESPONSE + SACT_CAPTURE_SAMPLES)
                return (uint16_t)c->response[record - MB_SACT_STEP_CAPTURE_RESPONSE];
            return 0;   /* step reads 0 */
        }
    }
    if (!motor_file(file, &m))
        return 0;
    const sact_motor_t *M = &b->motor[m];
    int32_t err24_8 = mod_diff(M->commanded, M->position);
    uint32_t commanded_counts = M->position_counts + (uint32_t)asr32(err24_8, SACT_POS_FRAC_BITS);
    switch (record) {
    case MB_SACT_MOTOR_VELOCITY_SETPOINT: return (uint16_t)M->velocity_setpoint;
    case MB_SACT_MOTOR_ACCELERATION: return M->acceleration;
    case MB_SACT_MOTOR_BRAKE: return M->brake;
    case MB_SACT_MOTOR_KP: return M->kp;
    case MB_SACT_MOTOR_KI: return M->ki;
    case MB_SACT_MOTOR_KD: return M->kd;
    case MB_SACT_MOTOR_INTEGRAL_LIMIT: return M->integral_limit;
    case MB_SACT_MOTOR_POSITION_STEP: return 0;
    case MB_SACT_MOTOR_POSITION_ERROR: return (uint16_t)M->error;
    case MB_SACT_MOTOR_POSITION: return (uint16_t)(M->position_counts >> 16);
    case MB_SACT_MOTOR_POSITION + 1: return (uint16_t)M->position_counts;
    case MB_SACT_MOTOR_COMMANDED_POSITION: return (uint16_t)(commanded_counts >> 16);
    case MB_SACT_MOTOR_COMMANDED_POSITION + 1: return (uint16_t)commanded_counts;
    /* window sum = counts per 16 Ts; x16 gives 1/256 count per Ts */
    case MB_SACT_MOTOR_MEASURED_VELOCITY: return (uint16_t)sat16(M->encoder_window_sum * (256 / SACT_WINDOW));
    case MB_SACT_MOTOR_COMMANDED_VELOCITY: return (uint16_t)sat16(asr32(M->commanded_velocity, 16));
    case MB_SACT_MOTOR_PWM_DUTY: return M->pwm;
    case MB_SACT_MOTOR_CURRENT: return (uint16_t)sat16(asr32(M->current_sum, SACT_CURRENT_AVG_LOG2));
    case MB_SACT_MOTOR_STATUS: return M->status;
    case MB_SACT_MOTOR_FOLLOWING_ERROR_LIMIT: return M->following_error_limit;
    case MB_SACT_MOTOR_CURRENT_LIMIT: return M->current_limit_ma;
    default: return 0;
    }
}

static mb_exception_t check_velocity(const sact_board_t *b, unsigned m, uint16_t value)
{
    int32_t v = (int16_t)value;
    if (v > b->max_velocity_setpoint || v < -b->max_velocity_setpoint)
        return MB_ILLEGAL_DATA_VALUE;
    /* A latched fault must be acknowledged before the motor may move again. */
    if (v != 0 && (b->motor[m].status & ST_FAULT))
        return MB_SERVER_DEVICE_FAILURE;
    return MB_OK;
}

static void sact_begin_write(void *board)
{
    sact_board_t *b = board;
    b->duplicate_request = false;
    b->request_writes = 0;
}

static mb_exception_t sact_check_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    sact_board_t *b = board;
    unsigned m;
    if (file == MB_SACT_FILE_CONFIG && record == MB_SACT_CONFIG_COMMAND_SEQUENCE) {
        /* The key names the whole request: only as its first register. A non-zero key equal to
         * the last one applied is a retry of a request already applied (its answer was lost):
         * answered as before, applied never again, whatever the rest of it. */
        if (b->request_writes++ != 0)
            return MB_ILLEGAL_DATA_ADDRESS;
        b->duplicate_request = value != 0 && value == b->last_sequence;
        return MB_OK;
    }
    b->request_writes++;
    if (b->duplicate_request)
        return MB_OK;
    if (file == MB_SACT_FILE_DRIVE)
        return check_velocity(b, record == MB_SACT_DRIVE_VELOCITY_SETPOINT_RIGHT, value);
    if (file == MB_SACT_FILE_STEP_CAPTURE && record == MB_SACT_STEP_CAPTURE_STEP && value != 0) {
        /* A braked or faulted loop holds the commanded position on the measured one: the
         * step would vanish and the recording show nothing. */
        const sact_motor_t *M = &b->motor[b->capture.motor];
        return (M->status & ST_FAULT) || M->brake ? MB_SERVER_DEVICE_FAILURE : MB_OK;
    }
    if (!motor_file(file, &m))
        return MB_OK;   /* config, capture: the static bounds of the map are the rule */
    switch (record) {
    case MB_SACT_MOTOR_VELOCITY_SETPOINT:
        return check_velocity(b, m, value);
    case MB_SACT_MOTOR_ACCELERATION:
        return (int32_t)value > b->max_acceleration ? MB_ILLEGAL_DATA_VALUE : MB_OK;
    case MB_SACT_MOTOR_POSITION_STEP:
        return (value != 0 && (b->motor[m].status & ST_FAULT)) ? MB_SERVER_DEVICE_FAILURE : MB_OK;
    default:
        return MB_OK;
    }
}

static void set_velocity(sact_board_t *b, unsigned m, uint16_t value)
{
    b->motor[m].velocity_setpoint = (int16_t)value;
    b->last_command_us = hal_time_us(b->hal);
    b->deadman_tripped = false;
}

static void sact_apply_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    sact_board_t *b = board;
    unsigned m;
    if (b->duplicate_request) {
        if (file == MB_SACT_FILE_CONFIG && record == MB_SACT_CONFIG_COMMAND_SEQUENCE)
            b->duplicates++;
        return;
    }
    if (file == MB_SACT_FILE_CONFIG && record == MB_SACT_CONFIG_COMMAND_SEQUENCE) {
        if (value != 0)
            b->last_sequence = value;
        return;
    }
    if (file == MB_SACT_FILE_DRIVE) {
        set_velocity(b, record == MB_SACT_DRIVE_VELOCITY_SETPOINT_RIGHT, value);
        return;
    }
    if (file == MB_SACT_FILE_CONFIG) {
        sact_robot_config_t *c = &b->config;
        switch (record) {
        case MB_SACT_CONFIG_ENCODER_LINES: c->encoder_lines = value; break;
        case MB_SACT_CONFIG_GEAR_RATIO: c->gear_ratio_x100 = value; break;
        case MB_SACT_CONFIG_NO_LOAD_SPEED: c->no_load_rpm = value; break;
        case MB_SACT_CONFIG_WHEEL_RADIUS: c->wheel_radius_01mm = value; break;
        case MB_SACT_CONFIG_MAX_SPEED: c->max_speed_mm_s = value; break;
        case MB_SACT_CONFIG_MAX_ACCEL: c->max_accel_mm_s2 = value; break;
        case MB_SACT_CONFIG_COMMAND_TIMEOUT: c->command_timeout_ms = value; break;
        default: return;
        }
        derive_limits(b);
        return;
    }
    if (file == MB_SACT_FILE_STEP_CAPTURE) {
        sact_capture_t *c = &b->capture;
        switch (record) {
        case MB_SACT_STEP_CAPTURE_MOTOR:
            c->motor = value == MB_SACT_FILE_MOTOR_LEFT ? 0u : 1u;
            c->active = false;   /* a recording in progress would mix two motors */
            break;
        case MB_SACT_STEP_CAPTURE_DECIMATION:
            c->decimation = value;
            c->active = false;   /* ... or two sample periods */
            break;
        case MB_SACT_STEP_CAPTURE_STEP:
            if (value == 0)
                break;
            /* Called with the control interrupt masked: the step and the start of the
             * recording land in the same control period. */
            b->motor[c->motor].commanded += (uint32_t)((int32_t)(int16_t)value * (1 << SACT_POS_FRAC_BITS));
            c->start = b->motor[c->motor].position_counts;
            c->recorded = 0;
            c->phase = 0;
            c->active = true;
            break;
        default: break;
        }
        return;
    }
    if (!motor_file(file, &m))
        return;
    sact_motor_t *M = &b->motor[m];
    switch (record) {
    case MB_SACT_MOTOR_VELOCITY_SETPOINT: set_velocity(b, m, value); break;
    case MB_SACT_MOTOR_ACCELERATION: M->acceleration = value; break;
    case MB_SACT_MOTOR_BRAKE: M->brake = value != 0; break;
    case MB_SACT_MOTOR_KP: M->kp = value; break;
    case MB_SACT_MOTOR_KI: M->ki = value; derive_integrator_max(M); break;
    case MB_SACT_MOTOR_KD: M->kd = value; break;
    case MB_SACT_MOTOR_INTEGRAL_LIMIT: M->integral_limit = value; derive_integrator_max(M); break;
    case MB_SACT_MOTOR_POSITION_STEP:
        M->commanded += (uint32_t)((int32_t)(int16_t)value * (1 << SACT_POS_FRAC_BITS));
        break;
    case MB_SACT_MOTOR_STATUS:
        /* The only accepted value is 0 (the map's bounds): acknowledge the fault. */
        M->status &= (uint16_t)~(ST_FAULT | ST_OVERCUR | ST_FOLLOWING);
        if (!(b->motor[0].status & ST_FAULT) && !(b->motor[1].status & ST_FAULT))
            hal_gpio_write(b->hal, HAL_PIN_FAULT_LED, false);
        break;
    case MB_SACT_MOTOR_FOLLOWING_ERROR_LIMIT: M->following_error_limit = value; break;
    case MB_SACT_MOTOR_CURRENT_LIMIT: M->current_limit_ma = value; break;
    default: break;
    }
}

static uint16_t sact_read(void *board, uint16_t file, uint16_t record)
{
    return sact_read_register(board, file, record);
}

static void sact_lock(void *board)
{
    sact_board_t *b = board;
    b->irq_state = hal_irq_save(b->hal);
}

static void sact_unlock(void *board)
{
    sact_board_t *b = board;
    hal_irq_restore(b->hal, b->irq_state);
}

static const mb_board_ops_t sact_ops = {
    .read = sact_read,
    .check_write = sact_check_write,
    .write = sact_apply_write,
    .lock = sact_lock,
    .unlock = sact_unlock,
    .begin_write = sact_begin_write,
};

mb_exception_t sact_write_register(sact_board_t *b, uint16_t file, uint16_t record, uint16_t value)
{
    const mb_record_desc_t *d = mb_map_find(&mb_sact_board, file, record);
    if (d == NULL || !(d->access & MB_ACCESS_W))
        return MB_ILLEGAL_DATA_ADDRESS;
    int32_t v = d->type == MB_T_I16 ? (int16_t)value : (int32_t)value;
    if (v < d->min || v > d->max)
        return MB_ILLEGAL_DATA_VALUE;
    sact_begin_write(b);   /* one register written directly is a request of its own */
    mb_exception_t e = sact_check_write(b, file, record, value);
    if (e == MB_OK)
        sact_apply_write(b, file, record, value);
    return e;
}

void sact_init(sact_board_t *b, hal_port_t *hal, uint32_t baud)
{
    memset(b, 0, sizeof *b);
    b->hal = hal;
    /* Reset values are the map's defaults: config first, since it bounds the rest. */
    static const uint16_t order[] = { MB_SACT_FILE_CONFIG, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_FILE_MOTOR_RIGHT,
                                      MB_SACT_FILE_STEP_CAPTURE };
    for (unsigned i = 0; i < sizeof order / sizeof order[0]; i++) {
        for (unsigned f = 0; f < mb_sact_board.n_files; f++) {
            const mb_file_desc_t *fd = &mb_sact_board.files[f];
            if (fd->file != order[i])
                continue;
            for (unsigned r = 0; r < fd->n_records; r++) {
                const mb_record_desc_t *d = &fd->records[r];
                if ((d->access & MB_ACCESS_W) && d->words == 1)
                    sact_apply_write(b, fd->file, d->record, (uint16_t)d->def);
            }
        }
    }
    for (unsigned m = 0; m < HAL_MOTORS; m++) {
        sact_motor_t *M = &b->motor[m];
        M->last_encoder = hal_encoder_count(hal, m);
        M->pwm = SACT_PWM_ZERO;
        hal_pwm_set(hal, m, SACT_PWM_ZERO);
        hal_gpio_write(hal, brake_pin[m], false);
    }
    b->last_command_us = hal_time_us(hal);
    mb_slave_init(&b->modbus, &mb_sact_board, &sact_ops, b, baud);
}
