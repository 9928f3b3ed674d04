/*
 * The simulated world: map loading and ray casting, drivetrain kinematics,
 * collisions, the inertial, sonar and ceiling-landmark boards, the battery, its docks
 * and the power board, determinism, fault injection, speed.
 */
#include <limits.h>
#include <math.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "bus_client.h"
#include "check.h"

#define LAB_MAP "maps/lab.yaml"

static world_t lab;

/* Robots on the lab map; the arena and slots stay valid for the whole test. */
typedef struct {
    arena_t arena;
    robot_t *list[4];
} floor_t;

static robot_t *place(floor_t *fl, int k, double x, double y, double theta, uint64_t seed)
{
    robot_config_t c;
    robot_config_default(&c);
    c.id = k + 1;
    c.seed = seed;
    c.x = x;
    c.y = y;
    c.theta = theta;
    fl->list[k] = calloc(1, sizeof(robot_t));
    fl->arena.world = &lab;
    fl->arena.robots = fl->list;
    fl->arena.n_robots = k + 1;
    robot_init(fl->list[k], &c, &fl->arena);
    return fl->list[k];
}

static void release(floor_t *fl)
{
    for (int k = 0; k < fl->arena.n_robots; k++)
        free(fl->list[k]);
}

static void run(robot_t **robots, int n, double seconds)
{
    for (long i = 0; i < lround(seconds * 1e6 / SACT_TS_US); i++)
        for (int k = 0; k < n; k++)
            robot_step(robots[k]);
}

/* 8.8 counts/Ts for a wheel surface speed in m/s, for the described robot. */
static uint16_t wheel_speed(double m_s)
{
    double counts_per_m = 4.0 * SABOT_ROBOT_ENCODER_LINES * SABOT_ROBOT_GEAR_RATIO / (2 * M_PI * SABOT_ROBOT_WHEEL_RADIUS_M);
    return (uint16_t)(int16_t)lround(m_s * counts_per_m * 50e-6 * 256.0);
}

static void drive(robot_t *r, double left, double right)
{
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, wheel_speed(left));
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_RIGHT, wheel_speed(right));
}

static void theLabMapLoadsWithRosConventions(void)
{
    CHECK(lab.width == 240 && lab.height == 180 && fabs(lab.resolution - 0.05) < 1e-12, "%dx%d", lab.width, lab.height);
    CHECK(world_occupied(&lab, 0.05, 0.05), "outer wall missing");
    CHECK(!world_occupied(&lab, 6.0, 4.5), "centre occupied");
    CHECK(world_occupied(&lab, 3.25, 3.0), "partition (x 3.0-3.5, y 2.0-6.0) missing");
    CHECK(!world_occupied(&lab, 10.75, 7.25), "unknown cells count as obstacles");
    CHECK(world_occupied(&lab, -1.0, 1.0), "outside the map is free");
    double c = world_clearance(&lab, 6.0, 4.5);
    CHECK(c > 1.0 && c < 3.0, "clearance at the centre %.3f", c);
}

static void raycastMeasuresTheDistanceToAWall(void)
{
    /* east wall: cells 237..239, its face at x = 237 * 0.05 = 11.85 m */
    double d = world_raycast(&lab, 6.0, 4.5, 0.0, 10.0);
    CHECK(fabs(d - 5.85) < 0.06, "east %.3f", d);
    d = world_raycast(&lab, 6.0, 4.5, M_PI / 2, 10.0);
    CHECK(fabs(d - (177 * 0.05 - 4.5)) < 0.06, "north %.3f", d);
    d = world_raycast(&lab, 6.0, 4.5, 0.0, 2.0);
    CHECK(d == 2.0, "max range not honoured: %.3f", d);
}

static void robotTurnsInPlaceAtTheExpectedRate(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 6.0, 4.5, 0.0, 1);
    drive(r, -0.2, 0.2);
    run(&r, 1, 2.0);
    double expected = 0.4 / r->cfg.params.track;   /* (v_r - v_l) / track */
    CHECK(fabs(r->body.omega - expected) < 0.03 * expected, "yaw rate %.3f, expected %.3f", r->body.omega, expected);
    CHECK(hypot(r->body.x - 6.0, r->body.y - 4.5) < 0.02, "drifted %.3f m", hypot(r->body.x - 6.0, r->body.y - 4.5));
    release(&fl);
}

static void robotStopsAtAWall(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 10.5, 2.0, 0.0, 1);
    drive(r, 0.3, 0.3);
    run(&r, 1, 6.0);
    CHECK(r->body.x <= 11.85 - r->cfg.params.radius + 1e-9, "went through the wall: x %.3f", r->body.x);
    CHECK(r->body.x > 11.85 - r->cfg.params.radius - 0.06, "stopped early: x %.3f", r->body.x);
    CHECK(r->body.collisions > 0, "no contact recorded");
    /* wheels spin against the wall: large slip, and the following error trips */
    CHECK(r->sact.motor[0].status & MB_SACT_MOTOR_STATUS_FOLLOWING_ERROR, "status %04x", r->sact.motor[0].status);
    release(&fl);
}

static void robotsCannotDriveThroughEachOther(void)
{
    floor_t fl = { 0 };
    robot_t *a = place(&fl, 0, 5.0, 6.5, 0.0, 1);
    robot_t *b = place(&fl, 1, 7.0, 6.5, M_PI, 2);
    drive(a, 0.3, 0.3);
    drive(b, 0.3, 0.3);
    run(fl.list, 2, 6.0);
    double gap = hypot(a->body.x - b->body.x, a->body.y - b->body.y);
    CHECK(gap >= 0.5 - 0.02, "centres %.3f m apart", gap);
    CHECK(a->body.collisions > 0 && b->body.collisions > 0, "no contact");
    release(&fl);
}

static double mean_gyro_z(robot_t *r, int samples, double *stddev)
{
    double sum = 0, sum2 = 0;
    uint16_t last = (uint16_t)r->ins.regs[MB_INS_SAMPLE_SAMPLE_COUNTER];
    for (int n = 0; n < samples;) {
        robot_step(r);
        if ((uint16_t)r->ins.regs[MB_INS_SAMPLE_SAMPLE_COUNTER] != last) {
            last = (uint16_t)r->ins.regs[MB_INS_SAMPLE_SAMPLE_COUNTER];
            double g = r->ins.regs[MB_INS_SAMPLE_GYRO_Z] / 131.0 * M_PI / 180.0;
            sum += g;
            sum2 += g * g;
            n++;
        }
    }
    double mean = sum / samples;
    *stddev = sqrt(sum2 / samples - mean * mean);
    return mean;
}

static void inertialBoardMeasuresYawRateGravityAndHeading(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 6.0, 4.5, 0.3, 5);
    double sd;
    double rest = mean_gyro_z(r, 400, &sd);
    /* white noise per sample: 0.01 deg/s/rtHz x sqrt(100 Hz) = 0.1 deg/s */
    double expected_sd = 0.01 * M_PI / 180 * sqrt(100.0);
    CHECK(sd > 0.7 * expected_sd && sd < 1.3 * expected_sd, "gyro noise %.5f rad/s, expected %.5f", sd, expected_sd);
    CHECK(fabs(rest - r->ins.gyro_bias[2]) < 4 * expected_sd / sqrt(400.0) + 1e-3, "rest %.5f vs bias %.5f", rest,
          r->ins.gyro_bias[2]);
    double az = r->ins.regs[MB_INS_SAMPLE_ACCEL_Z] / 16384.0 * 9.80665;
    CHECK(fabs(az - 9.80665) < 0.1 * 9.80665, "accel z %.3f", az);
    double heading = atan2(r->ins.regs[MB_INS_SAMPLE_MAG_Y], r->ins.regs[MB_INS_SAMPLE_MAG_X]);
    double expected_heading = remainder(M_PI / 2 - 0.3, 2 * M_PI);   /* north is map +y */
    CHECK(fabs(remainder(heading - expected_heading, 2 * M_PI)) < 0.3, "magnetic heading %.3f vs %.3f", heading,
          expected_heading);
    drive(r, -0.2, 0.2);
    run(&r, 1, 1.5);
    double turning = mean_gyro_z(r, 100, &sd);
    CHECK(fabs(turning - rest - r->body.omega) < 0.02, "gyro %.4f - bias vs true %.4f", turning - rest, r->body.omega);
    printf("    figure: gyro noise %.2f mdeg/s per sample at 200 Hz (expected %.2f), bias %.3f deg/s\n",
           sd * 180e3 / M_PI, expected_sd * 180e3 / M_PI, r->ins.gyro_bias[2] * 180 / M_PI);
    release(&fl);
}

static void sonarSeesTheWallAheadAndAnotherRobot(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 10.0, 2.0, 0.0, 1);
    CHECK(bus_write(r, MB_SONAR_ADDRESS, MB_SONAR_FILE_CONFIG, MB_SONAR_CONFIG_SWEEP_ENABLE, 0) == 0, "sweep off");
    run(&r, 1, 0.5);
    /* centre sensor is 0.20 m ahead of the centre; the wall face at 11.85 m */
    int16_t x = (int16_t)bus_read(r, MB_SONAR_ADDRESS, MB_SONAR_FILE_LATEST, 6 + 3);
    long range = bus_read(r, MB_SONAR_ADDRESS, MB_SONAR_FILE_LATEST, 6 + 2);
    CHECK(abs(x - 1850) < 40, "obstacle x %d mm", x);
    CHECK(labs(range - 1650) < 40, "range %ld mm", range);
    long count = bus_read(r, MB_SONAR_ADDRESS, MB_SONAR_FILE_POINTS, 0);
    CHECK(count > 10, "point ring has %ld points", count);
    release(&fl);

    floor_t fl2 = { 0 };
    robot_t *a = place(&fl2, 0, 4.5, 6.5, 0.0, 1);
    place(&fl2, 1, 6.0, 6.5, 0.0, 2);
    bus_write(a, MB_SONAR_ADDRESS, MB_SONAR_FILE_CONFIG, MB_SONAR_CONFIG_SWEEP_ENABLE, 0);
    run(fl2.list, 2, 0.5);
    x = (int16_t)bus_read(a, MB_SONAR_ADDRESS, MB_SONAR_FILE_LATEST, 6 + 3);
    CHECK(abs(x - 1250) < 40, "other robot at x %d mm, expected 1250", x);
    release(&fl2);
}

static void sonarServosSweep(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 6.0, 4.5, 0.0, 1);
    double lo = 1, hi = -1;
    for (int i = 0; i < 40; i++) {
        run(&r, 1, 0.05);
        double a = sonar_servo_offset(&r->sonar, 1, r->now_us);
        lo = fmin(lo, a);
        hi = fmax(hi, a);
    }
    double amp = MB_SONAR_CONFIG_SWEEP_HALF_ANGLE_DEFAULT * M_PI / 180;
    CHECK(hi > 0.9 * amp && lo < -0.9 * amp && hi <= amp + 1e-9, "sweep %.3f..%.3f", lo, hi);
    release(&fl);
}

static void theSameSeedGivesTheSameRun(void)
{
    double pose[3][3];
    int16_t gyro[3];
    uint64_t seeds[3] = { 42, 42, 43 };
    for (int k = 0; k < 3; k++) {
        floor_t fl = { 0 };
        robot_t *r = place(&fl, 0, 6.0, 4.5, 0.0, seeds[k]);
        drive(r, 0.25, 0.35);
        run(&r, 1, 2.0);
        pose[k][0] = r->body.x;
        pose[k][1] = r->body.y;
        pose[k][2] = r->body.theta;
        gyro[k] = r->ins.regs[MB_INS_SAMPLE_GYRO_Z];
        release(&fl);
    }
    CHECK(memcmp(pose[0], pose[1], sizeof pose[0]) == 0, "same seed, different pose");
    CHECK(gyro[0] == gyro[1], "same seed, different gyro sample");
    CHECK(gyro[0] != gyro[2] || memcmp(pose[0], pose[2], sizeof pose[0]) != 0, "seed has no effect");
}

static void injectedFaultsCorruptAndDropAnswers(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 6.0, 4.5, 0.0, 1);
    r->cfg.faults.crc_error_rate = 1.0;
    frame_t req = read_request(MB_SACT_ADDRESS, MB_SACT_FILE_CONFIG, 0, 1), a;
    CHECK(transact(r, &req, &a) > 0 && answer_exception(&a) == -1, "answer not corrupted");
    r->cfg.faults.crc_error_rate = 0.0;
    r->cfg.faults.drop_rate = 1.0;
    CHECK(transact(r, &req, &a) == 0, "answer not dropped");
    r->cfg.faults.drop_rate = 0.0;
    r->cfg.faults.latency_us = 15000;
    uint64_t t0 = r->now_us;
    CHECK(transact(r, &req, &a) > 0 && answer_exception(&a) == 0, "answer lost with latency");
    CHECK(r->now_us - t0 >= 15000, "latency not applied: %llu us", (unsigned long long)(r->now_us - t0));
    CHECK(r->answers_corrupted == 1 && r->answers_dropped == 1, "counters %llu %llu",
          (unsigned long long)r->answers_corrupted, (unsigned long long)r->answers_dropped);
    release(&fl);
}

/* ---- battery, docks, power board ---------------------------------------------------------------- */

static robot_t *place_with_battery(floor_t *fl, int k, double x, double y, double capacity_ah, double soc)
{
    robot_config_t c;
    robot_config_default(&c);
    c.id = k + 1;
    c.x = x;
    c.y = y;
    c.battery.capacity_ah = capacity_ah;
    c.battery_soc = soc;
    fl->list[k] = calloc(1, sizeof(robot_t));
    fl->arena.world = &lab;
    fl->arena.robots = fl->list;
    fl->arena.n_robots = k + 1;
    robot_init(fl->list[k], &c, &fl->arena);
    return fl->list[k];
}

static void theCellCurveRisesFromEmptyToTheChargersVoltage(void)
{
    CHECK(battery_cell_ocv(0) == 3.00 && battery_cell_ocv(1) == 4.20, "ends %.3f %.3f", battery_cell_ocv(0),
          battery_cell_ocv(1));
    CHECK(fabs(battery_cell_ocv(0.55) - 3.78) < 1e-9, "between 3.74 and 3.82: %.4f", battery_cell_ocv(0.55));
    for (int k = 0; k < 100; k++)
        CHECK(battery_cell_ocv((k + 1) / 100.0) > battery_cell_ocv(k / 100.0), "not rising at %d %%", k);
    CHECK(battery_cell_ocv(-1) == 3.00 && battery_cell_ocv(2) == 4.20, "clamped");
}

static void theLabAndTheTwoRoomsHaveTheirDocks(void)
{
    CHECK(lab.n_docks == 2 && lab.docks[0].x == 1.0 && lab.docks[0].y == 1.0 && lab.docks[1].x == 11.0,
          "%d docks in the lab", lab.n_docks);
    world_t rooms;
    char err[256];
    CHECK(world_load(&rooms, "maps/two-rooms.yaml", err, sizeof err) == 0, "%s", err);
    CHECK(rooms.n_docks == 2 && rooms.docks[0].x == 0.8 && rooms.docks[1].x == 7.8 && rooms.docks[1].y == 2.2,
          "%d docks in the two rooms", rooms.n_docks);
    for (int k = 0; k < rooms.n_docks; k++)
        CHECK(world_clearance(&rooms, rooms.docks[k].x, rooms.docks[k].y) > 0.5, "dock %d near a wall", k);
    for (int k = 0; k < lab.n_docks; k++)
        CHECK(world_clearance(&lab, lab.docks[k].x, lab.docks[k].y) > 0.5, "lab dock %d near a wall", k);
    world_free(&rooms);
    CHECK(world_dock_at(&lab, 1.0 + WORLD_DOCK_REACH * 0.99, 1.0) == 0, "within reach");
    CHECK(world_dock_at(&lab, 1.0 + WORLD_DOCK_REACH * 1.01, 1.0) == -1, "beyond reach");
}

static void badDocksListsAreRefusedAndChangeNothing(void)
{
    static const char *const bad[] = { "", "[", "[[1, 2]", "[[1, 2],]", "[[1]]", "[[1, 2, 3]]", "[[a, 2]]",
                                       "[[1, nan]]", "[1, 2]", "[[1, 2]] x", "[[1, 2] [3, 4]]" };
    world_t w = { 0 };
    w.n_docks = 1;
    w.docks[0] = (world_dock_t){ 7, 7 };
    char err[200];
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        CHECK(world_parse_docks(&w, bad[i], err, sizeof err) == -1 && strstr(err, "sabot_docks wants [[x, y], ...]"),
              "'%s' taken (%s)", bad[i], err);
        CHECK(w.n_docks == 1 && w.docks[0].x == 7, "'%s' changed the docks", bad[i]);
    }
    char many[400] = "[";
    for (int k = 0; k <= WORLD_MAX_DOCKS; k++)
        snprintf(many + strlen(many), sizeof many - strlen(many), "%s[%d, 1]", k ? ", " : "", k);
    strcat(many, "]");
    CHECK(world_parse_docks(&w, many, err, sizeof err) == -1 && strstr(err, "more than 16 docks"), "%s", err);
    CHECK(world_parse_docks(&w, " [ [ -1.5 ,2e-1 ],[3,4] ] ", err, sizeof err) == 0 && w.n_docks == 2 &&
              w.docks[0].x == -1.5 && w.docks[0].y == 0.2 && w.docks[1].y == 4,
          "%s", err);
    CHECK(world_parse_docks(&w, "[]", err, sizeof err) == 0 && w.n_docks == 0, "empty list");
}

/* At rest the battery carries the base load alone; driving, the motors' power too; the charge falls by the
 * current's integral over the capacity. */
static void theBatteryDrainsWithTheBaseLoadAndTheMotors(void)
{
    floor_t fl = { 0 };
    robot_t *r = place_with_battery(&fl, 0, 6.0, 4.5, 1.0, 0.8);
    const battery_t *b = &r->battery;
    double ocv = 7 * battery_cell_ocv(0.8);
    run(&r, 1, 0.5);
    double rest_current = b->current, rest_voltage = b->voltage;
    CHECK(fabs(rest_current - 15.0 / rest_voltage) < 0.02, "at rest %.4f A, base load alone %.4f A", rest_current,
          15.0 / rest_voltage);
    CHECK(fabs(rest_voltage - (ocv - 0.1 * rest_current)) < 0.01, "at rest %.4f V, OCV %.4f V", rest_voltage, ocv);
    double soc0 = b->soc, charge = 0;
    drive(r, 0.4, 0.4);
    for (long i = 0; i < 60000; i++) {   /* 3 s */
        robot_step(r);
        charge += b->current * SACT_TS_US * 1e-6;
    }
    /* rolling resistance (2.2 N at 0.4 m/s) and the motors' friction and copper losses: some 2 W */
    CHECK(b->current > rest_current + 0.04 && b->voltage < rest_voltage - 0.004,
          "driving at 0.4 m/s: %.4f A %.4f V, at rest %.4f A %.4f V", b->current, b->voltage, rest_current,
          rest_voltage);
    CHECK(fabs((soc0 - b->soc) - charge / 3600.0) < 1e-9, "soc fell %.6f, integral %.6f", soc0 - b->soc,
          charge / 3600.0);
    CHECK(!b->docked && !b->charging && !b->full, "flags away from a dock");
    printf("    figure: at rest %.3f A at %.3f V; at 0.4 m/s %.3f A at %.3f V\n", rest_current, rest_voltage,
           b->current, b->voltage);
    release(&fl);
}

/* On a dock: constant current, then constant voltage until C/20, then full with the dock carrying the load;
 * off the dock the battery drains again. */
static void aRobotOnADockChargesUntilFullAndDrainsWhenItLeaves(void)
{
    floor_t fl = { 0 };
    robot_t *r = place_with_battery(&fl, 0, 11.0, 1.05, 0.01, 0.5);
    const battery_t *b = &r->battery;
    run(&r, 1, 0.05);
    CHECK(b->docked && b->charging && !b->full && fabs(b->current + 5.0) < 1e-9, "docked %d charging %d %.4f A",
          b->docked, b->charging, b->current);
    CHECK(fabs(b->voltage - (7 * battery_cell_ocv(b->soc) + 0.5)) < 0.01, "charging at %.4f V", b->voltage);
    double soc = b->soc;
    run(&r, 1, 0.1);
    /* 5 A into 0.01 Ah for 0.1 s */
    CHECK(fabs(b->soc - soc - 5.0 * 0.1 / 36.0) < 1e-3, "soc rose %.5f", b->soc - soc);
    run(&r, 1, 8.0);
    CHECK(b->full && !b->charging && b->current == 0 && b->soc > 0.99, "full %d charging %d %.4f A soc %.5f",
          b->full, b->charging, b->current, b->soc);
    CHECK(fabs(b->voltage - 7 * battery_cell_ocv(b->soc)) < 1e-9, "full at rest %.4f V", b->voltage);
    r->body.y = 2.0;   /* carried off the dock */
    run(&r, 1, 0.05);
    CHECK(!b->docked && !b->full && !b->charging && b->current > 0.5, "off the dock: docked %d full %d %.4f A",
          b->docked, b->full, b->current);
    release(&fl);
}

/* The power board's file 1, read in one sub-request as a master would. */
static bool read_power(robot_t *r, long v[5])
{
    frame_t req = read_request(MB_POWER_ADDRESS, MB_POWER_FILE_LATEST, MB_POWER_LATEST_SEQUENCE, 5), a;
    if (transact(r, &req, &a) == 0 || answer_exception(&a) != 0 || a.len != 5 + 10 + 2)
        return false;
    for (int k = 0; k < 5; k++)
        v[k] = a.data[5 + 2 * k] << 8 | a.data[6 + 2 * k];
    return true;
}

static void thePowerBoardAveragesOverItsPeriodAndSaysWhenItCharges(void)
{
    floor_t fl = { 0 };
    robot_t *r = place_with_battery(&fl, 0, 6.0, 4.5, 2.0, 0.6);
    long v[5];
    CHECK(read_power(r, v) && v[0] == 0 && labs(v[1] - lround(7000 * battery_cell_ocv(0.6))) <= 20 && v[4] == 0,
          "at power-on: sequence %ld, %ld mV, status %ld", v[0], v[1], v[4]);
    CHECK(v[3] == 6000, "soc %ld", v[3]);
    uint16_t s0 = r->power.sequence;
    run(&r, 1, 1.0);
    CHECK((uint16_t)(r->power.sequence - s0) == 10, "%u measurements in 1 s at 100 ms",
          (unsigned)(uint16_t)(r->power.sequence - s0));
    /* noise: measurements at rest against the truth */
    double sv = 0, sc = 0;
    int n = 0;
    for (uint16_t last = r->power.sequence; n < 200;) {
        robot_step(r);
        if (r->power.sequence == last)
            continue;
        last = r->power.sequence;
        sv += pow(r->power.voltage_mv * 1e-3 - r->battery.voltage, 2);
        sc += pow(r->power.current_ma * 1e-3 - r->battery.current, 2);
        n++;
    }
    double sigma_v = sqrt(sv / n), sigma_c = sqrt(sc / n);
    CHECK(sigma_v > 0.003 && sigma_v < 0.007 && sigma_c > 0.003 && sigma_c < 0.007,
          "sigmas %.4f V %.4f A, model 0.005", sigma_v, sigma_c);
    printf("    figure: power board noise at rest: voltage sigma %.2f mV, current sigma %.2f mA (model 5, 5)\n",
           sigma_v * 1e3, sigma_c * 1e3);
    CHECK(read_power(r, v) && v[0] == r->power.sequence && labs((int16_t)v[2] - lround(r->battery.current * 1000)) < 30,
          "over the bus: sequence %ld, %d mA, truth %.4f A", v[0], (int16_t)v[2], r->battery.current);
    release(&fl);

    floor_t docked = { 0 };
    r = place_with_battery(&docked, 0, 1.0, 1.0, 2.0, 0.6);
    run(&r, 1, 0.25);
    CHECK(read_power(r, v) && v[4] == (MB_POWER_LATEST_STATUS_DOCKED | MB_POWER_LATEST_STATUS_CHARGING) &&
              labs((int16_t)v[2] + 5000) < 30,
          "on the dock: status %ld, %d mA", v[4], (int16_t)v[2]);
    release(&docked);
}

/* The landmark board's file 1, read in one sub-request as a master would. */
typedef struct {
    long sequence, id, range_mm, bearing, age_ms;   /* bearing in 1e-4 rad */
} sighting_t;

static bool read_sighting(robot_t *r, sighting_t *s)
{
    frame_t req = read_request(MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_LATEST, MB_LANDMARK_LATEST_SEQUENCE, 5), a;
    if (transact(r, &req, &a) == 0 || answer_exception(&a) != 0 || a.len != 5 + 10 + 2)
        return false;
    long v[5];
    for (int k = 0; k < 5; k++)
        v[k] = a.data[5 + 2 * k] << 8 | a.data[6 + 2 * k];
    *s = (sighting_t){ v[0], v[1], v[2], (int16_t)v[3], v[4] };
    return true;
}

/* The marker the camera should report from (x, y): the nearest within radius, or NULL. */
static const world_landmark_t *marker_in_view(double x, double y, double radius)
{
    const world_landmark_t *best = NULL;
    for (int k = 0; k < lab.n_landmarks; k++) {
        double d = hypot(lab.landmarks[k].x - x, lab.landmarks[k].y - y);
        if (d <= radius && (!best || d < hypot(best->x - x, best->y - y)))
            best = &lab.landmarks[k];
    }
    return best;
}

static void theLabHasItsCeilingLandmarks(void)
{
    CHECK(lab.n_landmarks == 10, "%d landmarks", lab.n_landmarks);
    CHECK(lab.n_landmarks > 4 && lab.landmarks[4].id == 5 && fabs(lab.landmarks[4].x - 5.6) < 1e-12 &&
              fabs(lab.landmarks[4].y - 3.6) < 1e-12,
          "landmark 5 at %.3f %.3f", lab.n_landmarks > 4 ? lab.landmarks[4].x : NAN,
          lab.n_landmarks > 4 ? lab.landmarks[4].y : NAN);
}

static void landmarkBoardReportsTheNearestMarkerInViewAtItsGeometry(void)
{
    static const double poses[][3] = {
        { 6.2, 3.3, 2.0 },    /* south-east of marker 5, facing north-west */
        { 6.3, 1.6, -2.5 },   /* between markers 2 and 3 */
        { 1.8, 5.7, 0.7 },    /* north of marker 7 */
        { 8.1, 6.2, -1.2 },   /* south-east of marker 9 */
    };
    const double range_sigma = 0.010, bearing_sigma = 0.5 * M_PI / 180;
    for (size_t i = 0; i < sizeof poses / sizeof poses[0]; i++) {
        floor_t fl = { 0 };
        robot_t *r = place(&fl, 0, poses[i][0], poses[i][1], poses[i][2], 3 + i);
        run(&r, 1, 0.25);
        sighting_t s;
        CHECK(read_sighting(r, &s), "pose %zu: no answer", i);
        const world_landmark_t *m = marker_in_view(r->body.x, r->body.y, 1.5);
        CHECK(m != NULL, "pose %zu: test pose has no marker in view", i);
        if (!m) {
            release(&fl);
            continue;
        }
        double range = hypot(m->x - r->body.x, m->y - r->body.y);
        double bearing = remainder(atan2(m->y - r->body.y, m->x - r->body.x) - r->body.theta, 2 * M_PI);
        CHECK(s.id == m->id, "pose %zu: sees %ld, nearest in view is %u", i, s.id, m->id);
        CHECK(fabs(s.range_mm * 1e-3 - range) < 4 * range_sigma + 1e-3, "pose %zu: range %ld mm, truth %.1f mm", i,
              s.range_mm, range * 1e3);
        CHECK(fabs(remainder(s.bearing * 1e-4 - bearing, 2 * M_PI)) < 4 * bearing_sigma + 1e-4,
              "pose %zu: bearing %.4f rad, truth %.4f", i, s.bearing * 1e-4, bearing);
        CHECK(s.sequence >= 2 && s.age_ms < MB_LANDMARK_CONFIG_PERIOD_DEFAULT + 5, "pose %zu: sequence %ld age %ld",
              i, s.sequence, s.age_ms);
        release(&fl);
    }
}

static void landmarkNoiseHasTheModelledSigmas(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 6.2, 3.3, 2.0, 9);
    CHECK(bus_write(r, MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_CONFIG, MB_LANDMARK_CONFIG_PERIOD, 20) == 0, "period");
    const world_landmark_t *m = marker_in_view(6.2, 3.3, 1.5);
    double sr = 0, sr2 = 0, sb = 0, sb2 = 0;
    const int n = 400;
    uint16_t last = r->landmark.sequence;
    for (int k = 0; k < n;) {
        robot_step(r);
        if (r->landmark.sequence == last)
            continue;
        last = r->landmark.sequence;
        double range = hypot(m->x - r->body.x, m->y - r->body.y);
        double bearing = atan2(m->y - r->body.y, m->x - r->body.x) - r->body.theta;
        double er = r->landmark.range_mm * 1e-3 - range;
        double eb = remainder(r->landmark.bearing * 1e-4 - bearing, 2 * M_PI);
        sr += er;
        sr2 += er * er;
        sb += eb;
        sb2 += eb * eb;
        k++;
    }
    double mr = sr / n, mb = sb / n, dr = sqrt(sr2 / n - mr * mr), db = sqrt(sb2 / n - mb * mb);
    CHECK(fabs(mr) < 4 * 0.010 / sqrt(n) + 0.5e-3, "range bias %.2f mm", mr * 1e3);
    CHECK(fabs(mb) < 4 * 0.5 * M_PI / 180 / sqrt(n) + 1e-4, "bearing bias %.3f deg", mb * 180 / M_PI);
    CHECK(dr > 0.8 * 0.010 && dr < 1.2 * 0.010, "range sigma %.2f mm, model 10", dr * 1e3);
    CHECK(db > 0.8 * 0.5 * M_PI / 180 && db < 1.2 * 0.5 * M_PI / 180, "bearing sigma %.3f deg, model 0.5",
          db * 180 / M_PI);
    printf("    figure: landmark range sigma %.2f mm (model 10), bearing sigma %.3f deg (model 0.5), %d samples\n",
           dr * 1e3, db * 180 / M_PI, n);
    release(&fl);
}

static void aMarkerBeyondTheViewRadiusIsNotSeen(void)
{
    floor_t fl = { 0 };
    /* 1.00 m due east of marker 5 (5.6, 3.6); the next nearest is 2.2 m away */
    robot_t *r = place(&fl, 0, 6.6, 3.6, 0.0, 4);
    CHECK(bus_write(r, MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_CONFIG, MB_LANDMARK_CONFIG_VIEW_RADIUS, 900) == 0,
          "radius 0.9 m");
    run(&r, 1, 0.25);
    sighting_t s;
    CHECK(read_sighting(r, &s) && s.id == 0 && s.range_mm == 0 && s.bearing == 0,
          "radius 0.9 m: id %ld range %ld bearing %ld", s.id, s.range_mm, s.bearing);
    long seq = s.sequence;
    CHECK(bus_write(r, MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_CONFIG, MB_LANDMARK_CONFIG_VIEW_RADIUS, 1100) == 0,
          "radius 1.1 m");
    run(&r, 1, 0.25);
    CHECK(read_sighting(r, &s) && s.id == 5 && labs(s.range_mm - 1000) < 40 && labs(labs(s.bearing) - 31416) < 400,
          "radius 1.1 m: id %ld range %ld bearing %ld", s.id, s.range_mm, s.bearing);
    CHECK(s.sequence > seq, "sequence did not advance");
    release(&fl);

    floor_t far = { 0 };
    r = place(&far, 0, 10.8, 8.0, 0.0, 4);   /* the north-east corner: nothing within 3 m */
    run(&r, 1, 0.5);
    CHECK(read_sighting(r, &s) && s.sequence >= 4 && s.id == 0 && s.range_mm == 0, "north-east: seq %ld id %ld",
          s.sequence, s.id);
    release(&far);
}

static void withoutLandmarksTheBoardMeasuresAndSeesNothing(void)
{
    arena_t arena = { 0 };
    robot_t *slot;
    robot_t *r = make_robot(1, &arena, &slot);   /* no world at all */
    run(&r, 1, 1.0);
    sighting_t s;
    CHECK(read_sighting(r, &s) && s.sequence >= 10 && s.id == 0, "no world: seq %ld id %ld", s.sequence, s.id);
    free(slot);

    /* a map without sabot_landmarks: the lab's image, no markers */
    char dir[PATH_MAX], yaml[PATH_MAX + 32], pgm[PATH_MAX], err[256];
    CHECK(realpath("maps/lab.pgm", pgm) != NULL, "maps/lab.pgm");
    snprintf(dir, sizeof dir, "build/tmp");
    mkdir("build", 0755);
    mkdir(dir, 0755);
    snprintf(yaml, sizeof yaml, "%s/plain.yaml", dir);
    FILE *f = fopen(yaml, "w");
    fprintf(f, "image: %s\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n", pgm);
    fclose(f);
    world_t plain;
    CHECK(world_load(&plain, yaml, err, sizeof err) == 0, "%s", err);
    CHECK(plain.n_landmarks == 0 && plain.landmarks == NULL, "%d landmarks", plain.n_landmarks);
    robot_t *list[1];
    arena_t a2 = { &plain, list, 1, NULL };
    list[0] = calloc(1, sizeof(robot_t));
    robot_config_t c;
    robot_config_default(&c);
    c.x = 5.6;   /* right under where the lab's marker 5 would be */
    c.y = 3.6;
    robot_init(list[0], &c, &a2);
    run(list, 1, 0.5);
    CHECK(read_sighting(list[0], &s) && s.sequence >= 4 && s.id == 0, "plain map: seq %ld id %ld", s.sequence, s.id);
    free(list[0]);
    world_free(&plain);
}

static void landmarkSequenceFollowsThePeriodAndAgeIsReadTime(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 6.2, 3.3, 2.0, 6);
    run(&r, 1, 0.05);
    uint16_t s0 = r->landmark.sequence;
    run(&r, 1, 1.0);
    CHECK((uint16_t)(r->landmark.sequence - s0) == 10, "%u measurements in 1 s at 100 ms",
          (unsigned)(uint16_t)(r->landmark.sequence - s0));
    CHECK(bus_write(r, MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_CONFIG, MB_LANDMARK_CONFIG_PERIOD, 250) == 0, "period");
    /* wait for a measurement under the new period, then count over 1 s */
    uint16_t s1 = r->landmark.sequence;
    while (r->landmark.sequence == s1)
        robot_step(r);
    s1 = r->landmark.sequence;
    run(&r, 1, 1.0);
    CHECK((uint16_t)(r->landmark.sequence - s1) == 4, "%u measurements in 1 s at 250 ms",
          (unsigned)(uint16_t)(r->landmark.sequence - s1));
    /* 1.0 s after a measurement at 250 ms: the latest is 0..250 ms old, and the age says so at read time */
    sighting_t s;
    CHECK(read_sighting(r, &s), "read");
    uint64_t expected_ms = (r->now_us - r->landmark.taken_us) / 1000;
    CHECK(labs(s.age_ms - (long)expected_ms) <= 3 && s.age_ms < 250, "age %ld ms, expected about %llu", s.age_ms,
          (unsigned long long)expected_ms);
    /* 120 ms after a fresh measurement (period 250 ms) the same one is read, 120 ms old plus the transaction */
    uint16_t s2 = r->landmark.sequence;
    while (r->landmark.sequence == s2)
        robot_step(r);
    run(&r, 1, 0.12);
    sighting_t later;
    CHECK(read_sighting(r, &later), "read");
    CHECK(later.sequence == r->landmark.sequence && later.age_ms >= 120 && later.age_ms <= 125,
          "sequence %ld, age %ld ms, expected 120..125", later.sequence, later.age_ms);
    release(&fl);
}

static void badLandmarkConfigurationWritesAreRefusedAndChangeNothing(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 6.2, 3.3, 2.0, 1);
    static const struct {
        uint16_t record, value;
        int exception;
    } bad[] = {
        { MB_LANDMARK_CONFIG_VIEW_RADIUS, MB_LANDMARK_CONFIG_VIEW_RADIUS_MIN - 1, MB_EXC_ILLEGAL_DATA_VALUE },
        { MB_LANDMARK_CONFIG_VIEW_RADIUS, MB_LANDMARK_CONFIG_VIEW_RADIUS_MAX + 1, MB_EXC_ILLEGAL_DATA_VALUE },
        { MB_LANDMARK_CONFIG_PERIOD, MB_LANDMARK_CONFIG_PERIOD_MIN - 1, MB_EXC_ILLEGAL_DATA_VALUE },
        { MB_LANDMARK_CONFIG_PERIOD, MB_LANDMARK_CONFIG_PERIOD_MAX + 1, MB_EXC_ILLEGAL_DATA_VALUE },
        { MB_LANDMARK_CONFIG_PERIOD, 0, MB_EXC_ILLEGAL_DATA_VALUE },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        int e = bus_write(r, MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_CONFIG, bad[i].record, bad[i].value);
        CHECK(e == bad[i].exception, "record %u = %u answered %d", bad[i].record, bad[i].value, e);
    }
    CHECK(r->landmark.view_radius_mm == MB_LANDMARK_CONFIG_VIEW_RADIUS_DEFAULT &&
              r->landmark.period_ms == MB_LANDMARK_CONFIG_PERIOD_DEFAULT,
          "changed: radius %u period %u", r->landmark.view_radius_mm, r->landmark.period_ms);
    /* one good and one bad value in one request: neither is taken */
    uint16_t both[2] = { 2000, 5 };
    frame_t req = write_request(MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_CONFIG, MB_LANDMARK_CONFIG_VIEW_RADIUS, both, 2), a;
    transact(r, &req, &a);
    CHECK(answer_exception(&a) == MB_EXC_ILLEGAL_DATA_VALUE, "answered %d", answer_exception(&a));
    CHECK(r->landmark.view_radius_mm == MB_LANDMARK_CONFIG_VIEW_RADIUS_DEFAULT, "radius taken from a refused request");
    CHECK(bus_write(r, MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_LATEST, MB_LANDMARK_LATEST_LANDMARK_ID, 3) ==
              MB_EXC_ILLEGAL_DATA_ADDRESS,
          "the measurement is writable");
    release(&fl);
}

/* Writes text to build/tmp/NAME and returns its path. */
static const char *tmp_file(const char *name, const char *text)
{
    static char path[PATH_MAX];
    mkdir("build", 0755);
    mkdir("build/tmp", 0755);
    snprintf(path, sizeof path, "build/tmp/%s", name);
    FILE *f = fopen(path, "w");
    fputs(text, f);
    fclose(f);
    return path;
}

static void badLandmarksFilesAreRefusedWithFileAndLine(void)
{
    static const struct {
        const char *text, *message;
    } cases[] = {
        { "1 1.0 2.0\n2 3.0\n", "bad.landmarks:2: expected 'id x y', got 2 fields" },
        { "# c\n\n1 1 2 3\n", "bad.landmarks:3: expected 'id x y', got 4 fields" },
        { "0 1.0 2.0\n", "bad.landmarks:1: id '0' is not an integer in 1..65535" },
        { "65536 1.0 2.0\n", "bad.landmarks:1: id '65536' is not an integer in 1..65535" },
        { "1.5 1.0 2.0\n", "bad.landmarks:1: id '1.5' is not an integer in 1..65535" },
        { "7 east 2.0\n", "bad.landmarks:1: x 'east' is not a number (metres)" },
        { "7 1.0 nan\n", "bad.landmarks:1: y 'nan' is not a number (metres)" },
        { "7 1.0 0x10\n", "bad.landmarks:1: y '0x10' is not a number (metres)" },
        { "7 1 1\n8 2 2 # b\n7 3 3\n", "bad.landmarks:3: landmark id 7 given twice (first on line 1)" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *path = tmp_file("bad.landmarks", cases[i].text);
        world_t w = { 0 };
        char err[256] = "";
        int rc = world_load_landmarks(&w, path, err, sizeof err);
        CHECK(rc == -1 && strstr(err, cases[i].message) && strstr(err, "build/tmp/bad.landmarks:"),
              "case %zu: rc %d, '%s', expected '%s'", i, rc, err, cases[i].message);
        CHECK(w.landmarks == NULL && w.n_landmarks == 0, "case %zu: landmarks kept", i);
    }
    const char *good = tmp_file("good.landmarks", "# markers\n\n  3 -1.5 2e-1  # tab and comment\n\t9\t4\t5\r\n");
    world_t w = { 0 };
    char err[256] = "";
    CHECK(world_load_landmarks(&w, good, err, sizeof err) == 0, "%s", err);
    CHECK(w.n_landmarks == 2 && w.landmarks[0].id == 3 && w.landmarks[0].x == -1.5 && w.landmarks[0].y == 0.2 &&
              w.landmarks[1].id == 9 && w.landmarks[1].y == 5.0,
          "%d landmarks", w.n_landmarks);
    free(w.landmarks);
    /* the YAML names a file that is not there */
    char pgm[PATH_MAX], yaml_text[PATH_MAX + 200];
    CHECK(realpath("maps/lab.pgm", pgm) != NULL, "maps/lab.pgm");
    snprintf(yaml_text, sizeof yaml_text, "image: %s\nresolution: 0.05\norigin: [0, 0, 0]\nsabot_landmarks: gone.lm\n",
             pgm);
    const char *yaml = tmp_file("gone.yaml", yaml_text);
    CHECK(world_load(&w, yaml, err, sizeof err) == -1 &&
              strstr(err, "landmarks file build/tmp/gone.lm: No such file or directory"),
          "%s", err);
}

#if !defined(__SANITIZE_ADDRESS__)
static void oneRobotRunsAtLeastFiftyTimesRealTime(void)
{
    floor_t fl = { 0 };
    robot_t *r = place(&fl, 0, 6.0, 4.5, 0.0, 1);
    drive(r, 0.2, 0.3);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    run(&r, 1, 5.0);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double wall = (t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) * 1e-9;
    double factor = 5.0 / wall;
    printf("    figure: speed factor %.0fx real time, %.0f ns per 50 us step\n", factor, wall / 100000 * 1e9);
    CHECK(factor >= 50.0, "only %.1fx real time", factor);
    release(&fl);
}
#endif

int main(void)
{
    printf("test_sim\n");
    char err[256];
    if (world_load(&lab, LAB_MAP, err, sizeof err)) {
        printf("%s\ntest_sim: 0 passed, 1 failed\n", err);
        return 1;
    }
    RUN(theLabMapLoadsWithRosConventions);
    RUN(raycastMeasuresTheDistanceToAWall);
    RUN(robotTurnsInPlaceAtTheExpectedRate);
    RUN(robotStopsAtAWall);
    RUN(robotsCannotDriveThroughEachOther);
    RUN(inertialBoardMeasuresYawRateGravityAndHeading);
    RUN(sonarSeesTheWallAheadAndAnotherRobot);
    RUN(sonarServosSweep);
    RUN(theLabHasItsCeilingLandmarks);
    RUN(landmarkBoardReportsTheNearestMarkerInViewAtItsGeometry);
    RUN(landmarkNoiseHasTheModelledSigmas);
    RUN(aMarkerBeyondTheViewRadiusIsNotSeen);
    RUN(withoutLandmarksTheBoardMeasuresAndSeesNothing);
    RUN(landmarkSequenceFollowsThePeriodAndAgeIsReadTime);
    RUN(badLandmarkConfigurationWritesAreRefusedAndChangeNothing);
    RUN(badLandmarksFilesAreRefusedWithFileAndLine);
    RUN(theCellCurveRisesFromEmptyToTheChargersVoltage);
    RUN(theLabAndTheTwoRoomsHaveTheirDocks);
    RUN(badDocksListsAreRefusedAndChangeNothing);
    RUN(theBatteryDrainsWithTheBaseLoadAndTheMotors);
    RUN(aRobotOnADockChargesUntilFullAndDrainsWhenItLeaves);
    RUN(thePowerBoardAveragesOverItsPeriodAndSaysWhenItCharges);
    RUN(theSameSeedGivesTheSameRun);
    RUN(injectedFaultsCorruptAndDropAnswers);
#if !defined(__SANITIZE_ADDRESS__)
    RUN(oneRobotRunsAtLeastFiftyTimesRealTime);
#endif
    world_free(&lab);
    return REPORT("test_sim");
}
