/*
 * Modbus RTU slave: framing, CRC, addressing and every exception path of 0x14/0x15,
 * exercised through the simulated RS-485 bus exactly as a master would.
 */
#include "bus_client.h"
#include "check.h"

#define SACT MB_SACT_ADDRESS
#define LEFT MB_SACT_FILE_MOTOR_LEFT
#define RIGHT MB_SACT_FILE_MOTOR_RIGHT

static arena_t arena;
static robot_t *slot;

static robot_t *fresh(void)
{
    free(slot);
    return make_robot(1, &arena, &slot);
}

/* A snapshot of every register a master can write, to prove "state unchanged". */
static void snapshot(robot_t *r, uint16_t *out)
{
    int k = 0;
    memset(out, 0, 80 * sizeof *out);
    for (uint16_t file = 1; file <= 4; file++) {
        for (uint16_t rec = 0; rec < 20; rec++) {
            const mb_record_desc_t *d = mb_map_find(&mb_sact_board, file, rec);
            /* status carries live flags besides the latched ones: not a parameter */
            if (d && (d->access & MB_ACCESS_W) && !(file <= 2 && rec == MB_SACT_MOTOR_STATUS))
                out[k++] = sact_read_register(&r->sact, file, rec);
        }
    }
}

static void crcMatchesPublishedVector(void)
{
    /* Modbus over serial line V1.02, appendix B example: 01 03 00 00 00 0A -> C5 CD */
    const uint8_t frame[] = { 0x01, 0x03, 0x00, 0x00, 0x00, 0x0A };
    CHECK(mb_crc16(frame, sizeof frame) == 0xCDC5, "crc %04x", mb_crc16(frame, sizeof frame));
}

static void readReturnsConfigurationDefaults(void)
{
    robot_t *r = fresh();
    frame_t req = read_request(SACT, MB_SACT_FILE_CONFIG, 0, 9), a;
    CHECK(transact(r, &req, &a) == 5 + 18 + 2, "len %zu", a.len);
    CHECK(a.data[0] == SACT && a.data[1] == 0x14, "header %02x %02x", a.data[0], a.data[1]);
    CHECK(a.data[2] == 20 && a.data[3] == 19 && a.data[4] == 6, "lengths %d %d %d", a.data[2], a.data[3], a.data[4]);
    CHECK(((a.data[5] << 8) | a.data[6]) == 512, "encoder lines");
    CHECK(((a.data[7] << 8) | a.data[8]) == 4300, "gear ratio");
}

static void readSeveralSubRequestsInOneFrame(void)
{
    robot_t *r = fresh();
    frame_t f = { .len = 0 };
    frame_put(&f, SACT);
    frame_put(&f, 0x14);
    frame_put(&f, 14);
    frame_put(&f, 6); frame_put16(&f, LEFT); frame_put16(&f, MB_SACT_MOTOR_KP); frame_put16(&f, 3);
    frame_put(&f, 6); frame_put16(&f, MB_SACT_FILE_CONFIG); frame_put16(&f, 6); frame_put16(&f, 1);
    frame_seal(&f);
    frame_t a;
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == 0, "exception %d", answer_exception(&a));
    CHECK(a.data[2] == 2 + 6 + 2 + 2, "response length %d", a.data[2]);
    CHECK(a.data[3] == 7 && a.data[4] == 6, "first sub-response header");
    CHECK(((a.data[5] << 8) | a.data[6]) == MB_SACT_MOTOR_KP_DEFAULT, "kp");
    CHECK(a.data[11] == 3 && a.data[12] == 6, "second sub-response header");
    CHECK(((a.data[13] << 8) | a.data[14]) == 50, "control period");
}

static void writeIsEchoedAndApplied(void)
{
    robot_t *r = fresh();
    uint16_t v = 300;
    frame_t req = write_request(SACT, LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, &v, 1), a;
    transact(r, &req, &a);
    CHECK(a.len == req.len && memcmp(a.data, req.data, req.len) == 0, "echo differs (len %zu)", a.len);
    CHECK(r->sact.motor[0].velocity_setpoint == 300, "set-point %d", r->sact.motor[0].velocity_setpoint);
}

static void unknownFunctionIsIllegalFunction(void)
{
    robot_t *r = fresh();
    frame_t f = { .len = 0 };
    frame_put(&f, SACT);
    frame_put(&f, 0x03);   /* read holding registers: not offered */
    frame_put16(&f, 0);
    frame_put16(&f, 1);
    frame_seal(&f);
    frame_t a;
    transact(r, &f, &a);
    CHECK(a.len == 5 && a.data[1] == 0x83 && answer_exception(&a) == MB_EXC_ILLEGAL_FUNCTION, "answer %02x %d",
          a.data[1], answer_exception(&a));
}

static int raw_read_exception(robot_t *r, uint8_t byte_count, const uint8_t *body, size_t body_len)
{
    frame_t f = { .len = 0 }, a;
    frame_put(&f, SACT);
    frame_put(&f, 0x14);
    frame_put(&f, byte_count);
    for (size_t i = 0; i < body_len; i++)
        frame_put(&f, body[i]);
    frame_seal(&f);
    transact(r, &f, &a);
    return answer_exception(&a);
}

static void readByteCountOutOfRangeIsIllegalValue(void)
{
    robot_t *r = fresh();
    uint8_t sub[14] = { 6, 0, 1, 0, 0, 0, 1, 6, 0, 1, 0, 0, 0, 1 };
    CHECK(raw_read_exception(r, 6, sub, 6) == MB_EXC_ILLEGAL_DATA_VALUE, "byte count 6");
    CHECK(raw_read_exception(r, 8, sub, 8) == MB_EXC_ILLEGAL_DATA_VALUE, "not a multiple of 7");
    CHECK(raw_read_exception(r, 14, sub, 7) == MB_EXC_ILLEGAL_DATA_VALUE, "count says 14, 7 sent");
    uint8_t big[0xF7] = { 0 };   /* the largest count that still fits a 256-byte frame */
    CHECK(raw_read_exception(r, 0xF7, big, 0xF7) == MB_EXC_ILLEGAL_DATA_VALUE, "byte count above 0xF5");
}

static void readBadAddressesAreIllegalAddress(void)
{
    robot_t *r = fresh();
    frame_t a;
    frame_t f = read_request(SACT, 9, 0, 1);   /* no file 9 */
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_ADDRESS, "file 9: %d", answer_exception(&a));
    f = read_request(SACT, 0, 0, 1);           /* file 0 is reserved */
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_ADDRESS, "file 0: %d", answer_exception(&a));
    f = read_request(SACT, LEFT, 19, 2);       /* runs past the last record */
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_ADDRESS, "past end: %d", answer_exception(&a));
    f = read_request(SACT, LEFT, 10000, 1);    /* beyond 0x270F */
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_ADDRESS, "record 10000: %d", answer_exception(&a));
    f = read_request(SACT, LEFT, 0, 0);        /* zero length */
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_ADDRESS, "length 0: %d", answer_exception(&a));
    uint8_t sub[7] = { 7, 0, 1, 0, 0, 0, 1 };  /* reference type 7 */
    CHECK(raw_read_exception(r, 7, sub, 7) == MB_EXC_ILLEGAL_DATA_ADDRESS, "reference type 7");
}

static void readLargerThanOnePduIsIllegalValue(void)
{
    robot_t *r = fresh();
    /* sonar points file: 65 registers = 132 bytes per sub-request; two exceed 253 */
    frame_t f = { .len = 0 }, a;
    frame_put(&f, MB_SONAR_ADDRESS);
    frame_put(&f, 0x14);
    frame_put(&f, 14);
    for (int k = 0; k < 2; k++) {
        frame_put(&f, 6);
        frame_put16(&f, MB_SONAR_FILE_POINTS);
        frame_put16(&f, 0);
        frame_put16(&f, 65);
    }
    frame_seal(&f);
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_VALUE, "exception %d", answer_exception(&a));
    f = read_request(MB_SONAR_ADDRESS, MB_SONAR_FILE_POINTS, 0, 65);
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == 0 && a.len == 5 + 130 + 2, "one full file fits: len %zu", a.len);
}

static void writeToReadOnlyRecordIsIllegalAddress(void)
{
    robot_t *r = fresh();
    uint16_t before[80], after[80];
    snapshot(r, before);
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_POSITION, 5) == MB_EXC_ILLEGAL_DATA_ADDRESS, "position");
    CHECK(bus_write(r, SACT, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_FIRMWARE_VERSION, 5) == MB_EXC_ILLEGAL_DATA_ADDRESS,
          "firmware version");
    snapshot(r, after);
    CHECK(memcmp(before, after, sizeof before) == 0, "state changed");
}

static void negativeGainIsIllegalValueAndChangesNothing(void)
{
    robot_t *r = fresh();
    uint16_t before[80], after[80];
    snapshot(r, before);
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_KP, (uint16_t)-5) == MB_EXC_ILLEGAL_DATA_VALUE, "kp -5");
    CHECK(bus_write(r, SACT, RIGHT, MB_SACT_MOTOR_KD, 0x8000) == MB_EXC_ILLEGAL_DATA_VALUE, "kd 0x8000");
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_INTEGRAL_LIMIT, 492) == MB_EXC_ILLEGAL_DATA_VALUE, "limit 492");
    snapshot(r, after);
    CHECK(memcmp(before, after, sizeof before) == 0, "state changed");
}

static void speedAboveLimitIsIllegalValueAndChangesNothing(void)
{
    robot_t *r = fresh();
    int32_t vmax = r->sact.max_velocity_setpoint;   /* 0.5 m/s in 8.8 counts/Ts */
    CHECK(vmax == 1196, "limit %d", vmax);
    uint16_t before[80], after[80];
    snapshot(r, before);
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, (uint16_t)(vmax + 1)) == MB_EXC_ILLEGAL_DATA_VALUE,
          "vmax + 1");
    CHECK(bus_write(r, SACT, RIGHT, MB_SACT_MOTOR_VELOCITY_SETPOINT, (uint16_t)(-vmax - 1)) == MB_EXC_ILLEGAL_DATA_VALUE,
          "-vmax - 1");
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_ACCELERATION, (uint16_t)(r->sact.max_acceleration + 1)) ==
              MB_EXC_ILLEGAL_DATA_VALUE, "accel above max_accel");
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_ACCELERATION, 0) == MB_EXC_ILLEGAL_DATA_VALUE, "accel 0");
    snapshot(r, after);
    CHECK(memcmp(before, after, sizeof before) == 0, "state changed");
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, (uint16_t)vmax) == 0, "vmax itself accepted");
}

static void oneBadSubRequestRejectsTheWholeWrite(void)
{
    robot_t *r = fresh();
    frame_t f = { .len = 0 }, a;
    frame_put(&f, SACT);
    frame_put(&f, 0x15);
    frame_put(&f, 18);
    frame_put(&f, 6); frame_put16(&f, LEFT); frame_put16(&f, MB_SACT_MOTOR_KP); frame_put16(&f, 1); frame_put16(&f, 77);
    frame_put(&f, 6); frame_put16(&f, RIGHT); frame_put16(&f, MB_SACT_MOTOR_KP); frame_put16(&f, 1); frame_put16(&f, 0xFFFF);
    frame_seal(&f);
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_VALUE, "exception %d", answer_exception(&a));
    CHECK(r->sact.motor[0].kp == MB_SACT_MOTOR_KP_DEFAULT, "first sub-request was applied: kp %d", r->sact.motor[0].kp);
}

static void malformedWritesAreIllegalValue(void)
{
    robot_t *r = fresh();
    frame_t f = { .len = 0 }, a;
    /* header says 2 registers, carries 1 */
    frame_put(&f, SACT); frame_put(&f, 0x15); frame_put(&f, 9);
    frame_put(&f, 6); frame_put16(&f, LEFT); frame_put16(&f, 3); frame_put16(&f, 2); frame_put16(&f, 1);
    frame_seal(&f);
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_VALUE, "short data: %d", answer_exception(&a));
    /* byte count below 9 */
    f.len = 0;
    frame_put(&f, SACT); frame_put(&f, 0x15); frame_put(&f, 7);
    frame_put(&f, 6); frame_put16(&f, LEFT); frame_put16(&f, 3); frame_put16(&f, 0);
    frame_seal(&f);
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_VALUE, "byte count 7: %d", answer_exception(&a));
    /* byte count disagrees with the frame */
    f.len = 0;
    frame_put(&f, SACT); frame_put(&f, 0x15); frame_put(&f, 20);
    frame_put(&f, 6); frame_put16(&f, LEFT); frame_put16(&f, 3); frame_put16(&f, 1); frame_put16(&f, 5);
    frame_seal(&f);
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_VALUE, "byte count 20: %d", answer_exception(&a));
    /* function code only */
    f.len = 0;
    frame_put(&f, SACT); frame_put(&f, 0x15);
    frame_seal(&f);
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_VALUE, "no byte count: %d", answer_exception(&a));
    CHECK(r->sact.motor[0].kp == MB_SACT_MOTOR_KP_DEFAULT, "kp changed");
}

static void statusAcceptsOnlyZero(void)
{
    robot_t *r = fresh();
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_STATUS, 1) == MB_EXC_ILLEGAL_DATA_VALUE, "status 1");
    CHECK(bus_write(r, SACT, LEFT, MB_SACT_MOTOR_STATUS, 0) == 0, "status 0");
}

static void motionWhileFaultedIsDeviceFailure(void)
{
    robot_t *r = fresh();
    r->sact.motor[1].status |= MB_SACT_MOTOR_STATUS_FAULT;   /* as a latched over-current leaves it */
    CHECK(bus_write(r, SACT, RIGHT, MB_SACT_MOTOR_VELOCITY_SETPOINT, 100) == MB_EXC_SERVER_DEVICE_FAILURE, "velocity");
    CHECK(bus_write(r, SACT, RIGHT, MB_SACT_MOTOR_POSITION_STEP, 10) == MB_EXC_SERVER_DEVICE_FAILURE, "step");
    uint16_t both[2] = { 100, 100 };
    frame_t f = write_request(SACT, MB_SACT_FILE_DRIVE, 0, both, 2), a;
    transact(r, &f, &a);
    CHECK(answer_exception(&a) == MB_EXC_SERVER_DEVICE_FAILURE, "drive file: %d", answer_exception(&a));
    CHECK(r->sact.motor[0].velocity_setpoint == 0, "healthy motor moved by a rejected request");
    CHECK(bus_write(r, SACT, RIGHT, MB_SACT_MOTOR_VELOCITY_SETPOINT, 0) == 0, "zero is always allowed");
    CHECK(bus_write(r, SACT, RIGHT, MB_SACT_MOTOR_STATUS, 0) == 0, "acknowledge");
    CHECK(bus_write(r, SACT, RIGHT, MB_SACT_MOTOR_VELOCITY_SETPOINT, 100) == 0, "velocity after acknowledge");
}

/* One 0x15 request: the idempotency key first, then a position step of the left motor. */
static frame_t keyed_step(uint16_t key, int16_t counts)
{
    frame_t f = { .len = 0 };
    frame_put(&f, SACT);
    frame_put(&f, 0x15);
    frame_put(&f, (uint8_t)(2 * (7 + 2)));
    frame_put(&f, 6);
    frame_put16(&f, MB_SACT_FILE_CONFIG);
    frame_put16(&f, MB_SACT_CONFIG_COMMAND_SEQUENCE);
    frame_put16(&f, 1);
    frame_put16(&f, key);
    frame_put(&f, 6);
    frame_put16(&f, MB_SACT_FILE_MOTOR_LEFT);
    frame_put16(&f, MB_SACT_MOTOR_POSITION_STEP);
    frame_put16(&f, 1);
    frame_put16(&f, (uint16_t)counts);
    frame_seal(&f);
    return f;
}

/* A retried step (its answer lost, the same request sent again) is answered as before and
 * applied once; a new key applies again; key 0 means no key; the key must come first. */
static void aRetriedKeyedWriteIsAppliedOnce(void)
{
    robot_t *r = fresh();
    uint32_t before = r->sact.motor[0].commanded;
    const uint32_t step = 10u << SACT_POS_FRAC_BITS;
    frame_t req = keyed_step(7, 10), a1, a2;
    transact(r, &req, &a1);
    CHECK(answer_exception(&a1) == 0, "keyed step: %d", answer_exception(&a1));
    uint32_t once = r->sact.motor[0].commanded;
    CHECK(once - before == step, "first step: %u", (unsigned)(once - before));
    transact(r, &req, &a2);                              /* the retry */
    CHECK(a2.len == a1.len && memcmp(a1.data, a2.data, a1.len) == 0, "the retry is answered as the first");
    CHECK(r->sact.motor[0].commanded == once, "the retry applied the step again");
    CHECK(r->sact.duplicates == 1, "duplicates %u", (unsigned)r->sact.duplicates);
    CHECK(bus_read(r, SACT, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_COMMAND_SEQUENCE) == 7, "reads the last key");

    req = keyed_step(8, 10);
    transact(r, &req, &a1);
    CHECK(r->sact.motor[0].commanded - once == step, "a new key applies");
    req = keyed_step(0, 10);
    transact(r, &req, &a1);
    transact(r, &req, &a2);
    CHECK(r->sact.motor[0].commanded - once == 3 * step, "key 0 is no key: both applied");
    CHECK(bus_read(r, SACT, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_COMMAND_SEQUENCE) == 8, "0 leaves the last key");

    /* the key after another register: refused whole */
    uint16_t late[2] = { MB_SACT_CONFIG_COMMAND_TIMEOUT_DEFAULT, 9 };
    frame_t f = write_request(SACT, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_COMMAND_TIMEOUT, late, 2);
    transact(r, &f, &a1);
    CHECK(answer_exception(&a1) == MB_EXC_ILLEGAL_DATA_ADDRESS, "late key: %d", answer_exception(&a1));
    CHECK(bus_read(r, SACT, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_COMMAND_SEQUENCE) == 8, "late key not taken");
    /* a duplicate is not judged again: a fault latched since would not turn its answer into an exception */
    req = keyed_step(8, 10);
    r->sact.motor[0].status |= MB_SACT_MOTOR_STATUS_FAULT;
    transact(r, &req, &a2);
    CHECK(answer_exception(&a2) == 0, "retry after a fault: %d", answer_exception(&a2));
    CHECK(r->sact.duplicates == 2, "taken as the retry it is: duplicates %u", (unsigned)r->sact.duplicates);
}

static void wrongCrcIsIgnored(void)
{
    robot_t *r = fresh();
    uint16_t v = 200;
    frame_t f = write_request(SACT, LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, &v, 1), a;
    f.data[f.len - 1] ^= 0x40;
    CHECK(transact(r, &f, &a) == 0, "answered a bad CRC");
    CHECK(r->sact.motor[0].velocity_setpoint == 0, "acted on a bad CRC");
    CHECK(r->sact.modbus.stats.crc_errors == 1, "crc errors %u", r->sact.modbus.stats.crc_errors);
}

static void shortFramesAreIgnored(void)
{
    robot_t *r = fresh();
    const uint8_t three[] = { SACT, 0x14, 0x07 };
    frame_t a;
    CHECK(transact_raw(r, three, sizeof three, &a) == 0, "3-byte frame answered");
    const uint8_t one[] = { SACT };
    CHECK(transact_raw(r, one, sizeof one, &a) == 0, "1-byte frame answered");
    CHECK(r->sact.modbus.stats.requests == 0, "counted as a request");
}

static void otherAddressesAreIgnored(void)
{
    robot_t *r = fresh();
    frame_t f = read_request(9, MB_SACT_FILE_CONFIG, 0, 1), a;
    CHECK(transact(r, &f, &a) == 0, "slave 9 answered");
    f = read_request(MB_INS_ADDRESS, MB_INS_FILE_CONFIG, MB_INS_CONFIG_WHO_AM_I, 1);
    CHECK(transact(r, &f, &a) > 0 && a.data[0] == MB_INS_ADDRESS, "INS board silent");
    CHECK(((a.data[5] << 8) | a.data[6]) == 0x71, "who_am_i %02x", a.data[6]);
}

static void broadcastWriteActsSilently(void)
{
    robot_t *r = fresh();
    uint16_t both[2] = { 150, -150 };
    frame_t f = write_request(0, MB_SACT_FILE_DRIVE, 0, both, 2), a;
    CHECK(transact(r, &f, &a) == 0, "broadcast answered");
    CHECK(r->sact.motor[0].velocity_setpoint == 150 && r->sact.motor[1].velocity_setpoint == -150, "not applied");
    f = read_request(0, MB_SACT_FILE_CONFIG, 0, 1);
    CHECK(transact(r, &f, &a) == 0, "broadcast read answered");
}

static void gapInsideFrameDiscardsIt(void)
{
    robot_t *r = fresh();
    mb_slave_t *s = &r->sact.modbus;
    frame_t f = read_request(SACT, MB_SACT_FILE_CONFIG, 0, 1);
    uint32_t t = 1000;
    for (size_t i = 0; i < f.len; i++) {
        t += (i == 4) ? 1000 : 90;   /* 1 ms > t1.5 = 750 us between bytes 3 and 4 */
        mb_slave_on_byte(s, f.data[i], t);
    }
    CHECK(mb_slave_poll(s, t + 1000) == 0, "too early: the frame is not over");
    CHECK(mb_slave_poll(s, t + 1800) == 0, "answered a broken frame");
    CHECK(s->stats.timing_errors == 1, "timing errors %u", s->stats.timing_errors);
    /* the same frame with even spacing is answered */
    for (size_t i = 0; i < f.len; i++)
        mb_slave_on_byte(s, f.data[i], t += 90);
    CHECK(mb_slave_poll(s, t + 1800) == 9, "clean frame not answered");
}

static void silenceOfThreeAndAHalfCharactersSplitsFrames(void)
{
    robot_t *r = fresh();
    mb_slave_t *s = &r->sact.modbus;
    frame_t f = read_request(SACT, MB_SACT_FILE_CONFIG, 0, 1);
    uint32_t t = 5000;
    /* first half, 2 ms of silence the main loop does not see, then the rest */
    for (size_t i = 0; i < 5; i++)
        mb_slave_on_byte(s, f.data[i], t += 90);
    t += 2000;
    for (size_t i = 5; i < f.len; i++)
        mb_slave_on_byte(s, f.data[i], t += 90);
    CHECK(mb_slave_poll(s, t + 1800) == 0, "two halves answered as one frame");
}

static void overlongFrameIsDiscarded(void)
{
    robot_t *r = fresh();
    uint8_t junk[300];
    for (int i = 0; i < 300; i++)
        junk[i] = (uint8_t)(i == 0 ? SACT : 0x55);
    frame_t a;
    CHECK(transact_raw(r, junk, sizeof junk, &a) == 0, "answered");
    for (int i = 0; i < 400; i++)   /* 300 characters take 29 ms on the line */
        robot_step(r);
    CHECK(r->sact.modbus.stats.overruns == 1, "overruns %u", r->sact.modbus.stats.overruns);
    frame_t f = read_request(SACT, MB_SACT_FILE_CONFIG, 0, 1);
    CHECK(transact(r, &f, &a) > 0, "slave did not recover");
}

int main(void)
{
    printf("test_modbus\n");
    RUN(crcMatchesPublishedVector);
    RUN(readReturnsConfigurationDefaults);
    RUN(readSeveralSubRequestsInOneFrame);
    RUN(writeIsEchoedAndApplied);
    RUN(unknownFunctionIsIllegalFunction);
    RUN(readByteCountOutOfRangeIsIllegalValue);
    RUN(readBadAddressesAreIllegalAddress);
    RUN(readLargerThanOnePduIsIllegalValue);
    RUN(writeToReadOnlyRecordIsIllegalAddress);
    RUN(negativeGainIsIllegalValueAndChangesNothing);
    RUN(speedAboveLimitIsIllegalValueAndChangesNothing);
    RUN(oneBadSubRequestRejectsTheWholeWrite);
    RUN(malformedWritesAreIllegalValue);
    RUN(statusAcceptsOnlyZero);
    RUN(motionWhileFaultedIsDeviceFailure);
    RUN(aRetriedKeyedWriteIsAppliedOnce);
    RUN(wrongCrcIsIgnored);
    RUN(shortFramesAreIgnored);
    RUN(otherAddressesAreIgnored);
    RUN(broadcastWriteActsSilently);
    RUN(gapInsideFrameDiscardsIt);
    RUN(silenceOfThreeAndAHalfCharactersSplitsFrames);
    RUN(overlongFrameIsDiscarded);
    free(slot);
    return REPORT("test_modbus");
}
