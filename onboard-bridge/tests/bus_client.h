/*
 * Test-side Modbus master: builds file-record requests byte by byte (independently
 * of the slave code) and exchanges them with a simulated robot's RS-485 bus.
 */
#ifndef TESTS_BUS_CLIENT_H
#define TESTS_BUS_CLIENT_H

#include <stdlib.h>
#include <string.h>

#include "robot.h"

typedef struct {
    uint8_t data[MB_ADU_MAX + 8];
    size_t len;
} frame_t;

/* Bit-by-bit CRC-16/MODBUS, written again here so a slave bug cannot hide in it. */
static inline uint16_t test_crc(const uint8_t *d, size_t n)
{
    uint16_t crc = 0xFFFF;
    for (size_t i = 0; i < n; i++) {
        crc ^= d[i];
        for (int b = 0; b < 8; b++)
            crc = (crc & 1) ? (uint16_t)((crc >> 1) ^ 0xA001) : (uint16_t)(crc >> 1);
    }
    return crc;
}

static inline void frame_put(frame_t *f, uint8_t b) { f->data[f->len++] = b; }
static inline void frame_put16(frame_t *f, uint16_t v)
{
    frame_put(f, (uint8_t)(v >> 8));
    frame_put(f, (uint8_t)v);
}
static inline void frame_seal(frame_t *f)
{
    uint16_t c = test_crc(f->data, f->len);
    frame_put(f, (uint8_t)c);
    frame_put(f, (uint8_t)(c >> 8));
}

static inline frame_t read_request(uint8_t address, uint16_t file, uint16_t record, uint16_t count)
{
    frame_t f = { .len = 0 };
    frame_put(&f, address);
    frame_put(&f, 0x14);
    frame_put(&f, 7);
    frame_put(&f, 6);
    frame_put16(&f, file);
    frame_put16(&f, record);
    frame_put16(&f, count);
    frame_seal(&f);
    return f;
}

static inline frame_t write_request(uint8_t address, uint16_t file, uint16_t record, const uint16_t *values,
                                    uint16_t count)
{
    frame_t f = { .len = 0 };
    frame_put(&f, address);
    frame_put(&f, 0x15);
    frame_put(&f, (uint8_t)(7 + 2 * count));
    frame_put(&f, 6);
    frame_put16(&f, file);
    frame_put16(&f, record);
    frame_put16(&f, count);
    for (uint16_t i = 0; i < count; i++)
        frame_put16(&f, values[i]);
    frame_seal(&f);
    return f;
}

/* Sends raw bytes and runs the robot until an answer has been transmitted, or 30 ms
 * after the request's last byte (silence). Returns the answer length (0 = silence). */
static inline size_t transact_raw(robot_t *r, const uint8_t *bytes, size_t len, frame_t *answer)
{
    robot_bus_write(r, 0, bytes, len);
    int steps = (int)((len * r->char_us + 30000u) / SACT_TS_US);
    for (int i = 0; i < steps; i++) {
        robot_step(r);
        bus_frame_t f;
        if (robot_bus_take(r, &f)) {
            memcpy(answer->data, f.data, f.len);
            answer->len = f.len;
            return f.len;
        }
    }
    answer->len = 0;
    return 0;
}

static inline size_t transact(robot_t *r, const frame_t *req, frame_t *answer)
{
    return transact_raw(r, req->data, req->len, answer);
}

/* Exception code of an answer, 0 for a normal answer, -1 for silence or a bad CRC. */
static inline int answer_exception(const frame_t *a)
{
    if (a->len < 4 || test_crc(a->data, a->len - 2) != (uint16_t)(a->data[a->len - 2] | a->data[a->len - 1] << 8))
        return -1;
    return (a->data[1] & 0x80) ? a->data[2] : 0;
}

/* Reads one register through the bus; returns -1 on any failure. */
static inline long bus_read(robot_t *r, uint8_t address, uint16_t file, uint16_t record)
{
    frame_t req = read_request(address, file, record, 1), ans;
    if (transact(r, &req, &ans) == 0 || answer_exception(&ans) != 0 || ans.len != 9)
        return -1;
    return (ans.data[5] << 8) | ans.data[6];
}

/* Writes one register through the bus; returns the exception code (0 = done, -1 silence). */
static inline int bus_write(robot_t *r, uint8_t address, uint16_t file, uint16_t record, uint16_t value)
{
    frame_t req = write_request(address, file, record, &value, 1), ans;
    transact(r, &req, &ans);
    return answer_exception(&ans);
}

/* A robot on an empty floor (no map), fresh state. */
static inline robot_t *make_robot(uint64_t seed, arena_t *arena, robot_t **slot)
{
    robot_t *r = calloc(1, sizeof *r);
    robot_config_t c;
    robot_config_default(&c);
    c.seed = seed;
    *slot = r;
    arena->world = NULL;
    arena->robots = slot;
    arena->n_robots = 1;
    robot_init(r, &c, arena);
    return r;
}

#endif
