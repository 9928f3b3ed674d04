/*
 * The robot's battery: a 7-cell lithium-ion pack (NMC chemistry, 25.2 V nominal) and
 * the dock's charger. Integrated every control period:
 *
 *   open-circuit voltage   OCV(soc) = cells x the cell's curve (battery_cell_ocv)
 *   load                   P = base load + sum over the motors of V_bridge x I_winding / bridge efficiency
 *                          (a motor braking back into the bridge returns its power: P may be negative)
 *   discharging            I = P / V (V of the previous period),  V = OCV - R I
 *   on a dock              the charger carries the load and charges at constant current, then constant
 *                          voltage: I = -min(I_cc, (cells x V_cv - OCV) / R),  V = OCV - R I
 *                          ending when |I| falls below C/20 (full: I = 0, V = OCV, until the robot leaves)
 *   state of charge        d soc / dt = -I / (3600 capacity)
 *
 * Not modelled: the motors' supply follows the battery (the drivetrain keeps its 24 V), the
 * protection circuit's cut-off at 0 % (the robot runs on and the charge stays at 0), temperature,
 * ageing, the cell's relaxation after a load (R is one resistance, no RC pair).
 */
#ifndef SIM_BATTERY_H
#define SIM_BATTERY_H

#include <stdbool.h>

typedef struct {
    int cells;                  /* in series */
    double capacity_ah;         /* Ah of the full pack */
    double resistance;          /* ohm, the pack's internal resistance */
    double base_load_w;         /* W: the embedded PC, the boards, the sensors */
    double bridge_efficiency;   /* the H-bridges' share of their input power that reaches the motors */
    double charge_current;      /* A, the charger's constant current */
    double charge_cell_voltage; /* V per cell of the charger's constant-voltage phase */
    double full_fraction;       /* the charge ends below this fraction of the capacity per hour (C/20) */
} battery_params_t;

/* The simulated robot's pack (battery.c says where each figure comes from); the capacity is the
 * power board's design_capacity default of the map. */
void battery_params_default(battery_params_t *p);

typedef struct {
    battery_params_t p;
    double soc;                 /* 0..1 */
    double voltage;             /* V at the terminals */
    double current;             /* A, positive discharging */
    bool docked, charging, full;
} battery_t;

/* Open-circuit voltage of one cell at a state of charge 0..1 (clamped). */
double battery_cell_ocv(double soc);

void battery_init(battery_t *b, const battery_params_t *p, double soc);

/* Sets the state of charge (0..1), as a test stages it; the voltage follows at once. */
void battery_set_soc(battery_t *b, double soc);

/* One period of dt seconds with the motors drawing motor_power_w at their bridges' outputs;
 * docked: the charger contacts touch a dock's. */
void battery_step(battery_t *b, double motor_power_w, bool docked, double dt);

#endif
