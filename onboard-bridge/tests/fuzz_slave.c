/*
 * libFuzzer harness for the SACT Modbus slave (built with ASan + UBSan).
 *
 * The first input byte picks how the rest is delivered:
 *   bit 0 = 0: the bytes are one ADU, handed to mb_slave_handle_frame as they are
 *              (mostly stopped by the CRC check: exercises the framing guards);
 *   bit 0 = 1: the harness addresses the frame to the SACT and appends a correct
 *              CRC, so the function-code, sub-request and value checks are reached;
 *   bit 1 = 1: the bytes go through the interrupt-level receiver instead, with
 *              inter-byte gaps taken from the input, then the main-loop poll.
 * After each request the control loop runs a few samples on whatever the request
 * left behind, so fuzzed parameters reach the arithmetic too.
 * Invariants checked: an answer fits one ADU, carries a correct CRC, echoes the
 * address, and is an exception or the function it answers.
 */
#include <stdlib.h>
#include <string.h>

#include "hal_host.h"
#include "sact.h"

static struct hal_port port;
static sact_board_t board;

static void check_answer(const uint8_t *a, size_t n)
{
    if (n == 0)
        return;
    if (n < 5 || n > MB_ADU_MAX)
        __builtin_trap();
    uint16_t crc = mb_crc16(a, n - 2);
    if (a[n - 2] != (uint8_t)crc || a[n - 1] != (uint8_t)(crc >> 8))
        __builtin_trap();
    if (a[0] != MB_SACT_ADDRESS)
        __builtin_trap();
    if ((a[1] & 0x7F) != 0x14 && (a[1] & 0x7F) != 0x15 && !(a[1] & 0x80))
        __builtin_trap();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    memset(&port, 0, sizeof port);
    port.adc_current[0] = port.adc_current[1] = SACT_ADC_ZERO;
    sact_init(&board, &port, 115200);
    uint8_t mode = data[0];
    data++;
    size--;

    uint8_t frame[MB_ADU_MAX + 2], answer[MB_ADU_MAX];
    size_t n = size > MB_ADU_MAX - 2 ? MB_ADU_MAX - 2 : size;
    memcpy(frame, data, n);
    if (mode & 1) {
        if (n < 2)
            return 0;
        frame[0] = MB_SACT_ADDRESS;
        uint16_t crc = mb_crc16(frame, n);
        frame[n++] = (uint8_t)crc;
        frame[n++] = (uint8_t)(crc >> 8);
    }

    size_t out;
    if (mode & 2) {
        /* receiver path: gaps of 0..255 us x 8 from a second stream of the input */
        uint32_t t = 100;
        for (size_t i = 0; i < n; i++) {
            t += (uint32_t)(data[(i * 7) % (size ? size : 1)] & 0x3F) * 8u;
            mb_slave_on_byte(&board.modbus, frame[i], t);
        }
        out = mb_slave_poll(&board.modbus, t + 2000);
        check_answer(board.modbus.tx, out);
    } else {
        out = mb_slave_handle_frame(&board.modbus, frame, n, answer);
        check_answer(answer, out);
    }
    for (int i = 0; i < 64; i++) {
        port.encoder[0] = (uint16_t)(port.encoder[0] + (i & 3));
        port.encoder[1] = (uint16_t)(port.encoder[1] - (i & 1));
        sact_control_isr(&board);
        port.time_us += SACT_TS_US;
        sact_poll(&board);
    }
    return 0;
}
