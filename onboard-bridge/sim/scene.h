/*
 * What moves on the floor besides the robots: disc obstacles and people, added,
 * moved and removed while the simulator runs (through its control channel).
 *
 * An obstacle is a fixed disc. A person is a disc of PERSON_RADIUS walking in a
 * straight line at constant velocity; people pass through walls and each other
 * (whoever stages the scene chooses their paths) but robots see them and bump into
 * them like into any obstacle. Positions in metres in the map frame.
 */
#ifndef SIM_SCENE_H
#define SIM_SCENE_H

#include <stdbool.h>

#define SCENE_MAX_ITEMS 64
#define SCENE_ID_MAX 32
#define PERSON_RADIUS 0.25   /* m: shoulder width ~0.5 m, as ROS people-tracking layers assume */

typedef enum { SCENE_OBSTACLE, SCENE_PERSON } scene_kind_t;

typedef struct {
    char id[SCENE_ID_MAX + 1];
    scene_kind_t kind;
    double x, y;             /* m, centre */
    double radius;           /* m */
    double vx, vy;           /* m/s; zero for obstacles */
} scene_item_t;

typedef struct {
    scene_item_t item[SCENE_MAX_ITEMS];
    int n;
} scene_t;

/* The item with this id (any kind), or NULL. */
scene_item_t *scene_find(scene_t *s, const char *id);

/* Appends an item; false when the scene is full. The caller has checked the id. */
bool scene_add(scene_t *s, const scene_item_t *item);

void scene_remove(scene_t *s, scene_item_t *item);

/* Advances every person by dt seconds. */
void scene_step(scene_t *s, double dt);

/* Whether a disc of `radius` at (x, y) overlaps an item. */
bool scene_overlaps(const scene_t *s, double x, double y, double radius);

/* Whether a disc of `radius` moving from (x0, y0) to (x1, y1) ends overlapping an
 * item it comes closer to: contact blocks approach, never parting. */
bool scene_blocks(const scene_t *s, double x0, double y0, double x1, double y1, double radius);

/* Distance along the ray from (x, y) at `angle` to the first item's edge, or
 * max_range when none is nearer. */
double scene_raycast(const scene_t *s, double x, double y, double angle, double max_range);

#endif
