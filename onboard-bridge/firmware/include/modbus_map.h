/*
 * Register-map descriptors shared by every board on the SabotOne RS-485 bus.
 *
 * The tables themselves are generated from docs/sact-modbus-map.json (the one
 * machine-readable map the Java driver reads too); this header only describes
 * their shape. A Modbus "file record" is one 16-bit register: a request names
 * (file, record, length) and the descriptors say which registers exist, who may
 * write them and which values a write may carry.
 */
#ifndef MODBUS_MAP_H
#define MODBUS_MAP_H

#include <stdint.h>

typedef enum { MB_T_U16, MB_T_I16, MB_T_U32, MB_T_I32 } mb_type_t;
typedef enum { MB_ACCESS_R = 1, MB_ACCESS_W = 2, MB_ACCESS_RW = 3 } mb_access_t;

/* Limits a board computes from its own configuration (e.g. max wheel speed). */
typedef enum { MB_LIMIT_NONE, MB_LIMIT_MAX_SPEED, MB_LIMIT_MAX_ACCEL } mb_limit_t;

typedef struct {
    uint16_t record;   /* first record number */
    uint16_t words;    /* registers covered (2 for 32-bit values, count for arrays) */
    uint8_t type;      /* mb_type_t */
    uint8_t access;    /* mb_access_t */
    uint8_t limit;     /* mb_limit_t: dynamic bound on |value| */
    int32_t min, max;  /* static bounds of a written value */
    int32_t def;       /* value after reset */
} mb_record_desc_t;

typedef struct {
    uint16_t file;
    const mb_record_desc_t *records;
    uint8_t n_records;
} mb_file_desc_t;

typedef struct {
    uint8_t address;
    const mb_file_desc_t *files;
    uint8_t n_files;
} mb_board_desc_t;

#include "modbus_map_gen.h"

/* Finds the descriptor covering (file, record); NULL when no register is there. */
const mb_record_desc_t *mb_map_find(const mb_board_desc_t *board, uint16_t file, uint16_t record);

#endif
