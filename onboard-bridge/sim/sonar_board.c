#include "sonar_board.h"

#include <math.h>
#include <string.h>

#define DEG (M_PI / 180.0)

void sonar_model_default(sonar_model_t *m)
{
    m->min_range = 0.02;
    m->max_range = 4.0;
    m->beam_half_angle = 15.0 * DEG;
    m->noise_floor = 0.003;
    m->noise_fraction = 0.005;
    m->rays = 7;
    static const double mount_deg[SONAR_SENSORS] = { 40.0, 0.0, -40.0 };
    for (int k = 0; k < SONAR_SENSORS; k++) {
        m->mount[k].mount_angle = mount_deg[k] * DEG;
        m->mount[k].mount_x = 0.20 * cos(mount_deg[k] * DEG);
        m->mount[k].mount_y = 0.20 * sin(mount_deg[k] * DEG);
    }
}

static uint16_t sonar_read(void *board, uint16_t file, uint16_t record)
{
    sonar_board_t *b = board;
    if (file == MB_SONAR_FILE_LATEST)
        return b->latest[record];
    if (file == MB_SONAR_FILE_POINTS)
        return record == MB_SONAR_POINTS_POINT_COUNT ? b->point_count : (uint16_t)b->points[record - 1];
    switch (record) {
    case MB_SONAR_CONFIG_SWEEP_ENABLE: return b->sweep_enable;
    case MB_SONAR_CONFIG_SWEEP_HALF_ANGLE: return b->sweep_half_angle_deg;
    case MB_SONAR_CONFIG_SWEEP_RATE: return b->sweep_rate_deg_s;
    default: return b->ping_period_ms;
    }
}

static mb_exception_t sonar_check_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    (void)board, (void)file, (void)record, (void)value;
    return MB_OK;
}

static void sonar_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    sonar_board_t *b = board;
    if (file != MB_SONAR_FILE_CONFIG)
        return;
    switch (record) {
    case MB_SONAR_CONFIG_SWEEP_ENABLE: b->sweep_enable = value; break;
    case MB_SONAR_CONFIG_SWEEP_HALF_ANGLE: b->sweep_half_angle_deg = value; break;
    case MB_SONAR_CONFIG_SWEEP_RATE: b->sweep_rate_deg_s = value; break;
    case MB_SONAR_CONFIG_PING_PERIOD: b->ping_period_ms = value; break;
    default: break;
    }
}

static const mb_board_ops_t sonar_ops = { .read = sonar_read, .check_write = sonar_check_write, .write = sonar_write };

void sonar_init(sonar_board_t *b, const sonar_model_t *m, uint64_t seed, uint32_t baud)
{
    memset(b, 0, sizeof *b);
    b->model = *m;
    rng_seed(&b->rng, seed);
    b->sweep_enable = MB_SONAR_CONFIG_SWEEP_ENABLE_DEFAULT;
    b->sweep_half_angle_deg = MB_SONAR_CONFIG_SWEEP_HALF_ANGLE_DEFAULT;
    b->sweep_rate_deg_s = MB_SONAR_CONFIG_SWEEP_RATE_DEFAULT;
    b->ping_period_ms = MB_SONAR_CONFIG_PING_PERIOD_DEFAULT;
    for (int k = 0; k < SONAR_SENSORS; k++)
        b->next_ping_us[k] = (uint64_t)k * 20000u;
    mb_slave_init(&b->modbus, &mb_sonar_board, &sonar_ops, b, baud);
}

double sonar_servo_offset(const sonar_board_t *b, int k, uint64_t now_us)
{
    if (!b->sweep_enable || b->sweep_half_angle_deg == 0)
        return 0.0;
    double amp = b->sweep_half_angle_deg * DEG, rate = b->sweep_rate_deg_s * DEG;
    double period = 4.0 * amp / rate;
    double phase = fmod(now_us * 1e-6 / period + k / 3.0, 1.0);
    /* triangle: 0 -> +amp -> 0 -> -amp -> 0 */
    double tri = phase < 0.25 ? 4 * phase : phase < 0.75 ? 2 - 4 * phase : 4 * phase - 4;
    return amp * tri;
}

static int16_t mm(double m)
{
    double q = nearbyint(m * 1000.0);
    return q > 32767 ? 32767 : q < -32768 ? -32768 : (int16_t)q;
}

void sonar_update(sonar_board_t *b, const body_state_t *body, uint64_t now_us,
                  sonar_raycast_fn raycast, void *ctx)
{
    const sonar_model_t *m = &b->model;
    for (int k = 0; k < SONAR_SENSORS; k++) {
        if (now_us < b->next_ping_us[k])
            continue;
        b->next_ping_us[k] += (uint64_t)b->ping_period_ms * 1000u;
        const sonar_mount_t *mt = &m->mount[k];
        double axis = mt->mount_angle + sonar_servo_offset(b, k, now_us);
        double c = cos(body->theta), s = sin(body->theta);
        double sx = body->x + c * mt->mount_x - s * mt->mount_y;
        double sy = body->y + s * mt->mount_x + c * mt->mount_y;
        double nearest = m->max_range;
        for (int r = 0; r < m->rays; r++) {
            double off = m->rays > 1 ? m->beam_half_angle * (2.0 * r / (m->rays - 1) - 1.0) : 0.0;
            double d = raycast(ctx, sx, sy, body->theta + axis + off, m->max_range);
            if (d < nearest)
                nearest = d;
        }
        uint16_t *reg = &b->latest[6 * k];
        reg[0]++;
        reg[1] = (uint16_t)(int16_t)nearbyint(remainder(axis, 2 * M_PI) * 1e4);
        double measured = nearest + (m->noise_floor + m->noise_fraction * nearest) * rng_gauss(&b->rng);
        if (nearest >= m->max_range || measured < m->min_range) {
            reg[2] = reg[3] = reg[4] = 0;
            reg[5] = 0;
            continue;
        }
        double px = mt->mount_x + measured * cos(axis), py = mt->mount_y + measured * sin(axis);
        reg[2] = (uint16_t)nearbyint(measured * 1000.0);
        reg[3] = (uint16_t)mm(px);
        reg[4] = (uint16_t)mm(py);
        reg[5] = 1;
        unsigned slot = b->point_count % SONAR_RING;
        b->points[2 * slot] = mm(px);
        b->points[2 * slot + 1] = mm(py);
        b->point_count++;
    }
}
