#include "robot.h"

#include <math.h>
#include <string.h>

/* Current-sense chain noise, in ADC LSB (about 6 mA). */
#define ADC_NOISE_LSB 2.0

void robot_config_default(robot_config_t *c)
{
    memset(c, 0, sizeof *c);
    c->id = 1;
    robot_params_default(&c->params);
    c->seed = 1;
    c->baud = MB_SERIAL_BAUD;
    battery_params_default(&c->battery);
    c->battery_soc = 1.0;
}

static bool footprint_blocked(void *ctx, double x, double y)
{
    const robot_t *self = ctx;
    const arena_t *a = self->arena;
    double radius = self->cfg.params.radius;
    if (a->world && world_clearance(a->world, x, y) < radius)
        return true;
    if (a->scene && scene_blocks(a->scene, self->body.x, self->body.y, x, y, radius))
        return true;
    for (int i = 0; i < a->n_robots; i++) {
        const robot_t *o = a->robots[i];
        if (o == self)
            continue;
        double dx = o->body.x - x, dy = o->body.y - y, reach = radius + o->cfg.params.radius;
        /* Only block motion that brings the two closer: robots in contact can part. */
        double now_dx = o->body.x - self->body.x, now_dy = o->body.y - self->body.y;
        if (dx * dx + dy * dy < reach * reach && dx * dx + dy * dy < now_dx * now_dx + now_dy * now_dy)
            return true;
    }
    return false;
}

/* Ray against the map, the scene's obstacles and people, and the other robots' discs. */
static double arena_raycast(void *ctx, double x, double y, double angle, double max_range)
{
    const robot_t *self = ctx;
    const arena_t *a = self->arena;
    double best = a->world ? world_raycast(a->world, x, y, angle, max_range) : max_range;
    if (a->scene)
        best = scene_raycast(a->scene, x, y, angle, best);
    double ux = cos(angle), uy = sin(angle);
    for (int i = 0; i < a->n_robots; i++) {
        const robot_t *o = a->robots[i];
        if (o == self)
            continue;
        double ox = o->body.x - x, oy = o->body.y - y, rr = o->cfg.params.radius;
        double along = ox * ux + oy * uy;
        double perp2 = ox * ox + oy * oy - along * along;
        if (along <= 0 || perp2 > rr * rr)
            continue;
        double t = along - sqrt(rr * rr - perp2);
        if (t >= 0 && t < best)
            best = t;
    }
    return best;
}

static void sact_uart_to_bus(void *ctx, const uint8_t *frame, size_t len);

static void queue_answer(robot_t *r, robot_board_t board, const uint8_t *frame, size_t len)
{
    if (len == 0 || r->link_cut[board])
        return;
    if (rng_uniform(&r->fault_rng) < r->cfg.faults.drop_rate) {
        r->answers_dropped++;
        return;
    }
    if (r->tx_count == BUS_TX_QUEUE)
        return;   /* a master that never reads: its oldest answers are still queued */
    bus_frame_t *f = &r->tx[r->tx_count++];
    memcpy(f->data, frame, len);
    f->len = len;
    f->port = r->master_port;
    f->due_us = r->now_us + (uint64_t)len * r->char_us + r->cfg.faults.latency_us;
    if (rng_uniform(&r->fault_rng) < r->cfg.faults.crc_error_rate) {
        f->data[len - 1] ^= (uint8_t)(1u << (rng_next(&r->fault_rng) >> 61));
        r->answers_corrupted++;
    }
}

static void sact_uart_to_bus(void *ctx, const uint8_t *frame, size_t len)
{
    queue_answer(ctx, BOARD_SACT, frame, len);
}

void robot_init(robot_t *r, const robot_config_t *cfg, const arena_t *arena)
{
    memset(r, 0, sizeof *r);
    r->cfg = *cfg;
    r->arena = arena;
    drivetrain_init(&r->drivetrain, &cfg->params, SACT_TS_US * 1e-6);
    r->body.x = cfg->x;
    r->body.y = cfg->y;
    r->body.theta = cfg->theta;
    /* Independent streams per subsystem, all derived from the one seed. */
    rng_seed(&r->noise_rng, cfg->seed * 1000003u + 1u);
    rng_seed(&r->fault_rng, cfg->seed * 1000003u + 2u);
    r->char_us = (11u * 1000000u + cfg->baud - 1u) / cfg->baud;
    r->master_port = -1;

    r->hal.uart_send = sact_uart_to_bus;
    r->hal.uart_ctx = r;
    for (int w = 0; w < 2; w++) {
        r->hal.encoder[w] = (uint16_t)cfg->encoder_offset;
        r->hal.adc_current[w] = SACT_ADC_ZERO;
    }
    sact_init(&r->sact, &r->hal, cfg->baud);
    /* Boot with the firmware's wheel geometry matching the simulated robot's. */
    sact_write_register(&r->sact, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_GEAR_RATIO,
                        (uint16_t)lround(cfg->params.gear_ratio * 100.0));
    sact_write_register(&r->sact, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_ENCODER_LINES,
                        (uint16_t)cfg->params.encoder_lines);
    sact_write_register(&r->sact, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_WHEEL_RADIUS,
                        (uint16_t)lround(cfg->params.wheel_radius * 1e4));

    ins_error_model_t ins_model;
    ins_error_model_default(&ins_model);
    ins_init(&r->ins, &ins_model, cfg->seed * 1000003u + 3u, cfg->baud);
    sonar_model_t sonar_model;
    sonar_model_default(&sonar_model);
    sonar_init(&r->sonar, &sonar_model, cfg->seed * 1000003u + 4u, cfg->baud);
    landmark_model_t landmark_model;
    landmark_model_default(&landmark_model);
    landmark_init(&r->landmark, &landmark_model, cfg->seed * 1000003u + 5u, cfg->baud);
    battery_init(&r->battery, &cfg->battery, cfg->battery_soc);
    power_model_t power_model;
    power_model_default(&power_model);
    power_init(&r->power, &power_model, &r->battery, cfg->seed * 1000003u + 6u, cfg->baud);
}

static uint16_t adc_sample(robot_t *r, double amps)
{
    /* 0.25 V/A around mid-rail into a 3.3 V 12-bit converter (sact_config.h). */
    double lsb = SACT_ADC_ZERO + amps * 0.25 / 3.3 * 4096.0 + ADC_NOISE_LSB * rng_gauss_fast(&r->noise_rng);
    return (uint16_t)(lsb < 0 ? 0 : lsb > 4095 ? 4095 : lrint(lsb));
}

void robot_step(robot_t *r)
{
    /* RS-485 bytes whose last bit has arrived by now. */
    while (r->rx_tail != r->rx_head && r->rx_time[r->rx_tail] <= r->now_us) {
        uint8_t byte = r->rx_byte[r->rx_tail];
        uint32_t t = (uint32_t)r->rx_time[r->rx_tail];
        r->rx_tail = (r->rx_tail + 1u) % BUS_RX_QUEUE;
        r->hal.time_us = t;
        if (!r->link_cut[BOARD_SACT])
            sact_uart_rx_isr(&r->sact, byte);
        if (!r->link_cut[BOARD_INS])
            mb_slave_on_byte(&r->ins.modbus, byte, t);
        if (!r->link_cut[BOARD_SONAR])
            mb_slave_on_byte(&r->sonar.modbus, byte, t);
        if (!r->link_cut[BOARD_LANDMARK])
            mb_slave_on_byte(&r->landmark.modbus, byte, t);
        if (!r->link_cut[BOARD_POWER])
            mb_slave_on_byte(&r->power.modbus, byte, t);
    }

    /* Sample the hardware, run the control interrupt, apply its outputs. */
    r->hal.time_us = (uint32_t)r->now_us;
    for (int w = 0; w < 2; w++) {
        r->hal.encoder[w] = (uint16_t)(drivetrain_encoder(&r->drivetrain, &r->body, w) + r->cfg.encoder_offset);
        r->hal.adc_current[w] = adc_sample(r, r->body.wheel[w].current);
    }
    sact_control_isr(&r->sact);
    bridge_input_t in[2] = {
        { r->hal.pwm[0], r->hal.pin[HAL_PIN_BRAKE_M1] },
        { r->hal.pwm[1], r->hal.pin[HAL_PIN_BRAKE_M2] },
    };
    drivetrain_step(&r->drivetrain, &r->body, in, footprint_blocked, r);
    /* The bridges' output power, as the drivetrain computed each winding's voltage and current. */
    double motor_power = 0;
    for (int w = 0; w < 2; w++)
        motor_power += drivetrain_bridge_voltage(&r->drivetrain, in[w]) * r->body.wheel[w].current;
    const world_t *world = r->arena->world;
    bool docked = world && world_dock_at(world, r->body.x, r->body.y) >= 0;
    battery_step(&r->battery, motor_power, docked, SACT_TS_US * 1e-6);
    /* A person walking into a standing robot presses on it too. */
    if (!r->body.in_contact && r->arena->scene &&
        scene_overlaps(r->arena->scene, r->body.x, r->body.y, r->cfg.params.radius)) {
        r->body.in_contact = true;
        r->body.collisions++;
    }
    r->now_us += SACT_TS_US;
    if (r->frame_end_us && r->now_us >= r->frame_end_us)
        r->frame_end_us = 0;   /* the boards' main loops below see the silence in this step */

    ins_update(&r->ins, &r->body, r->now_us);
    sonar_update(&r->sonar, &r->body, r->now_us, arena_raycast, r);
    landmark_update(&r->landmark, &r->body, r->now_us, world ? world->landmarks : NULL,
                    world ? world->n_landmarks : 0);
    power_update(&r->power, &r->battery, r->now_us, SACT_TS_US);

    /* Main loops of the boards. */
    r->hal.time_us = (uint32_t)r->now_us;
    sact_poll(&r->sact);
    queue_answer(r, BOARD_INS, r->ins.modbus.tx, mb_slave_poll(&r->ins.modbus, (uint32_t)r->now_us));
    queue_answer(r, BOARD_SONAR, r->sonar.modbus.tx, mb_slave_poll(&r->sonar.modbus, (uint32_t)r->now_us));
    queue_answer(r, BOARD_LANDMARK, r->landmark.modbus.tx,
                 mb_slave_poll(&r->landmark.modbus, (uint32_t)r->now_us));
    queue_answer(r, BOARD_POWER, r->power.modbus.tx, mb_slave_poll(&r->power.modbus, (uint32_t)r->now_us));
}

size_t robot_bus_write(robot_t *r, int port, const uint8_t *bytes, size_t len)
{
    size_t n = 0;
    uint64_t t = r->line_free_us > r->now_us ? r->line_free_us : r->now_us;
    for (; n < len; n++) {
        unsigned next = (r->rx_head + 1u) % BUS_RX_QUEUE;
        if (next == r->rx_tail) {
            r->rx_overflows++;
            break;
        }
        t += r->char_us;
        r->rx_byte[r->rx_head] = bytes[n];
        r->rx_time[r->rx_head] = t;
        r->rx_head = next;
    }
    r->line_free_us = t;
    if (n > 0) {
        r->master_port = port;
        r->frame_end_us = t + r->sact.modbus.t35_us;
    }
    return n;
}

bool robot_bus_take(robot_t *r, bus_frame_t *out)
{
    for (unsigned i = 0; i < r->tx_count; i++) {
        if (r->tx[i].due_us <= r->now_us) {
            *out = r->tx[i];
            memmove(&r->tx[i], &r->tx[i + 1], (r->tx_count - i - 1u) * sizeof r->tx[0]);
            r->tx_count--;
            return true;
        }
    }
    return false;
}

uint64_t robot_bus_next_due(const robot_t *r)
{
    uint64_t next = UINT64_MAX;
    for (unsigned i = 0; i < r->tx_count; i++)
        if (r->tx[i].due_us < next)
            next = r->tx[i].due_us;
    return next;
}

uint64_t robot_bus_next_event(const robot_t *r)
{
    uint64_t next = robot_bus_next_due(r);
    return r->frame_end_us && r->frame_end_us < next ? r->frame_end_us : next;
}
