#include "battery.h"

#include <math.h>

#include "modbus_map.h"

/* A cell's open-circuit voltage at 0 %, 10 %, ... 100 %: a typical NMC 18650 cell's rest voltage after a
 * slow discharge (the shape of the manufacturers' 0.2 C curves), ending at the charger's 4.20 V so that the
 * constant-voltage phase ends at a full cell. Assumed figures, not one data sheet's. */
static const double CELL_OCV[] = { 3.00, 3.45, 3.55, 3.62, 3.68, 3.74, 3.82, 3.91, 3.99, 4.08, 4.20 };
#define OCV_STEPS ((int)(sizeof CELL_OCV / sizeof CELL_OCV[0]) - 1)

void battery_params_default(battery_params_t *p)
{
    /* 7S4P of 2.5 Ah NMC cells: 25.2 V nominal for the 24 V motors, 10 Ah (the map's design_capacity
     * default, one source); 7 x 30 mOhm / 4 per cell string plus ~40 mOhm of protection circuit, fuse and
     * wiring. The base load: an embedded PC of ~10 W, the four boards and the sensors ~3 W, the radio ~2 W.
     * Locked-antiphase bridges of MOSFETs lose about 5 %. The charger: 0.5 C constant current, 4.20 V per
     * cell, ending at C/20, the usual lithium-ion profile. */
    p->cells = 7;
    p->capacity_ah = MB_POWER_CONFIG_DESIGN_CAPACITY_DEFAULT * 1e-3;
    p->resistance = 0.10;
    p->base_load_w = 15.0;
    p->bridge_efficiency = 0.95;
    p->charge_current = 5.0;
    p->charge_cell_voltage = 4.20;
    p->full_fraction = 0.05;
}

double battery_cell_ocv(double soc)
{
    if (!(soc > 0))
        return CELL_OCV[0];
    if (soc >= 1)
        return CELL_OCV[OCV_STEPS];
    double at = soc * OCV_STEPS;
    int k = (int)at;
    return CELL_OCV[k] + (at - k) * (CELL_OCV[k + 1] - CELL_OCV[k]);
}

static double clamp01(double v) { return v < 0 ? 0 : v > 1 ? 1 : v; }

void battery_init(battery_t *b, const battery_params_t *p, double soc)
{
    *b = (battery_t){ .p = *p };
    battery_set_soc(b, soc);
}

void battery_set_soc(battery_t *b, double soc)
{
    b->soc = clamp01(soc);
    b->current = 0;
    b->voltage = b->p.cells * battery_cell_ocv(b->soc);
    b->charging = b->full = false;
}

void battery_step(battery_t *b, double motor_power_w, bool docked, double dt)
{
    const battery_params_t *p = &b->p;
    double ocv = p->cells * battery_cell_ocv(b->soc);
    if (!docked)
        b->full = false;
    b->docked = docked;
    if (docked && !b->full) {
        double cv_current = (p->cells * p->charge_cell_voltage - ocv) / p->resistance;
        double charge = fmin(p->charge_current, cv_current);
        if (charge < p->full_fraction * p->capacity_ah) {
            b->full = true;
        } else {
            b->current = -charge;
            b->charging = true;
        }
    }
    if (b->full) {
        b->current = 0;
        b->charging = false;
    } else if (!docked) {
        double motors = motor_power_w > 0 ? motor_power_w / p->bridge_efficiency : motor_power_w;
        b->current = (p->base_load_w + motors) / b->voltage;
        b->charging = false;
    }
    b->soc = clamp01(b->soc - b->current * dt / (3600.0 * p->capacity_ah));
    b->voltage = ocv - p->resistance * b->current;
}
