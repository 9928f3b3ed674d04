/*
 * The register map file is the contract: this suite reads docs/sact-modbus-map.json
 * itself and checks that the boards serve exactly what it says: every record, its
 * access, bounds and default, and the limits derived from the configuration. Defaults
 * given as "default_from" are read from docs/sabot-robot.properties here too.
 */
#include <math.h>

#include "bus_client.h"
#include "check.h"
#include "json_mini.h"

#ifndef MAP_JSON
#define MAP_JSON "../docs/sact-modbus-map.json"
#endif
#define ROBOT_PROPERTIES "../docs/sabot-robot.properties"
#define MAP_DOC "../docs/SACT-MODBUS.md"

static json_t *doc;
static arena_t arena;
static robot_t *slot;

static robot_t *fresh(void)
{
    free(slot);
    return make_robot(11, &arena, &slot);
}

static const mb_board_desc_t *board_desc(const char *name)
{
    if (!strcmp(name, "sact")) return &mb_sact_board;
    if (!strcmp(name, "ins")) return &mb_ins_board;
    if (!strcmp(name, "sonar")) return &mb_sonar_board;
    if (!strcmp(name, "landmark")) return &mb_landmark_board;
    if (!strcmp(name, "power")) return &mb_power_board;
    return NULL;
}

static const json_t *file_records(const json_t *board, const json_t *file)
{
    const char *tmpl = json_str(file, "template");
    return *tmpl ? json_get(json_get(board, "templates"), tmpl) : json_get(file, "records");
}

static int words_of(const json_t *rec)
{
    const char *t = json_str(rec, "type");
    int words = (!strcmp(t, "int32") || !strcmp(t, "uint32")) ? 2 : 1;
    return words * (int)json_num(rec, "count", 1);
}

/* Calls fn for every record of every file of every board in the JSON map. */
typedef void (*record_fn)(const json_t *board, const json_t *file, const json_t *rec);
static void each_record(record_fn fn)
{
    const json_t *boards = json_get(doc, "boards");
    for (int b = 0; boards && b < boards->count; b++) {
        const json_t *files = json_get(boards->items[b], "files");
        for (int f = 0; files && f < files->count; f++) {
            const json_t *recs = file_records(boards->items[b], files->items[f]);
            for (int r = 0; recs && r < recs->count; r++)
                fn(boards->items[b], files->items[f], recs->items[r]);
        }
    }
}

/* A key's number in the robot description (key = value lines, # comments); NAN if absent. */
static double robot_value(const char *key)
{
    FILE *f = fopen(ROBOT_PROPERTIES, "r");
    char line[512];
    double value = NAN;
    while (f && fgets(line, sizeof line, f)) {
        char k[128];
        double v;
        if (line[0] != '#' && sscanf(line, " %127[A-Za-z0-9_.] = %lf", k, &v) == 2 && !strcmp(k, key))
            value = v;
    }
    if (f)
        fclose(f);
    return value;
}

/* A record's power-on value: "default", or the robot description's value x factor. */
static long default_of(const json_t *rec)
{
    const json_t *from = json_get(rec, "default_from");
    if (!from)
        return (long)json_num(rec, "default", 0);
    return lround(robot_value(json_str(from, "robot")) * json_num(from, "factor", NAN));
}

static int robot_records;

static void check_robot_record(const json_t *board, const json_t *file, const json_t *rec)
{
    static const char *const robot_constants[] = { "encoder_lines", "gear_ratio", "no_load_speed",
                                                   "wheel_radius",  "max_speed",  "max_accel" };
    if (strcmp(json_str(board, "name"), "sact") || strcmp(json_str(file, "name"), "config"))
        return;
    for (size_t i = 0; i < sizeof robot_constants / sizeof robot_constants[0]; i++) {
        if (strcmp(json_str(rec, "name"), robot_constants[i]))
            continue;
        robot_records++;
        const json_t *from = json_get(rec, "default_from");
        CHECK(from && !json_get(rec, "default"), "%s repeats a number instead of naming a robot key",
              robot_constants[i]);
        CHECK(from && !isnan(robot_value(json_str(from, "robot"))), "%s: key '%s' not in %s", robot_constants[i],
              from ? json_str(from, "robot") : "", ROBOT_PROPERTIES);
    }
}

static void robotConstantsComeFromTheRobotDescription(void)
{
    robot_records = 0;
    each_record(check_robot_record);
    CHECK(robot_records == 6, "%d of the 6 robot constants found in the config file", robot_records);
    CHECK(MB_SACT_CONFIG_GEAR_RATIO_DEFAULT == lround(SABOT_ROBOT_GEAR_RATIO * 100), "gear ratio %d",
          MB_SACT_CONFIG_GEAR_RATIO_DEFAULT);
    CHECK(MB_SACT_CONFIG_NO_LOAD_SPEED_DEFAULT == lround(robot_value("motor.noLoadSpeed.rpm")), "no-load %d",
          MB_SACT_CONFIG_NO_LOAD_SPEED_DEFAULT);
}

static int json_records;

static void check_descriptor(const json_t *board, const json_t *file, const json_t *rec)
{
    const mb_board_desc_t *bd = board_desc(json_str(board, "name"));
    uint16_t fnum = (uint16_t)json_num(file, "file", 0), rnum = (uint16_t)json_num(rec, "record", 0);
    const mb_record_desc_t *d = bd ? mb_map_find(bd, fnum, rnum) : NULL;
    json_records++;
    CHECK(d != NULL, "%s file %u record %u (%s) missing", json_str(board, "name"), fnum, rnum, json_str(rec, "name"));
    if (!d)
        return;
    const char *acc = json_str(rec, "access");
    int access = (strchr(acc, 'r') ? MB_ACCESS_R : 0) | (strchr(acc, 'w') ? MB_ACCESS_W : 0);
    CHECK(d->record == rnum && d->words == words_of(rec), "%s span", json_str(rec, "name"));
    CHECK(d->access == access, "%s access", json_str(rec, "name"));
    CHECK(d->min == (int32_t)json_num(rec, "min", 0) && d->max == (int32_t)json_num(rec, "max", 0), "%s bounds",
          json_str(rec, "name"));
    CHECK(d->def == (int32_t)default_of(rec), "%s default", json_str(rec, "name"));
    CHECK(bd->address == (uint8_t)json_num(board, "slave_address", 0), "%s address", json_str(board, "name"));
}

static void everyRecordOfTheMapIsServedAsDescribed(void)
{
    json_records = 0;
    each_record(check_descriptor);
    int c_records = 0;
    const mb_board_desc_t *all[] = { &mb_sact_board, &mb_ins_board, &mb_sonar_board, &mb_landmark_board,
                                     &mb_power_board };
    for (int b = 0; b < 5; b++)
        for (int f = 0; f < all[b]->n_files; f++)
            c_records += all[b]->files[f].n_records;
    CHECK(json_records == c_records, "JSON has %d records, firmware %d", json_records, c_records);
    CHECK(json_records > 40, "only %d records", json_records);
}

static void check_default_over_bus(const json_t *board, const json_t *file, const json_t *rec)
{
    /* flag registers ("bits") report live state, not a stored default */
    if (strcmp(json_str(rec, "access"), "rw") || words_of(rec) != 1 || json_get(rec, "bits"))
        return;
    robot_t *r = slot;
    uint8_t addr = (uint8_t)json_num(board, "slave_address", 0);
    long v = bus_read(r, addr, (uint16_t)json_num(file, "file", 0), (uint16_t)json_num(rec, "record", 0));
    long expect = default_of(rec);
    if (!strcmp(json_str(rec, "type"), "int16") && v >= 0x8000)
        v -= 0x10000;
    CHECK(v == expect, "%s.%s.%s reads %ld, map default %ld", json_str(board, "name"), json_str(file, "name"),
          json_str(rec, "name"), v, expect);
}

static void writableRecordsStartAtTheMapDefaults(void)
{
    fresh();
    each_record(check_default_over_bus);
}

/* The limit a board derives for records with "max_from", from the map's defaults. */
static double dynamic_limit(const char *from)
{
    const json_t *boards = json_get(doc, "boards");
    const json_t *cfg = NULL;
    for (int f = 0; f < json_get(boards->items[0], "files")->count; f++)
        if (!strcmp(json_str(json_get(boards->items[0], "files")->items[f], "name"), "config"))
            cfg = json_get(json_get(boards->items[0], "files")->items[f], "records");
    double val[16] = { 0 };
    for (int i = 0; i < cfg->count && i < 16; i++)
        val[i] = (double)default_of(cfg->items[i]);
    double counts_per_m = 4 * val[0] * val[1] / 100.0 / (2 * M_PI * val[3] * 1e-4);
    double ts = json_num(json_get(doc, "control"), "period_us", 0) * 1e-6;
    if (!strcmp(from, "max_speed"))
        return floor(val[4] * 1e-3 * counts_per_m * ts * 256 + 0.5);
    return floor(val[5] * 1e-3 * counts_per_m * ts * ts * 16777216.0);
}

static void check_write_bounds(const json_t *board, const json_t *file, const json_t *rec)
{
    uint8_t addr = (uint8_t)json_num(board, "slave_address", 0);
    uint16_t fnum = (uint16_t)json_num(file, "file", 0), rnum = (uint16_t)json_num(rec, "record", 0);
    const char *name = json_str(rec, "name");
    bool is_signed = !strcmp(json_str(rec, "type"), "int16");
    long lo = (long)json_num(rec, "min", 0), hi = (long)json_num(rec, "max", 0);
    if (!strchr(json_str(rec, "access"), 'w')) {
        robot_t *r = fresh();
        CHECK(bus_write(r, addr, fnum, rnum, 1) == MB_EXC_ILLEGAL_DATA_ADDRESS, "read-only %s accepted a write", name);
        return;
    }
    const char *from = json_str(rec, "max_from");
    if (*from) {
        hi = (long)dynamic_limit(from);
        if (lo < 0)
            lo = -hi;
    }
    const long type_lo = is_signed ? -32768 : 0, type_hi = is_signed ? 32767 : 65535;
    long probes[4] = { lo, hi, lo - 1, hi + 1 };
    for (int k = 0; k < 4; k++) {
        if (probes[k] < type_lo || probes[k] > type_hi)
            continue;   /* not expressible on the wire */
        robot_t *r = fresh();
        long before = bus_read(r, addr, fnum, rnum);
        int e = bus_write(r, addr, fnum, rnum, (uint16_t)probes[k]);
        long after = bus_read(r, addr, fnum, rnum);
        if (k < 2) {
            CHECK(e == 0, "%s = %ld rejected with %d", name, probes[k], e);
        } else {
            CHECK(e == MB_EXC_ILLEGAL_DATA_VALUE, "%s = %ld answered %d", name, probes[k], e);
            CHECK(after == before, "%s changed by a rejected write", name);
        }
    }
}

static void writesAreBoundedExactlyByTheMap(void) { each_record(check_write_bounds); }

static void velocityLimitFollowsTheConfiguration(void)
{
    robot_t *r = fresh();
    CHECK(r->sact.max_velocity_setpoint == (int32_t)dynamic_limit("max_speed"), "speed limit %d vs %g",
          r->sact.max_velocity_setpoint, dynamic_limit("max_speed"));
    CHECK(abs(r->sact.max_acceleration - (int32_t)dynamic_limit("max_accel")) <= 1, "accel limit %d vs %g",
          r->sact.max_acceleration, dynamic_limit("max_accel"));
}

static char *map_doc;
static int doc_rows;

/* A landmark or power record's row of its board's table in docs/SACT-MODBUS.md: "| file | rec | name | type | access | unit |
 * meaning |", and for a writable record its bounds and default in the meaning. */
static void check_doc_row(const json_t *board, const json_t *file, const json_t *rec)
{
    if (strcmp(json_str(board, "name"), "landmark") && strcmp(json_str(board, "name"), "power"))
        return;
    char row[160];
    snprintf(row, sizeof row, "\n| %ld | %ld | %s | %s | %s |", (long)json_num(file, "file", 0),
             (long)json_num(rec, "record", 0), json_str(rec, "name"), json_str(rec, "type"), json_str(rec, "access"));
    const char *at = map_doc ? strstr(map_doc, row) : NULL;
    doc_rows++;
    CHECK(at != NULL, "%s has no row '%s'", MAP_DOC, row + 1);
    if (!at || !strchr(json_str(rec, "access"), 'w'))
        return;
    const char *end = strchr(at + 1, '\n');
    char bounds[96];
    snprintf(bounds, sizeof bounds, "%ld–%ld, default %ld", (long)json_num(rec, "min", 0),
             (long)json_num(rec, "max", 0), default_of(rec));
    const char *b = strstr(at, bounds);
    CHECK(b && (!end || b < end), "%s row of %s does not say '%s'", MAP_DOC, json_str(rec, "name"), bounds);
}

static void theLandmarkAndPowerTablesOfTheDocumentAreTheMaps(void)
{
    FILE *f = fopen(MAP_DOC, "rb");
    CHECK(f != NULL, "cannot read %s", MAP_DOC);
    if (!f)
        return;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    map_doc = calloc(1, (size_t)n + 1);
    CHECK(fread(map_doc, 1, (size_t)n, f) == (size_t)n, "short read");
    fclose(f);
    doc_rows = 0;
    each_record(check_doc_row);
    CHECK(doc_rows == 14, "%d landmark and power records in the map", doc_rows);
    free(map_doc);
    map_doc = NULL;
}

int main(void)
{
    printf("test_map (%s)\n", MAP_JSON);
    doc = json_load(MAP_JSON);
    if (!doc) {
        printf("test_map: 0 passed, 1 failed\n");
        return 1;
    }
    RUN(robotConstantsComeFromTheRobotDescription);
    RUN(everyRecordOfTheMapIsServedAsDescribed);
    RUN(writableRecordsStartAtTheMapDefaults);
    RUN(writesAreBoundedExactlyByTheMap);
    RUN(velocityLimitFollowsTheConfiguration);
    RUN(theLandmarkAndPowerTablesOfTheDocumentAreTheMaps);
    json_free(doc);
    free(slot);
    return REPORT("test_map");
}
