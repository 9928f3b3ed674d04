/*
 * Virtual obstacle board (slave address 3): three ultrasonic rangers on servos that
 * sweep, each reporting the nearest echo as a point relative to the robot centre.
 *
 * Sensor model (HC-SR04 data sheet: 2 cm - 4 m, 15 deg measuring angle, 3 mm
 * resolution, >= 60 ms measurement cycle): a ping casts rays across the beam cone
 * (15 deg each side of the axis) and the first echo wins, as with a real transducer.
 * The board cannot tell where in the cone the echo came from, so it places the point
 * on the beam axis: that angular uncertainty is the sensor's, and the map keeps it.
 * Range noise sigma = 3 mm + 0.5 % of the range (speed of sound vs. temperature).
 * Specular misses on glancing walls are not modelled. Sensors ping 20 ms apart so
 * that their echoes do not cross.
 */
#ifndef SIM_SONAR_BOARD_H
#define SIM_SONAR_BOARD_H

#include "drivetrain.h"
#include "modbus_rtu.h"
#include "rng.h"

#define SONAR_SENSORS 3
#define SONAR_RING 32

typedef struct {
    double mount_angle;      /* rad, beam axis at servo centre, robot frame */
    double mount_x, mount_y; /* m, robot frame */
} sonar_mount_t;

typedef struct {
    double min_range, max_range, beam_half_angle;
    double noise_floor, noise_fraction;
    int rays;
    sonar_mount_t mount[SONAR_SENSORS];
} sonar_model_t;

void sonar_model_default(sonar_model_t *m);

/* Range to the first obstacle along a ray in the map frame (world and other robots). */
typedef double (*sonar_raycast_fn)(void *ctx, double x, double y, double angle, double max_range);

typedef struct {
    sonar_model_t model;
    sim_rng_t rng;
    uint16_t sweep_enable, sweep_half_angle_deg, sweep_rate_deg_s, ping_period_ms;
    uint64_t next_ping_us[SONAR_SENSORS];
    uint16_t latest[SONAR_SENSORS * 6];     /* file 1 image */
    int16_t points[2 * SONAR_RING];         /* file 2 ring, x/y pairs in mm */
    uint16_t point_count;
    mb_slave_t modbus;
} sonar_board_t;

void sonar_init(sonar_board_t *b, const sonar_model_t *m, uint64_t seed, uint32_t baud);

/* Servo angle offset of sensor k at time t: a triangle wave, sensors a third apart. */
double sonar_servo_offset(const sonar_board_t *b, int k, uint64_t now_us);

void sonar_update(sonar_board_t *b, const body_state_t *body, uint64_t now_us,
                  sonar_raycast_fn raycast, void *ctx);

#endif
