#include "power_board.h"

#include <math.h>
#include <string.h>

void power_model_default(power_model_t *m)
{
    /* A 16-bit shunt and bus monitor (INA226 class: 1.25 mV bus LSB, a 2 mOhm shunt's ~1 mA LSB), its
     * readings averaged over the period: a few LSB of noise left. Assumed figures. */
    m->voltage_sigma = 0.005;
    m->current_sigma = 0.005;
}

static uint16_t power_read(void *board, uint16_t file, uint16_t record)
{
    const power_board_t *b = board;
    if (file == MB_POWER_FILE_CONFIG)
        return record == MB_POWER_CONFIG_DESIGN_CAPACITY ? b->design_capacity_mah : b->period_ms;
    switch (record) {
    case MB_POWER_LATEST_SEQUENCE: return b->sequence;
    case MB_POWER_LATEST_VOLTAGE: return b->voltage_mv;
    case MB_POWER_LATEST_CURRENT: return (uint16_t)b->current_ma;
    case MB_POWER_LATEST_STATE_OF_CHARGE: return b->soc;
    default: return b->status;
    }
}

/* The static bounds of the map (checked by the RTU layer) are the whole rule here. */
static mb_exception_t power_check_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    (void)board, (void)file, (void)record, (void)value;
    return MB_OK;
}

static void power_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    power_board_t *b = board;
    if (file == MB_POWER_FILE_CONFIG && record == MB_POWER_CONFIG_PERIOD)
        b->period_ms = value;
}

static const mb_board_ops_t power_ops = { .read = power_read, .check_write = power_check_write,
                                          .write = power_write };

static long quantise(double v, double lsb, long lo, long hi)
{
    double q = nearbyint(v / lsb);
    return q < lo ? lo : q > hi ? hi : (long)q;
}

static void measure(power_board_t *b, double voltage, double current, const battery_t *battery)
{
    b->sequence++;
    b->voltage_mv = (uint16_t)quantise(voltage + b->model.voltage_sigma * rng_gauss(&b->rng), 1e-3, 0, 65535);
    b->current_ma = (int16_t)quantise(current + b->model.current_sigma * rng_gauss(&b->rng), 1e-3, -32768, 32767);
    b->soc = (uint16_t)quantise(battery->soc, 1e-4, 0, MB_POWER_LATEST_STATE_OF_CHARGE_MAX);
    b->status = (uint16_t)((battery->docked ? MB_POWER_LATEST_STATUS_DOCKED : 0u) |
                           (battery->charging ? MB_POWER_LATEST_STATUS_CHARGING : 0u) |
                           (battery->full ? MB_POWER_LATEST_STATUS_FULL : 0u));
}

void power_init(power_board_t *b, const power_model_t *m, const battery_t *battery, uint64_t seed, uint32_t baud)
{
    memset(b, 0, sizeof *b);
    b->model = *m;
    rng_seed(&b->rng, seed);
    double mah = nearbyint(battery->p.capacity_ah * 1000.0);
    b->design_capacity_mah = (uint16_t)(mah < 1 ? 1 : mah > 65535 ? 65535 : mah);
    b->period_ms = MB_POWER_CONFIG_PERIOD_DEFAULT;
    b->next_us = (uint64_t)b->period_ms * 1000u;
    /* At power-on the gauge reads the battery at rest, so the registers are never empty. */
    measure(b, battery->voltage, battery->current, battery);
    b->sequence = 0;
    mb_slave_init(&b->modbus, &mb_power_board, &power_ops, b, baud);
}

void power_update(power_board_t *b, const battery_t *battery, uint64_t now_us, uint32_t dt_us)
{
    b->voltage_sum += battery->voltage * dt_us * 1e-6;
    b->current_sum += battery->current * dt_us * 1e-6;
    if (now_us < b->next_us)
        return;
    double span = (now_us - b->since_us) * 1e-6;
    measure(b, b->voltage_sum / span, b->current_sum / span, battery);
    b->voltage_sum = b->current_sum = 0;
    b->since_us = now_us;
    b->next_us = now_us + (uint64_t)b->period_ms * 1000u;
}
