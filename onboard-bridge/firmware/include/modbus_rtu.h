/*
 * Modbus RTU slave for file-record access (function codes 0x14 and 0x15).
 *
 * Follows "MODBUS Application Protocol Specification V1.1b3" (sections 6.14, 6.15, 7)
 * and "MODBUS over Serial Line V1.02" (2.5.1 RTU framing, 6.2.2 CRC):
 *  - a frame ends after 3.5 character times of silence (fixed 1750 us above 19200
 *    baud); a gap of more than 1.5 characters inside a frame makes it invalid;
 *  - frames with a wrong CRC, shorter than 4 bytes or for another address are
 *    dropped silently; address 0 is a broadcast: writes act, nothing is answered,
 *    reads are ignored (the spec allows broadcast for writes only);
 *  - the exception response is the function code | 0x80 plus one code byte.
 * Writes are validated in full (every sub-request, every value) before the first
 * register changes, so a rejected request leaves the board as it was.
 *
 * The receiver has no heap and no OS: the UART interrupt calls mb_slave_on_byte(),
 * the main loop calls mb_slave_poll() and sends what it returns.
 */
#ifndef MODBUS_RTU_H
#define MODBUS_RTU_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modbus_map.h"

#define MB_ADU_MAX 256   /* address + PDU (253) + CRC */

typedef enum {
    MB_OK = 0,
    MB_ILLEGAL_FUNCTION = MB_EXC_ILLEGAL_FUNCTION,
    MB_ILLEGAL_DATA_ADDRESS = MB_EXC_ILLEGAL_DATA_ADDRESS,
    MB_ILLEGAL_DATA_VALUE = MB_EXC_ILLEGAL_DATA_VALUE,
    MB_SERVER_DEVICE_FAILURE = MB_EXC_SERVER_DEVICE_FAILURE
} mb_exception_t;

/* What a board provides on top of the generic range checks of its descriptors. */
typedef struct {
    /* Current value of one register; never fails for a register the map defines. */
    uint16_t (*read)(void *board, uint16_t file, uint16_t record);
    /* Board rules beyond the static bounds: dynamic limits, state (e.g. fault latched). */
    mb_exception_t (*check_write)(void *board, uint16_t file, uint16_t record, uint16_t value);
    void (*write)(void *board, uint16_t file, uint16_t record, uint16_t value);
    /* Bracket the reads of one sub-request and the commit of a validated write, so the
     * control interrupt never sees half a request nor tears a 32-bit value (optional). */
    void (*lock)(void *board);
    void (*unlock)(void *board);
    /* Called once at the start of every write request (0x15), before its first check_write:
     * a board that gives requests an idempotency key resets its per-request state (optional). */
    void (*begin_write)(void *board);
} mb_board_ops_t;

typedef struct {
    uint32_t frames;        /* complete frames seen on the line */
    uint32_t crc_errors;
    uint32_t timing_errors; /* frames broken by an inter-character gap > 1.5 chars */
    uint32_t overruns;      /* frames longer than 256 bytes */
    uint32_t requests;      /* frames addressed to this board or broadcast */
    uint32_t exceptions;
} mb_stats_t;

typedef struct {
    const mb_board_desc_t *map;
    const mb_board_ops_t *ops;
    void *board;
    uint32_t t15_us, t35_us;

    /* receiver state, shared with the UART interrupt */
    uint8_t rx[MB_ADU_MAX];
    uint16_t rx_len;
    bool rx_broken;         /* gap > t1.5 or overrun: discard at the end of the frame */
    uint32_t last_byte_us;

    uint8_t tx[MB_ADU_MAX];
    mb_stats_t stats;
} mb_slave_t;

uint16_t mb_crc16(const uint8_t *data, size_t len);

/* baud sets the character timing; above 19200 the spec's fixed 750/1750 us apply. */
void mb_slave_init(mb_slave_t *s, const mb_board_desc_t *map, const mb_board_ops_t *ops,
                   void *board, uint32_t baud);

/* UART receive interrupt: one byte and the timer value when it arrived. */
void mb_slave_on_byte(mb_slave_t *s, uint8_t byte, uint32_t now_us);

/* Main loop: when 3.5 characters of silence close a frame, handles it. Returns the
 * length of the response in s->tx (0 = nothing to send). */
size_t mb_slave_poll(mb_slave_t *s, uint32_t now_us);

/* Handles one complete ADU (address .. CRC). Returns the response length written to
 * resp (0 = stay silent). Pure with respect to timing: the unit tests and the fuzzer
 * call it directly. */
size_t mb_slave_handle_frame(mb_slave_t *s, const uint8_t *adu, size_t len, uint8_t *resp);

#endif
