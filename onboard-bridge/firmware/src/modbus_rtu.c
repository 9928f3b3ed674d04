#include "modbus_rtu.h"

#include <string.h>

/* Sub-request layout (spec 6.14/6.15): reference type, file (2), record (2), length (2). */
#define SUBREQ_HEADER 7u
#define PDU_MAX 253u
/* Byte-count limits of the request, spec 6.14 (0x07..0xF5) and 6.15 (0x09..0xFB). */
#define READ_BYTES_MIN 0x07u
#define READ_BYTES_MAX 0xF5u
#define WRITE_BYTES_MIN 0x09u
#define WRITE_BYTES_MAX 0xFBu

static uint16_t get_u16(const uint8_t *p) { return (uint16_t)((p[0] << 8) | p[1]); }

static void put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v >> 8);
    p[1] = (uint8_t)v;
}

/* CRC-16/MODBUS: polynomial 0xA001 (reflected 0x8005), init 0xFFFF, sent low byte first. */
uint16_t mb_crc16(const uint8_t *data, size_t len)
{
    uint16_t crc = 0xFFFFu;
    for (size_t i = 0; i < len; i++) {
        crc ^= data[i];
        for (int bit = 0; bit < 8; bit++)
            crc = (crc & 1u) ? (uint16_t)((crc >> 1) ^ 0xA001u) : (uint16_t)(crc >> 1);
    }
    return crc;
}

const mb_record_desc_t *mb_map_find(const mb_board_desc_t *board, uint16_t file, uint16_t record)
{
    for (unsigned f = 0; f < board->n_files; f++) {
        const mb_file_desc_t *fd = &board->files[f];
        if (fd->file != file)
            continue;
        for (unsigned r = 0; r < fd->n_records; r++) {
            const mb_record_desc_t *d = &fd->records[r];
            if (record >= d->record && record < d->record + d->words)
                return d;
        }
        return NULL;
    }
    return NULL;
}

void mb_slave_init(mb_slave_t *s, const mb_board_desc_t *map, const mb_board_ops_t *ops,
                   void *board, uint32_t baud)
{
    memset(s, 0, sizeof *s);
    s->map = map;
    s->ops = ops;
    s->board = board;
    if (baud > 19200u || baud == 0) {
        /* Serial line spec 2.5.1.1: fixed timers above 19200 baud. */
        s->t15_us = MB_SERIAL_T1_5_US;
        s->t35_us = MB_SERIAL_T3_5_US;
    } else {
        /* 11 bits per character (start, 8 data, parity or 2nd stop, stop). */
        uint32_t char_us = (11u * 1000000u + baud - 1u) / baud;
        s->t15_us = (3u * char_us + 1u) / 2u;
        s->t35_us = (7u * char_us + 1u) / 2u;
    }
}

void mb_slave_on_byte(mb_slave_t *s, uint8_t byte, uint32_t now_us)
{
    if (s->rx_len > 0) {
        uint32_t gap = now_us - s->last_byte_us;
        if (gap >= s->t35_us) {
            /* The main loop missed the end of the previous frame: drop it rather than
             * answer late, since the master has moved on. */
            s->rx_len = 0;
            s->rx_broken = false;
        } else if (gap > s->t15_us) {
            s->rx_broken = true;
        }
    }
    s->last_byte_us = now_us;
    if (s->rx_len < MB_ADU_MAX)
        s->rx[s->rx_len++] = byte;
    else
        s->rx_broken = true;
}

size_t mb_slave_poll(mb_slave_t *s, uint32_t now_us)
{
    if (s->rx_len == 0 || now_us - s->last_byte_us < s->t35_us)
        return 0;
    size_t len = s->rx_len;
    bool broken = s->rx_broken;
    s->rx_len = 0;
    s->rx_broken = false;
    s->stats.frames++;
    if (broken) {
        if (len >= MB_ADU_MAX)
            s->stats.overruns++;
        else
            s->stats.timing_errors++;
        return 0;
    }
    return mb_slave_handle_frame(s, s->rx, len, s->tx);
}

static size_t exception(mb_slave_t *s, uint8_t *resp, uint8_t function, mb_exception_t code)
{
    s->stats.exceptions++;
    resp[1] = (uint8_t)(function | 0x80u);
    resp[2] = (uint8_t)code;
    return 3;
}

/* Checks the reference type and that every register of the span exists. */
static mb_exception_t check_span(const mb_slave_t *s, const uint8_t *sub, uint16_t *file,
                                 uint16_t *record, uint16_t *count)
{
    *file = get_u16(sub + 1);
    *record = get_u16(sub + 3);
    *count = get_u16(sub + 5);
    if (sub[0] != MB_REFERENCE_TYPE || *file == 0 || *count == 0 ||
        *record > MB_MAX_RECORD_NUMBER || (uint32_t)*record + *count - 1u > MB_MAX_RECORD_NUMBER)
        return MB_ILLEGAL_DATA_ADDRESS;
    uint32_t end = (uint32_t)*record + *count;
    for (uint32_t r = *record; r < end;) {
        const mb_record_desc_t *d = mb_map_find(s->map, *file, (uint16_t)r);
        if (d == NULL)
            return MB_ILLEGAL_DATA_ADDRESS;
        r = (uint32_t)d->record + d->words;
    }
    return MB_OK;
}

static size_t read_file_record(mb_slave_t *s, const uint8_t *pdu, size_t pdu_len, uint8_t *resp)
{
    if (pdu_len < 2)
        return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_VALUE);
    uint8_t byte_count = pdu[1];
    if (byte_count < READ_BYTES_MIN || byte_count > READ_BYTES_MAX ||
        byte_count % SUBREQ_HEADER != 0 || pdu_len != 2u + byte_count)
        return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_VALUE);

    /* Response PDU: function, length, then per sub-request: length, type 6, data. */
    size_t out = 3;
    for (size_t off = 2; off < pdu_len; off += SUBREQ_HEADER) {
        uint16_t file, record, count;
        mb_exception_t e = check_span(s, pdu + off, &file, &record, &count);
        if (e != MB_OK)
            return exception(s, resp, pdu[0], e);
        /* The answer must fit one PDU: 2 + sum(2 + 2n) <= 253. */
        if ((out - 1u) + 2u + 2u * (size_t)count > PDU_MAX)
            return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_VALUE);
        resp[out++] = (uint8_t)(1u + 2u * count);
        resp[out++] = MB_REFERENCE_TYPE;
        if (s->ops->lock)
            s->ops->lock(s->board);
        for (uint16_t i = 0; i < count; i++, out += 2)
            put_u16(resp + out, s->ops->read(s->board, file, (uint16_t)(record + i)));
        if (s->ops->unlock)
            s->ops->unlock(s->board);
    }
    resp[1] = pdu[0];
    resp[2] = (uint8_t)(out - 3u);
    return out;
}

/* Static bounds of the descriptor, interpreted by the register's type. */
static bool value_in_bounds(const mb_record_desc_t *d, uint16_t raw)
{
    int32_t v = (d->type == MB_T_I16) ? (int32_t)(int16_t)raw : (int32_t)raw;
    return v >= d->min && v <= d->max;
}

static size_t write_file_record(mb_slave_t *s, const uint8_t *pdu, size_t pdu_len, uint8_t *resp)
{
    if (pdu_len < 2)
        return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_VALUE);
    uint8_t byte_count = pdu[1];
    if (byte_count < WRITE_BYTES_MIN || byte_count > WRITE_BYTES_MAX || pdu_len != 2u + byte_count)
        return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_VALUE);

    if (s->ops->begin_write)
        s->ops->begin_write(s->board);
    /* Pass 1: structure, addresses, access rights, values. Nothing changes yet. */
    for (size_t off = 2; off < pdu_len;) {
        if (pdu_len - off < SUBREQ_HEADER)
            return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_VALUE);
        uint16_t count = get_u16(pdu + off + 5);
        if (pdu_len - off - SUBREQ_HEADER < 2u * (size_t)count)
            return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_VALUE);
        uint16_t file, record;
        mb_exception_t e = check_span(s, pdu + off, &file, &record, &count);
        if (e != MB_OK)
            return exception(s, resp, pdu[0], e);
        const uint8_t *data = pdu + off + SUBREQ_HEADER;
        for (uint16_t i = 0; i < count; i++) {
            const mb_record_desc_t *d = mb_map_find(s->map, file, (uint16_t)(record + i));
            if (!(d->access & MB_ACCESS_W))
                return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_ADDRESS);
            uint16_t value = get_u16(data + 2u * i);
            if (!value_in_bounds(d, value))
                return exception(s, resp, pdu[0], MB_ILLEGAL_DATA_VALUE);
            e = s->ops->check_write(s->board, file, (uint16_t)(record + i), value);
            if (e != MB_OK)
                return exception(s, resp, pdu[0], e);
        }
        off += SUBREQ_HEADER + 2u * (size_t)count;
    }

    /* Pass 2: commit, as one critical section so the control loop sees all or nothing. */
    if (s->ops->lock)
        s->ops->lock(s->board);
    for (size_t off = 2; off < pdu_len;) {
        uint16_t file = get_u16(pdu + off + 1), record = get_u16(pdu + off + 3);
        uint16_t count = get_u16(pdu + off + 5);
        for (uint16_t i = 0; i < count; i++)
            s->ops->write(s->board, file, (uint16_t)(record + i),
                          get_u16(pdu + off + SUBREQ_HEADER + 2u * i));
        off += SUBREQ_HEADER + 2u * (size_t)count;
    }
    if (s->ops->unlock)
        s->ops->unlock(s->board);

    /* The normal response echoes the request (spec 6.15). */
    memcpy(resp + 1, pdu, pdu_len);
    return 1u + pdu_len;
}

size_t mb_slave_handle_frame(mb_slave_t *s, const uint8_t *adu, size_t len, uint8_t *resp)
{
    if (len < 4 || len > MB_ADU_MAX)
        return 0;
    uint16_t crc = (uint16_t)(adu[len - 2] | (adu[len - 1] << 8));
    if (mb_crc16(adu, len - 2) != crc) {
        s->stats.crc_errors++;
        return 0;
    }
    uint8_t address = adu[0];
    bool broadcast = address == MB_BROADCAST_ADDRESS;
    if (!broadcast && address != s->map->address)
        return 0;
    s->stats.requests++;

    const uint8_t *pdu = adu + 1;
    size_t pdu_len = len - 3;
    size_t n;
    switch (pdu[0]) {
    case MB_READ_FILE_RECORD:
        if (broadcast)
            return 0;   /* reads cannot be broadcast: ignore */
        n = read_file_record(s, pdu, pdu_len, resp);
        break;
    case MB_WRITE_FILE_RECORD:
        n = write_file_record(s, pdu, pdu_len, resp);
        break;
    default:
        n = exception(s, resp, pdu[0], MB_ILLEGAL_FUNCTION);
        break;
    }
    if (broadcast)
        return 0;
    resp[0] = address;
    uint16_t out_crc = mb_crc16(resp, n);
    resp[n] = (uint8_t)out_crc;
    resp[n + 1] = (uint8_t)(out_crc >> 8);
    return n + 2;
}
