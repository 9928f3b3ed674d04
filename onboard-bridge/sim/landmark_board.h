/*
 * Virtual ceiling-landmark board (slave address 4): an up-looking camera at the robot
 * centre that reads passive markers on the ceiling, in the manner of a Hagisonic
 * StarGazer. Every period it measures once: the nearest marker whose horizontal
 * distance from the camera is within the view radius, as an id, a horizontal range
 * and a bearing in the robot frame (counter-clockwise from the heading); id 0 when no
 * marker is in view. The registers keep that measurement until the next one, and
 * report its age when read, so a master can tell how old a fix is.
 *
 * Error model: range sigma = 10 mm, bearing sigma = 0.5 deg, white and gaussian, drawn
 * from the board's own seeded generator (landmark_model_default() says why these
 * figures). The marker is identified without error: StarGazer markers carry a coded
 * id, and a misread is not modelled. Quantised to 1 mm and 1e-4 rad.
 */
#ifndef SIM_LANDMARK_BOARD_H
#define SIM_LANDMARK_BOARD_H

#include "drivetrain.h"
#include "modbus_rtu.h"
#include "rng.h"
#include "world.h"

typedef struct {
    double range_sigma;        /* m */
    double bearing_sigma;      /* rad */
} landmark_model_t;

void landmark_model_default(landmark_model_t *m);

typedef struct {
    landmark_model_t model;
    sim_rng_t rng;
    uint16_t view_radius_mm, period_ms;      /* file 2 */
    uint16_t sequence, landmark_id, range_mm;
    int16_t bearing;                         /* 1e-4 rad */
    uint64_t next_us;                        /* when the next measurement is due */
    uint64_t taken_us;                       /* when the current one was taken */
    uint64_t now_us;                         /* last update, for the age read at any moment */
    mb_slave_t modbus;
} landmark_board_t;

void landmark_init(landmark_board_t *b, const landmark_model_t *m, uint64_t seed, uint32_t baud);

/* Advances the board's clock to now_us and measures when a period has elapsed; the
 * markers are the world's (n may be 0: the camera then never sees anything). */
void landmark_update(landmark_board_t *b, const body_state_t *body, uint64_t now_us,
                     const world_landmark_t *marks, int n);

#endif
