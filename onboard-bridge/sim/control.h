/*
 * The simulator's control channel: a line protocol on loopback TCP with which tests
 * and demos stage events while the simulation runs (obstacles, people, board links)
 * and read the ground truth. One command per line, one answer line per command:
 * "ok ..." or "error <message>"; a refused command changes nothing. The commands are
 * described in onboard-bridge/README.md ("Control channel").
 */
#ifndef SIM_CONTROL_H
#define SIM_CONTROL_H

#include <poll.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "robot.h"
#include "scene.h"

#define CONTROL_MAX_CLIENTS 8
#define CONTROL_LINE_MAX 256          /* bytes of one command, newline included */
#define CONTROL_ANSWER_MAX 8192       /* `list` of a full scene fits */
#define CONTROL_POLLFDS (1 + CONTROL_MAX_CLIENTS)

/* What the commands act on. */
typedef struct {
    scene_t *scene;
    robot_t *robots;                  /* robots[0] is robot 1 */
    int n_robots;
    const uint64_t *sim_us;           /* current simulated time */
} control_target_t;

/* Executes one command (no newline). Writes the answer line, without its newline,
 * into out. Returns true for "ok". */
bool control_execute(const control_target_t *t, const char *line, char *out, size_t out_len);

typedef struct {
    int fd;
    size_t len;
    bool overlong;                    /* discarding the rest of a line that did not fit */
    char buf[CONTROL_LINE_MAX];
} control_client_t;

typedef struct {
    int listen_fd;
    int port;
    control_client_t client[CONTROL_MAX_CLIENTS];
} control_server_t;

/* Listens on 127.0.0.1:port (0 = a free port, then s->port says which). Returns 0,
 * or -1 with errno set. */
int control_open(control_server_t *s, int port);

/* Fills CONTROL_POLLFDS entries (unused ones with fd -1). */
void control_pollfds(const control_server_t *s, struct pollfd *pfd);

/* Accepts connections and answers every complete line received, in order. */
void control_serve(control_server_t *s, const struct pollfd *pfd, const control_target_t *t);

void control_close(control_server_t *s);

#endif
