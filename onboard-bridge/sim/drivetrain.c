#include "drivetrain.h"

#include "modbus_map.h"   /* SABOT_ROBOT_*, generated from docs/sabot-robot.properties */

#include <math.h>
#include <string.h>

void robot_params_default(robot_params_t *p)
{
    memset(p, 0, sizeof *p);
    p->supply_v = 24.0;
    p->resistance = 7.9;
    p->inductance = 0.77e-3;
    /* Kt = Ke from the described no-load speed (Vs / Ke): 24 V / 7743 rpm = 29.6 mNm/A, the data sheet's. */
    p->torque_constant = p->supply_v / (SABOT_ROBOT_MOTOR_NOLOADSPEED_RPM * 2.0 * M_PI / 60.0);
    p->rotor_inertia = 1.24e-6;
    /* ~60 mA no-load current x Kt */
    p->motor_friction = 1.8e-3;
    p->gear_ratio = SABOT_ROBOT_GEAR_RATIO;
    p->gear_efficiency = 0.70;       /* Maxon GP 32 A, 3 stages */
    p->gear_inertia = 0.7e-7;        /* GP 32 A, 3 stages, at the input */
    p->wheel_radius = SABOT_ROBOT_WHEEL_RADIUS_M;
    p->wheel_inertia = 0.6 * p->wheel_radius * p->wheel_radius / 2.0;   /* 0.6 kg disc */
    p->track = SABOT_ROBOT_TRACK_WIDTH_M;
    p->mass = 15.0;
    p->yaw_inertia = 15.0 * 0.25 * 0.25 / 2.0;      /* uniform disc of the footprint */
    p->drive_load = 0.8;
    p->rolling_coeff = 0.015;
    p->tire_mu = 0.8;
    p->slip_damping = 3000.0;
    p->radius = 0.25;
    p->encoder_lines = SABOT_ROBOT_ENCODER_LINES;
}

void drivetrain_init(drivetrain_t *d, const robot_params_t *p, double dt)
{
    d->p = *p;
    d->dt = dt;
    d->current_decay = exp(-p->resistance * dt / p->inductance);
    d->wheel_inertia_eff = (p->rotor_inertia + p->gear_inertia) * p->gear_ratio * p->gear_ratio +
                           p->wheel_inertia;
    d->counts_per_rad = 4.0 * p->encoder_lines / (2.0 * M_PI);
}

static double clamp(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

double drivetrain_bridge_voltage(const drivetrain_t *d, bridge_input_t in)
{
    return in.brake ? 0.0 : d->p.supply_v * (2.0 * in.pwm / 1024.0 - 1.0);
}

void drivetrain_step(drivetrain_t *d, body_state_t *s, const bridge_input_t in[2],
                     bool (*blocked)(void *ctx, double x, double y), void *ctx)
{
    const robot_params_t *p = &d->p;
    const double dt = d->dt, g = 9.81;
    const double normal = p->mass * g * p->drive_load / 2.0;
    const double rolling = p->rolling_coeff * p->mass * g / 2.0;
    double force[2], roll[2];

    for (int w = 0; w < 2; w++) {
        wheel_state_t *ws = &s->wheel[w];
        double omega_m = ws->omega * p->gear_ratio;
        double volts = drivetrain_bridge_voltage(d, in[w]);
        double i_ss = (volts - p->torque_constant * omega_m) / p->resistance;
        ws->current = i_ss + (ws->current - i_ss) * d->current_decay;
        double tau_m = p->torque_constant * ws->current - p->motor_friction * tanh(omega_m / 0.5);
        ws->torque = tau_m;
        double tau_w = tau_m * ws->omega >= 0.0 ? p->gear_ratio * p->gear_efficiency * tau_m
                                                : p->gear_ratio * tau_m / p->gear_efficiency;
        double side = w == 0 ? -1.0 : 1.0;
        double v_contact = s->v + side * s->omega * p->track / 2.0;
        ws->slip = p->wheel_radius * ws->omega - v_contact;
        force[w] = clamp(p->slip_damping * ws->slip, -p->tire_mu * normal, p->tire_mu * normal);
        roll[w] = rolling * tanh(v_contact / 0.005);
        ws->omega += dt * (tau_w - p->wheel_radius * force[w]) / d->wheel_inertia_eff;
        if (ws->jammed)
            ws->omega = 0.0;  /* the jam takes any torque: the motor stalls, the tyre drags on the floor */
        ws->motor_angle += dt * ws->omega * p->gear_ratio;
    }

    double f_net = force[0] + force[1] - roll[0] - roll[1];
    double moment = ((force[1] - roll[1]) - (force[0] - roll[0])) * p->track / 2.0;
    double v_old = s->v;
    s->v += dt * f_net / p->mass;
    s->omega += dt * moment / p->yaw_inertia;
    s->theta = remainder(s->theta + dt * s->omega, 2.0 * M_PI);
    double nx = s->x + dt * s->v * cos(s->theta), ny = s->y + dt * s->v * sin(s->theta);
    s->in_contact = blocked && blocked(ctx, nx, ny);
    if (s->in_contact) {
        /* Inelastic bump: the body stops, the wheels keep turning and slip. */
        s->v = 0.0;
        s->collisions++;
    } else {
        s->x = nx;
        s->y = ny;
    }
    s->accel = (s->v - v_old) / dt;
}

int64_t drivetrain_encoder(const drivetrain_t *d, const body_state_t *s, int wheel)
{
    return (int64_t)floor(s->wheel[wheel].motor_angle * d->counts_per_rad);
}
