/*
 * SACT control loop: step response on the simulated robot, velocity ramps, faults,
 * deadman, and the modular arithmetic that must survive counter wrap-around.
 */
#include <math.h>

#include "bus_client.h"
#include "check.h"

static arena_t arena;
static robot_t *slot;

static robot_t *fresh(void)
{
    free(slot);
    return make_robot(7, &arena, &slot);
}

static int32_t position_of(const robot_t *r, int m) { return (int32_t)r->sact.motor[m].position_counts; }

static void run(robot_t *r, double seconds)
{
    for (long i = 0; i < lround(seconds * 1e6 / SACT_TS_US); i++)
        robot_step(r);
}

/* Figures of a step response (robot on its wheels, both motors stepped). */
typedef struct {
    double rise_ms, overshoot_pct, settling_ms;
    int32_t final_error;
    int32_t worst_late_error;   /* max |error| in the last 100 ms */
} step_figures_t;

static step_figures_t step_response(robot_t *r, int16_t step)
{
    run(r, 0.1);
    int32_t start = position_of(r, 0);
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_POSITION_STEP, (uint16_t)step);
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_RIGHT, MB_SACT_MOTOR_POSITION_STEP, (uint16_t)step);
    double t10 = -1, t90 = -1, peak = 0, settled_at = 0;
    step_figures_t f = { 0 };
    const int steps = 8000;   /* 400 ms */
    for (int i = 1; i <= steps; i++) {
        robot_step(r);
        double y = position_of(r, 0) - start, t = i * SACT_TS_US * 1e-3;
        if (t10 < 0 && y >= 0.1 * step) t10 = t;
        if (t90 < 0 && y >= 0.9 * step) t90 = t;
        if (y > peak) peak = y;
        if (fabs(y - step) > 0.02 * step) settled_at = t;   /* 2 % band */
        if (i > steps - 2000 && abs((int)(y - step)) > f.worst_late_error)
            f.worst_late_error = abs((int)(y - step));
    }
    f.rise_ms = t90 - t10;
    f.overshoot_pct = (peak - step) / step * 100.0;
    f.settling_ms = settled_at;
    f.final_error = position_of(r, 0) - start - step;
    return f;
}

static void positionStepOf200CountsMeetsTheSpecification(void)
{
    robot_t *r = fresh();
    step_figures_t f = step_response(r, 200);
    printf("    figure: 200-count step: rise %.2f ms, overshoot %.1f %%, settling (2 %%) %.1f ms, "
           "final error %d counts\n", f.rise_ms, f.overshoot_pct, f.settling_ms, f.final_error);
    CHECK(f.rise_ms > 0 && f.rise_ms <= 25.0, "rise %.2f ms", f.rise_ms);
    CHECK(f.overshoot_pct <= 5.0, "overshoot %.1f %%", f.overshoot_pct);
    CHECK(f.settling_ms <= 100.0, "settling %.1f ms", f.settling_ms);
    CHECK(f.worst_late_error <= 1, "steady-state error %d counts", f.worst_late_error);
    CHECK(!(r->sact.motor[0].status & MB_SACT_MOTOR_STATUS_FAULT), "fault");
}

static void negativeStepIsSymmetric(void)
{
    robot_t *r = fresh();
    step_figures_t up = step_response(r, 200);
    robot_t *r2 = fresh();
    (void)r;
    run(r2, 0.1);
    int32_t start = position_of(r2, 0);
    sact_write_register(&r2->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_POSITION_STEP, (uint16_t)-200);
    sact_write_register(&r2->sact, MB_SACT_FILE_MOTOR_RIGHT, MB_SACT_MOTOR_POSITION_STEP, (uint16_t)-200);
    run(r2, 0.4);
    CHECK(abs(position_of(r2, 0) - start + 200) <= 1, "down step ends %d off", position_of(r2, 0) - start + 200);
    CHECK(up.worst_late_error <= 1, "up step");
}

static void velocityRampHonoursTheAccelerationParameter(void)
{
    robot_t *r = fresh();
    const uint16_t accel = 2000;     /* 2^-24 counts/Ts^2 = 0.26 m/s^2 at the wheel */
    const int16_t target = 1000;     /* 8.8 counts/Ts = 0.42 m/s */
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_ACCELERATION, accel);
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, (uint16_t)target);
    int32_t prev = r->sact.motor[0].commanded_velocity;
    long expected_steps = ((long)target << 16) / accel;   /* 8.8 -> 8.24 */
    long ramp_steps = 0;
    int bad_increment = 0;
    while (r->sact.motor[0].commanded_velocity < ((int32_t)target << 16) && ramp_steps < 10 * expected_steps) {
        robot_step(r);
        int32_t v = r->sact.motor[0].commanded_velocity;
        if (v - prev != accel && v != ((int32_t)target << 16))
            bad_increment++;
        prev = v;
        ramp_steps++;
    }
    CHECK(bad_increment == 0, "%d steps changed velocity by something else than the acceleration", bad_increment);
    CHECK(labs(ramp_steps - expected_steps) <= 1, "ramp took %ld steps, expected %ld", ramp_steps, expected_steps);
    run(r, 0.3);
    /* measured velocity (16-sample window, 1/256 count per Ts) follows the command */
    int16_t measured = (int16_t)sact_read_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_MEASURED_VELOCITY);
    CHECK(abs(measured - target) <= 40, "measured %d vs %d", measured, target);
    CHECK(r->sact.motor[0].status & MB_SACT_MOTOR_STATUS_AT_SETPOINT, "at-set-point flag");
    printf("    figure: ramp of %d (8.8 counts/Ts) at %u: %ld steps = %.1f ms, measured %d after 300 ms\n", target,
           accel, ramp_steps, ramp_steps * 0.05, measured);
}

static void robotReachesCommandedWheelSpeed(void)
{
    robot_t *r = fresh();
    /* 0.3 m/s: 0.3 * 186878 counts/m * 50e-6 * 256 = 717.6 */
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, 718);
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_RIGHT, 718);
    run(r, 2.0);
    CHECK(fabs(r->body.v - 0.3) < 0.006, "body speed %.4f m/s", r->body.v);
    CHECK(fabs(r->body.omega) < 0.01, "yaw rate %.4f", r->body.omega);
}

/* A stand-alone board with an ideal plant: the motor speed follows the bridge voltage
 * with a first-order lag. Fast enough to run billions of counts. */
typedef struct {
    struct hal_port hal;
    sact_board_t board;
    double position[2], speed[2];   /* counts, counts per Ts */
} bench_board_t;

static void bench_init(bench_board_t *b, uint16_t encoder_start)
{
    memset(b, 0, sizeof *b);
    b->hal.encoder[0] = b->hal.encoder[1] = encoder_start;
    b->hal.adc_current[0] = b->hal.adc_current[1] = SACT_ADC_ZERO;
    b->position[0] = b->position[1] = encoder_start;
    sact_init(&b->board, &b->hal, 115200);
}

static void bench_step(bench_board_t *b, bool stalled)
{
    sact_control_isr(&b->board);
    /* full voltage -> the configured no-load speed, time constant 200 samples */
    const sact_robot_config_t *c = &b->board.config;
    double full = c->no_load_rpm / 60.0 * 4.0 * c->encoder_lines * SACT_TS_US * 1e-6;
    for (int m = 0; m < 2; m++) {
        double target = stalled || b->hal.pin[HAL_PIN_BRAKE_M1 + m] ? 0.0 : (b->hal.pwm[m] - 512.0) / 512.0 * full;
        b->speed[m] += (target - b->speed[m]) / 200.0;
        b->position[m] += b->speed[m];
        b->hal.encoder[m] = (uint16_t)(int64_t)floor(b->position[m]);
    }
    b->hal.time_us += SACT_TS_US;
}

/* commanded minus measured position in whole counts */
static int32_t mod_diff_counts(const sact_motor_t *M)
{
    uint32_t d = M->commanded - M->position;
    return (int32_t)(d <= INT32_MAX ? (int32_t)d : -(int32_t)(~d) - 1) / 256;
}

static void positionStaysCorrectPastTwoToThe32Counts(void)
{
    static bench_board_t b;
    bench_init(&b, 0xFF00);   /* the 16-bit counter wraps within the first samples */
    /* raise the speed limit so the run covers 2^32 counts in ~100 M samples */
    sact_write_register(&b.board, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_MAX_SPEED, 5000);
    sact_write_register(&b.board, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_MAX_ACCEL, 10000);
    sact_write_register(&b.board, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_NO_LOAD_SPEED, 30000);
    sact_write_register(&b.board, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_ACCELERATION, 65535);
    int16_t v = (int16_t)b.board.max_velocity_setpoint;   /* ~46.7 counts per Ts */
    sact_write_register(&b.board, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, (uint16_t)v);
    double start = b.position[0];
    /* The loop must behave the same after the wraps as before them: compare the worst
     * tracking error of an early window (no wrap of the 24.8 position yet, which needs
     * 2^24 counts) with the last window, past 2^32 counts. */
    int32_t early_error = 0, late_error = 0;
    bool crossed_2_31 = false;
    uint64_t steps = 0;
    const double total = 4294967296.0 + 5e6;
    while (b.position[0] - start < total) {
        bench_step(&b, false);
        steps++;
        int32_t e = abs(b.board.motor[0].error);
        if (steps > 100000 && steps <= 300000 && e > early_error)
            early_error = e;
        if (b.position[0] - start > total - 9e6 && e > late_error)
            late_error = e;
        if (b.position[0] - start > 2147483648.0)
            crossed_2_31 = true;
        if (b.board.motor[0].status & MB_SACT_MOTOR_STATUS_FAULT)
            break;
    }
    CHECK(crossed_2_31, "never passed 2^31 counts");
    CHECK(!(b.board.motor[0].status & MB_SACT_MOTOR_STATUS_FAULT), "fault after %llu samples", (unsigned long long)steps);
    /* the reported position is the true count modulo 2^32 (the encoder as last sampled) */
    sact_control_isr(&b.board);
    uint32_t truth = (uint32_t)(uint64_t)((int64_t)floor(b.position[0]) - 0xFF00);
    CHECK(b.board.motor[0].position_counts == truth, "position %u, true %u", b.board.motor[0].position_counts, truth);
    CHECK(late_error <= early_error + 16, "tracking error %d/16 counts after the wraps, %d/16 before", late_error,
          early_error);
    CHECK(early_error < 16 * 8, "tracking error %d/16 counts", early_error);
    /* stop: the loop comes to rest on the commanded position */
    sact_write_register(&b.board, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, 0);
    for (int i = 0; i < 40000; i++)
        bench_step(&b, false);
    int32_t rest = mod_diff_counts(&b.board.motor[0]);
    CHECK(abs(rest) <= 4, "at rest %d counts from the command", rest);
    printf("    figure: %.4g counts (%llu samples) at %d/256 counts per Ts; worst error %.2f counts before "
           "the wraps, %.2f after\n", b.position[0] - start, (unsigned long long)steps, v, early_error / 16.0,
           late_error / 16.0);
}

static void integratorIsClampedAndNeverWraps(void)
{
    static bench_board_t b;
    bench_init(&b, 0);
    sact_write_register(&b.board, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_FOLLOWING_ERROR_LIMIT, 2047);
    sact_write_register(&b.board, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_KI, 2000);
    sact_write_register(&b.board, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_POSITION_STEP, 2000);
    const sact_motor_t *M = &b.board.motor[0];
    bool ever_negative = false, ever_beyond = false;
    /* stalled rotor for 60 s of control time: the error stays saturated positive */
    for (long i = 0; i < 1200000; i++) {
        bench_step(&b, true);
        ever_negative |= M->integrator < 0;
        ever_beyond |= M->integrator > M->integrator_max;
    }
    CHECK(!ever_negative, "integrator changed sign");
    CHECK(!ever_beyond, "integrator beyond its clamp");
    CHECK(M->pwm == SACT_PWM_MAX, "output %u, expected %u", M->pwm, SACT_PWM_MAX);
    /* release: no wind-up, so the overshoot is bounded by the integral limit */
    double before = b.position[0];
    int32_t peak = 0;
    for (long i = 0; i < 200000; i++) {
        bench_step(&b, false);
        int32_t over = (int32_t)(b.position[0] - before) - 2000;
        if (over > peak)
            peak = over;
    }
    CHECK(peak < 200, "overshoot after release %d counts", peak);
    CHECK(abs(M->error) <= 16, "settled error %d/16", M->error);
}

static void overCurrentBrakesAndLatchesAFault(void)
{
    robot_t *r = fresh();
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_CURRENT_LIMIT, 500);
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_POSITION_STEP, 1000);
    run(r, 0.05);
    uint16_t st = r->sact.motor[0].status;
    CHECK((st & MB_SACT_MOTOR_STATUS_FAULT) && (st & MB_SACT_MOTOR_STATUS_OVER_CURRENT), "status %04x", st);
    CHECK(r->hal.pin[HAL_PIN_BRAKE_M1] && r->hal.pin[HAL_PIN_FAULT_LED], "brake/LED not set");
    CHECK(!(r->sact.motor[1].status & MB_SACT_MOTOR_STATUS_FAULT), "the other motor faulted");
    run(r, 0.5);
    CHECK(fabs(r->body.wheel[0].omega) < 0.05, "wheel still turning at %.3f rad/s", r->body.wheel[0].omega);
    CHECK(bus_write(r, MB_SACT_ADDRESS, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, 100) ==
              MB_EXC_SERVER_DEVICE_FAILURE, "motion accepted while faulted");
    CHECK(bus_write(r, MB_SACT_ADDRESS, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_STATUS, 0) == 0, "acknowledge");
    CHECK(!(r->sact.motor[0].status & MB_SACT_MOTOR_STATUS_FAULT) && !r->hal.pin[HAL_PIN_FAULT_LED], "not cleared");
}

static void followingErrorBrakesAndLatchesAFault(void)
{
    static bench_board_t b;
    bench_init(&b, 0);
    sact_write_register(&b.board, MB_SACT_FILE_MOTOR_RIGHT, MB_SACT_MOTOR_FOLLOWING_ERROR_LIMIT, 300);
    sact_write_register(&b.board, MB_SACT_FILE_MOTOR_RIGHT, MB_SACT_MOTOR_POSITION_STEP, 500);
    bench_step(&b, true);
    uint16_t st = b.board.motor[1].status;
    CHECK((st & MB_SACT_MOTOR_STATUS_FAULT) && (st & MB_SACT_MOTOR_STATUS_FOLLOWING_ERROR), "status %04x", st);
    CHECK(b.hal.pin[HAL_PIN_BRAKE_M2] && b.hal.pwm[1] == SACT_PWM_ZERO, "not braked");
}

static void brakeHoldsAndReleasesWithoutAJump(void)
{
    robot_t *r = fresh();
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, 700);
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_RIGHT, 700);
    run(r, 1.0);
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_BRAKE, 1);
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_RIGHT, MB_SACT_MOTOR_BRAKE, 1);
    run(r, 1.5);
    CHECK(fabs(r->body.v) < 0.01, "still moving at %.3f m/s", r->body.v);
    CHECK(r->sact.motor[0].status & MB_SACT_MOTOR_STATUS_BRAKING, "braking flag");
    CHECK(r->sact.motor[0].velocity_setpoint == 700, "brake must not forget the set-point");
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, 0);
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_RIGHT, 0);
    int32_t held = position_of(r, 0);
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_BRAKE, 0);
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_RIGHT, MB_SACT_MOTOR_BRAKE, 0);
    run(r, 0.2);
    CHECK(abs(position_of(r, 0) - held) <= 2, "jumped %d counts on release", position_of(r, 0) - held);
}

static void deadmanStopsTheRobotWhenCommandsStop(void)
{
    robot_t *r = fresh();
    CHECK(bus_write(r, MB_SACT_ADDRESS, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_COMMAND_TIMEOUT, 200) == 0, "timeout");
    uint16_t both[2] = { 700, 700 };
    frame_t f = write_request(MB_SACT_ADDRESS, MB_SACT_FILE_DRIVE, 0, both, 2), a;
    transact(r, &f, &a);
    run(r, 0.15);
    CHECK(r->sact.motor[0].velocity_setpoint == 700, "stopped too early");
    run(r, 1.5);
    CHECK(r->sact.motor[0].velocity_setpoint == 0 && r->sact.motor[1].velocity_setpoint == 0, "set-points kept");
    CHECK(fabs(r->body.v) < 0.005, "robot still moving at %.3f m/s", r->body.v);
}

static void tighterSpeedLimitClampsTheCurrentSetPoint(void)
{
    robot_t *r = fresh();
    sact_write_register(&r->sact, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_VELOCITY_SETPOINT, 1100);
    CHECK(sact_write_register(&r->sact, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_MAX_SPEED, 250) == MB_OK, "write");
    CHECK(r->sact.motor[0].velocity_setpoint == r->sact.max_velocity_setpoint, "set-point %d, limit %d",
          r->sact.motor[0].velocity_setpoint, r->sact.max_velocity_setpoint);
    CHECK(abs(r->sact.max_velocity_setpoint - 598) <= 1, "limit for 0.25 m/s %d", r->sact.max_velocity_setpoint);
}

static void gearRatioOf66IsHonoured(void)
{
    robot_t *r = fresh();
    sact_write_register(&r->sact, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_GEAR_RATIO, 6600);
    /* 0.5 m/s with 66:1 -> 0.5 / (2 pi 0.075) * 66 * 2048 * 50e-6 * 256 = 1835.6 */
    CHECK(abs(r->sact.max_velocity_setpoint - 1836) <= 1, "limit %d", r->sact.max_velocity_setpoint);
}

/* The board's own recording of a step (map file step_capture) is the measured position
 * every `decimation` periods from the period after the step, relative to the step's. */
static void stepCaptureRecordsTheResponseAtTheControlRate(void)
{
    robot_t *r = fresh();
    run(r, 0.1);
    sact_board_t *b = &r->sact;
    CHECK(sact_write_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_MOTOR,
                              MB_SACT_FILE_MOTOR_RIGHT) == MB_OK, "motor");
    CHECK(sact_write_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_DECIMATION, 8) == MB_OK, "dec");
    int32_t start = position_of(r, 1), left = position_of(r, 0);
    CHECK(sact_write_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_STEP, 300) == MB_OK, "step");
    CHECK(sact_read_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_STEP) == 0, "step reads 0");
    int16_t expected[SACT_CAPTURE_SAMPLES];
    for (int i = 0; i < SACT_CAPTURE_SAMPLES * 8; i++) {
        robot_step(r);   /* the board samples at the end of its control period */
        if (i % 8 == 0)
            expected[i / 8] = (int16_t)(position_of(r, 1) - start);
    }
    CHECK(sact_read_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_RECORDED) ==
          SACT_CAPTURE_SAMPLES, "recorded %u", sact_read_register(b, MB_SACT_FILE_STEP_CAPTURE,
                                                                   MB_SACT_STEP_CAPTURE_RECORDED));
    int mismatches = 0;
    for (int k = 0; k < SACT_CAPTURE_SAMPLES; k++)
        mismatches += (int16_t)sact_read_register(b, MB_SACT_FILE_STEP_CAPTURE,
                                                  (uint16_t)(MB_SACT_STEP_CAPTURE_RESPONSE + k)) != expected[k];
    CHECK(mismatches == 0, "%d samples differ from the positions measured", mismatches);
    CHECK(expected[0] == 0 && abs(expected[SACT_CAPTURE_SAMPLES - 1] - 300) <= 6, "from 0 to within 2 %% of the step: %d..%d",
          expected[0], expected[SACT_CAPTURE_SAMPLES - 1]);
    printf("    figure: 300-count step recorded by the board: sample 10 (4 ms) = %d counts\n", expected[10]);
    CHECK(abs(position_of(r, 0) - left) <= 20, "the other wheel held (moved %d counts)", position_of(r, 0) - left);
    /* more periods: the recording stays as it was */
    run(r, 0.01);
    CHECK(sact_read_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_RESPONSE) == 0, "kept");
}

static void stepCaptureIsRefusedOnABrakedOrFaultedMotor(void)
{
    robot_t *r = fresh();
    sact_board_t *b = &r->sact;
    sact_write_register(b, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_BRAKE, 1);
    run(r, 0.01);
    uint32_t before = b->motor[0].commanded;
    CHECK(sact_write_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_STEP, 100) ==
          MB_SERVER_DEVICE_FAILURE, "braked: exception 4");
    CHECK(b->motor[0].commanded == before && !b->capture.active, "nothing changed");
    CHECK(sact_write_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_STEP, 2049) ==
          MB_ILLEGAL_DATA_VALUE, "over the map's bound: exception 3");
    CHECK(sact_write_register(b, MB_SACT_FILE_STEP_CAPTURE, MB_SACT_STEP_CAPTURE_MOTOR, 3) ==
          MB_ILLEGAL_DATA_VALUE, "motor 3: exception 3");
}

int main(void)
{
    printf("test_control\n");
    RUN(positionStepOf200CountsMeetsTheSpecification);
    RUN(negativeStepIsSymmetric);
    RUN(velocityRampHonoursTheAccelerationParameter);
    RUN(robotReachesCommandedWheelSpeed);
    RUN(positionStaysCorrectPastTwoToThe32Counts);
    RUN(integratorIsClampedAndNeverWraps);
    RUN(overCurrentBrakesAndLatchesAFault);
    RUN(followingErrorBrakesAndLatchesAFault);
    RUN(brakeHoldsAndReleasesWithoutAJump);
    RUN(deadmanStopsTheRobotWhenCommandsStop);
    RUN(tighterSpeedLimitClampsTheCurrentSetPoint);
    RUN(gearRatioOf66IsHonoured);
    RUN(stepCaptureRecordsTheResponseAtTheControlRate);
    RUN(stepCaptureIsRefusedOnABrakedOrFaultedMotor);
    free(slot);
    return REPORT("test_control");
}
