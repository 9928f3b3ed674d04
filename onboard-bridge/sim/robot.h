/*
 * One simulated SabotOne: the SACT firmware core on the host HAL, the drivetrain
 * physics, the battery, the inertial, sonar, ceiling-landmark and power boards, and the
 * RS-485 bus that joins them. The battery charges while the robot stands on one of the
 * world's docks.
 *
 * The bus is a multi-drop line: every byte a master sends reaches every board's
 * UART, spaced by one character time (11 bits at the configured baud), and the
 * addressed board answers. Answers leave after their own transmission time plus any
 * injected latency, and go back to the transport (pty or TCP connection) that sent
 * the request; like a real line, the bus serves one master at a time.
 * Fault injection acts on answers: a dropped answer never leaves, a corrupted one
 * has a flipped CRC bit. A board's link can be cut (robot_t.link_cut) while the
 * board runs on.
 */
#ifndef SIM_ROBOT_H
#define SIM_ROBOT_H

#include "battery.h"
#include "drivetrain.h"
#include "hal_host.h"
#include "ins_board.h"
#include "landmark_board.h"
#include "power_board.h"
#include "rng.h"
#include "sact.h"
#include "scene.h"
#include "sonar_board.h"
#include "world.h"

#define BUS_RX_QUEUE 4096
#define BUS_TX_QUEUE 16

typedef struct {
    double crc_error_rate;   /* probability that an answer's CRC is corrupted */
    double drop_rate;        /* probability that an answer is lost */
    uint32_t latency_us;     /* added before an answer leaves */
} bus_faults_t;

typedef struct {
    int id;
    robot_params_t params;
    uint64_t seed;
    double x, y, theta;      /* start pose, map frame */
    uint32_t baud;
    bus_faults_t faults;
    int64_t encoder_offset;  /* initial counter value (tests start near a wrap) */
    battery_params_t battery;
    double battery_soc;      /* state of charge at start, 0..1 */
} robot_config_t;

void robot_config_default(robot_config_t *c);

typedef struct {
    uint8_t data[MB_ADU_MAX];
    size_t len;
    uint64_t due_us;
    int port;
} bus_frame_t;

typedef struct robot robot_t;

typedef struct {
    const world_t *world;    /* may be NULL: an empty, unbounded floor */
    robot_t **robots;        /* everyone sharing the floor, for collisions and echoes */
    int n_robots;
    const scene_t *scene;    /* may be NULL: no obstacles or people beyond the map */
} arena_t;

/* The boards on a robot's bus. */
typedef enum { BOARD_SACT, BOARD_INS, BOARD_SONAR, BOARD_LANDMARK, BOARD_POWER, BOARD_COUNT } robot_board_t;

struct robot {
    robot_config_t cfg;
    drivetrain_t drivetrain;
    body_state_t body;
    struct hal_port hal;
    sact_board_t sact;
    ins_board_t ins;
    sonar_board_t sonar;
    landmark_board_t landmark;   /* sees the world's ceiling markers (none without a world) */
    battery_t battery;
    power_board_t power;
    const arena_t *arena;
    sim_rng_t noise_rng, fault_rng;
    uint64_t now_us;
    uint32_t char_us;

    /* RS-485 line: bytes in flight toward the boards */
    uint8_t rx_byte[BUS_RX_QUEUE];
    uint64_t rx_time[BUS_RX_QUEUE];
    unsigned rx_head, rx_tail;
    uint64_t line_free_us;   /* when the last queued byte has been received */
    uint64_t frame_end_us;   /* when the boards see the end of the frame on the line (0: none pending) */
    int master_port;         /* transport that sent the last request */
    bus_frame_t tx[BUS_TX_QUEUE];
    unsigned tx_count;
    uint64_t answers_dropped, answers_corrupted, rx_overflows;
    /* A board whose RS-485 link is cut: it neither hears the line nor answers, but
     * its firmware keeps running (the SACT deadman still acts). */
    bool link_cut[BOARD_COUNT];
};

void robot_init(robot_t *r, const robot_config_t *cfg, const arena_t *arena);

/* One control period: firmware interrupt, physics, sensors, bus. */
void robot_step(robot_t *r);

/* Bytes a master wrote, from transport `port`. Returns the number accepted. */
size_t robot_bus_write(robot_t *r, int port, const uint8_t *bytes, size_t len);

/* Moves the next answer whose transmission has completed into *out; false if none. */
bool robot_bus_take(robot_t *r, bus_frame_t *out);

/* Time until the next answer is due (UINT64_MAX when none). */
uint64_t robot_bus_next_due(const robot_t *r);

/* The next simulated time at which the bus needs a step: the end of a request (3.5 characters of silence
 * after its last byte, when the boards answer) or an answer due (UINT64_MAX when the line is idle). */
uint64_t robot_bus_next_event(const robot_t *r);

#endif
