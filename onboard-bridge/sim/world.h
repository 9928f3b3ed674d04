/*
 * The world: an occupancy grid loaded from a ROS map_server map (YAML + PGM), a
 * distance field for collisions, and ray casting for the range sensors.
 *
 * Frames follow ROS: the map frame is right-handed, `origin` is the pose of the
 * lower-left pixel, image row 0 is the top of the map. A cell is an obstacle when
 * its occupancy p > occupied_thresh, with p = (255 - v)/255 (or v/255 if negate);
 * unknown cells (between the thresholds) neither block nor echo. Outside the map
 * counts as an obstacle, so robots cannot leave it.
 *
 * Ceiling landmarks (a Sabot extension that map_server ignores, as it ignores every
 * key it does not know): `sabot_landmarks: FILE`, relative to the YAML's folder
 * unless absolute, one marker per line `id x y` (id 1..65535, x and y in metres in
 * the map frame), `#` comments and blank lines allowed, ids unique.
 *
 * Docks (a Sabot extension too): `sabot_docks: [[x, y], [x, y], ...]` in metres in the map
 * frame, a flow sequence on one line. A dock's charger contacts meet the robot's when the
 * robot's centre is within WORLD_DOCK_REACH of the dock's point, whatever its heading.
 */
#ifndef SIM_WORLD_H
#define SIM_WORLD_H

#include <stdbool.h>
#include <stdint.h>

#define WORLD_MAX_LANDMARKS 1024
#define WORLD_MAX_DOCKS 16
/* m: a robot whose centre is this close to a dock's point charges there. The docking goal's
 * tolerance must be tighter (sabot.onboard.motion's dock settings). */
#define WORLD_DOCK_REACH 0.15

/* A charging dock on the floor at (x, y), m, map frame. */
typedef struct {
    double x, y;
} world_dock_t;

/* A passive marker on the ceiling above (x, y). */
typedef struct {
    uint16_t id;               /* 1..65535 */
    double x, y;               /* m, map frame */
} world_landmark_t;

typedef struct {
    int width, height;         /* cells */
    double resolution;         /* m per cell */
    double origin_x, origin_y; /* m, lower-left corner */
    uint8_t *occupied;         /* width*height, row 0 = bottom (y up) */
    float *clearance;          /* m from the cell centre to the nearest obstacle cell */
    world_landmark_t *landmarks; /* n_landmarks markers, in file order (NULL when none) */
    int n_landmarks;
    world_dock_t docks[WORLD_MAX_DOCKS]; /* n_docks, in the YAML's order */
    int n_docks;
} world_t;

/* Loads a map_server YAML (image, resolution, origin, negate, occupied_thresh,
 * free_thresh, and Sabot's sabot_landmarks and sabot_docks), its PGM (P5 or P2) and its landmarks.
 * Returns 0, or -1 with a message in err (a landmarks file's errors as FILE:LINE: ...). */
int world_load(world_t *w, const char *yaml_path, char *err, int err_len);
void world_free(world_t *w);

/* Reads a landmarks file into w->landmarks. Returns 0, or -1 with "FILE:LINE: problem"
 * (or "FILE: problem") in err, leaving w's landmarks as they were. */
int world_load_landmarks(world_t *w, const char *path, char *err, int err_len);

/* Parses a sabot_docks value, "[[x, y], ...]", into w->docks. Returns 0, or -1 with a
 * message naming what was wrong in err, leaving w's docks as they were. */
int world_parse_docks(world_t *w, const char *value, char *err, int err_len);

/* The dock whose reach (x, y) is in, or -1. */
int world_dock_at(const world_t *w, double x, double y);

bool world_occupied(const world_t *w, double x, double y);

/* Distance from (x, y) to the nearest obstacle cell's centre minus half a cell: a
 * lower bound good to one cell, which is the map's own precision. */
double world_clearance(const world_t *w, double x, double y);

/* First obstacle along the ray, by grid traversal (Amanatides & Woo 1987).
 * Returns the distance in m, or max_range when nothing is hit before it. */
double world_raycast(const world_t *w, double x, double y, double angle, double max_range);

#endif
