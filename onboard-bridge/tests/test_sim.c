/*
 * The simulated world: map loading and ray casting, drivetrain kinematics,
 * collisions, the inertial and sonar boards, determinism, fault injection, speed.
 */
#include <math.h>
#include <time.h>

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
    RUN(theSameSeedGivesTheSameRun);
    RUN(injectedFaultsCorruptAndDropAnswers);
#if !defined(__SANITIZE_ADDRESS__)
    RUN(oneRobotRunsAtLeastFiftyTimesRealTime);
#endif
    world_free(&lab);
    return REPORT("test_sim");
}
