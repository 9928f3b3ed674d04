/*
 * Virtual power board (slave address 5): the battery's fuel gauge and the charger contacts.
 * Every period it stores one measurement: the terminal voltage and the current averaged over
 * the period just ended (a shunt monitor's averaging, as an INA226 does), the state of charge,
 * and whether the contacts touch a dock's, current flows into the battery, the charge has ended.
 *
 * Error model: voltage sigma 5 mV and current sigma 5 mA on each measurement, white and
 * gaussian from the board's own seeded generator (a 16-bit monitor's LSB and noise after
 * averaging); quantised to 1 mV, 1 mA and 0.01 %. The state of charge is the gauge's coulomb
 * count; its drift against the true charge is not modelled (it reports the battery's).
 */
#ifndef SIM_POWER_BOARD_H
#define SIM_POWER_BOARD_H

#include "battery.h"
#include "modbus_rtu.h"
#include "rng.h"

typedef struct {
    double voltage_sigma;      /* V */
    double current_sigma;      /* A */
} power_model_t;

void power_model_default(power_model_t *m);

typedef struct {
    power_model_t model;
    sim_rng_t rng;
    uint16_t design_capacity_mah, period_ms;   /* file 2 */
    uint16_t sequence, voltage_mv, soc;        /* soc in 0.01 % */
    int16_t current_ma;
    uint16_t status;
    double voltage_sum, current_sum;           /* V s, A s since the last measurement */
    uint64_t since_us, next_us;
    mb_slave_t modbus;
} power_board_t;

void power_init(power_board_t *b, const power_model_t *m, const battery_t *battery, uint64_t seed,
                uint32_t baud);

/* Accumulates the battery over the period ending at now_us (dt_us long) and measures when a
 * period has elapsed. */
void power_update(power_board_t *b, const battery_t *battery, uint64_t now_us, uint32_t dt_us);

#endif
