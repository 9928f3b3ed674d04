/*
 * Physics of a SabotOne: two Maxon A-MAX 32 motors in locked-antiphase H-bridges,
 * planetary gearheads, rubber wheels with slip, a 15 kg body on casters.
 *
 * Per wheel, integrated at the control rate Ts = 50 us:
 *   bridge   V = Vs (2 d/1024 - 1); brake shorts the terminals (V = 0)
 *   winding  L di/dt = V - R i - Ke w_m          (exact step for constant V, w_m)
 *   motor    tau_m = Kt i - tau_f tanh(w_m / w_f)
 *   gearhead tau_w = N eta tau_m when the motor drives, N tau_m / eta when driven
 *   wheel    J_w dw/dt = tau_w - r F
 *   contact  F = clamp(c_slip (r w - v_contact), +-mu N_wheel)
 *   body     m dv/dt = F_l + F_r - rolling;  I_z dw_z/dt = (F_r - F_l) b/2 - rolling moment
 * with J_w = (J_rotor + J_gear) N^2 + J_wheel reflected to the wheel. The contact
 * stiffness keeps c_slip (r^2/J_w + 1/m_eff) Ts well below 1, so the explicit step is
 * stable and does not ring.
 */
#ifndef SIM_DRIVETRAIN_H
#define SIM_DRIVETRAIN_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    /* Maxon A-MAX 32 (24 V winding) data sheet values */
    double supply_v;         /* V */
    double resistance;       /* ohm, terminal */
    double inductance;       /* H, terminal */
    double torque_constant;  /* N m / A, = back-EMF constant in V s/rad */
    double rotor_inertia;    /* kg m^2 */
    double motor_friction;   /* N m, from the no-load current */
    /* gearhead and wheel */
    double gear_ratio;
    double gear_efficiency;
    double gear_inertia;     /* kg m^2 at the motor shaft */
    double wheel_radius;     /* m */
    double wheel_inertia;    /* kg m^2 */
    double track;            /* m, between the wheel contact points */
    /* body */
    double mass;             /* kg */
    double yaw_inertia;      /* kg m^2 */
    double drive_load;       /* fraction of the weight on the two drive wheels (casters carry the rest) */
    double rolling_coeff;    /* rolling resistance coefficient */
    double tire_mu;          /* friction coefficient of the tyres */
    double slip_damping;     /* N per m/s of slip velocity: the linear part of the tyre curve */
    double radius;           /* m, footprint disc for collisions */
    int encoder_lines;       /* per motor revolution, x4 quadrature */
} robot_params_t;

void robot_params_default(robot_params_t *p);

typedef struct {
    double current;          /* A */
    double omega;            /* rad/s of the wheel */
    double motor_angle;      /* rad of the motor shaft since start */
    double torque;           /* N m at the motor shaft (for the record) */
    double slip;             /* m/s, wheel surface minus ground */
    bool jammed;             /* held still by something caught in it (a staged fault: the motor stalls) */
} wheel_state_t;

typedef struct {
    double x, y, theta;      /* m, m, rad in the map frame */
    double v, omega;         /* m/s forward, rad/s yaw */
    double accel;            /* m/s^2 forward, last step */
    wheel_state_t wheel[2];  /* 0 left, 1 right */
    uint64_t collisions;     /* steps spent pressed against an obstacle */
    bool in_contact;
} body_state_t;

typedef struct {
    robot_params_t p;
    /* derived once */
    double current_decay;    /* exp(-R Ts / L) */
    double wheel_inertia_eff;
    double counts_per_rad;
    double dt;
} drivetrain_t;

void drivetrain_init(drivetrain_t *d, const robot_params_t *p, double dt);

/* Bridge inputs of one wheel. */
typedef struct {
    uint16_t pwm;
    bool brake;
} bridge_input_t;

/* The voltage a bridge puts across its motor's winding (0 while braking: the terminals are shorted). */
double drivetrain_bridge_voltage(const drivetrain_t *d, bridge_input_t in);

/* Advances wheels and body by dt. `blocked(ctx, x, y)` says whether the footprint at
 * (x, y) collides; a blocked translation is undone and the forward speed zeroed. */
void drivetrain_step(drivetrain_t *d, body_state_t *s, const bridge_input_t in[2],
                     bool (*blocked)(void *ctx, double x, double y), void *ctx);

/* Encoder counter of a wheel's motor (x4 quadrature), full 64-bit count. */
int64_t drivetrain_encoder(const drivetrain_t *d, const body_state_t *s, int wheel);

#endif
