#include "landmark_board.h"

#include <math.h>
#include <string.h>

void landmark_model_default(landmark_model_t *m)
{
    /* Assumed figures, not a data sheet's. Range sigma 10 mm: a camera 2-3 m below the
     * marker with a few hundred pixels across its view finds the marker's centre to
     * about a centimetre on the floor. Bearing sigma 0.5 deg is that centimetre seen
     * from 1.15 m, the middle of the default 1.5 m view radius. A camera's position
     * noise is isotropic, so its bearing noise really grows as the range shrinks; the
     * constant is what the localizer's range-bearing update takes as its sigma. */
    m->range_sigma = 0.010;
    m->bearing_sigma = 0.5 * M_PI / 180.0;
}

static uint16_t landmark_read(void *board, uint16_t file, uint16_t record)
{
    const landmark_board_t *b = board;
    if (file == MB_LANDMARK_FILE_CONFIG)
        return record == MB_LANDMARK_CONFIG_VIEW_RADIUS ? b->view_radius_mm : b->period_ms;
    switch (record) {
    case MB_LANDMARK_LATEST_SEQUENCE: return b->sequence;
    case MB_LANDMARK_LATEST_LANDMARK_ID: return b->landmark_id;
    case MB_LANDMARK_LATEST_RANGE: return b->range_mm;
    case MB_LANDMARK_LATEST_BEARING: return (uint16_t)b->bearing;
    default: {
        /* The age is the reader's: how old the measurement is now, not when it was stored. */
        uint64_t age_ms = (b->now_us - b->taken_us) / 1000u;
        return age_ms > MB_LANDMARK_LATEST_AGE_MAX ? MB_LANDMARK_LATEST_AGE_MAX : (uint16_t)age_ms;
    }
    }
}

/* The static bounds of the map (checked by the RTU layer) are the whole rule here. */
static mb_exception_t landmark_check_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    (void)board, (void)file, (void)record, (void)value;
    return MB_OK;
}

static void landmark_write(void *board, uint16_t file, uint16_t record, uint16_t value)
{
    landmark_board_t *b = board;
    if (file != MB_LANDMARK_FILE_CONFIG)
        return;
    if (record == MB_LANDMARK_CONFIG_VIEW_RADIUS)
        b->view_radius_mm = value;
    else if (record == MB_LANDMARK_CONFIG_PERIOD)
        b->period_ms = value;
}

static const mb_board_ops_t landmark_ops = { .read = landmark_read, .check_write = landmark_check_write,
                                             .write = landmark_write };

void landmark_init(landmark_board_t *b, const landmark_model_t *m, uint64_t seed, uint32_t baud)
{
    memset(b, 0, sizeof *b);
    b->model = *m;
    rng_seed(&b->rng, seed);
    b->view_radius_mm = MB_LANDMARK_CONFIG_VIEW_RADIUS_DEFAULT;
    b->period_ms = MB_LANDMARK_CONFIG_PERIOD_DEFAULT;
    mb_slave_init(&b->modbus, &mb_landmark_board, &landmark_ops, b, baud);
}

void landmark_update(landmark_board_t *b, const body_state_t *body, uint64_t now_us,
                     const world_landmark_t *marks, int n)
{
    b->now_us = now_us;
    if (now_us < b->next_us)
        return;
    b->next_us = now_us + (uint64_t)b->period_ms * 1000u;
    double view = b->view_radius_mm * 1e-3, best = INFINITY;
    int seen = -1;
    for (int k = 0; k < n; k++) {
        double d = hypot(marks[k].x - body->x, marks[k].y - body->y);
        if (d <= view && d < best) {
            best = d;
            seen = k;
        }
    }
    b->sequence++;
    b->taken_us = now_us;
    if (seen < 0) {
        b->landmark_id = 0;
        b->range_mm = 0;
        b->bearing = 0;
        return;
    }
    double dx = marks[seen].x - body->x, dy = marks[seen].y - body->y;
    double range = best + b->model.range_sigma * rng_gauss(&b->rng);
    double bearing = atan2(dy, dx) - body->theta + b->model.bearing_sigma * rng_gauss(&b->rng);
    double q = nearbyint(remainder(bearing, 2 * M_PI) * 1e4);
    b->landmark_id = marks[seen].id;
    b->range_mm = (uint16_t)(range <= 0 ? 0 : range >= 65.535 ? 65535 : nearbyint(range * 1000.0));
    b->bearing = (int16_t)(q > MB_LANDMARK_LATEST_BEARING_MAX ? MB_LANDMARK_LATEST_BEARING_MAX
                           : q < MB_LANDMARK_LATEST_BEARING_MIN ? MB_LANDMARK_LATEST_BEARING_MIN : q);
}
