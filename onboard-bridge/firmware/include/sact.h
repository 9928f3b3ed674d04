/*
 * SACT motor board firmware core: two position/velocity loops at Ts = 50 us and the
 * Modbus register interface (docs/sact-modbus-map.json, files 1-4).
 *
 * Control law per motor and per sample (thesis, chapter 4, written out):
 *   measured position   p += wrap-safe (int16)(encoder - last encoder)       [24.8 counts]
 *   commanded velocity  v moves toward the set-point by at most `acceleration` [8.24 counts/Ts]
 *   commanded position  c += v                                                [24.8 counts]
 *   error               e = sat16((c - p) >> 4)                               [12.4 counts]
 *   output              u = (Kp e + Kd (e - e[k-16])) >> 8 + clamp((Ki sum e) >> 16) + ff(v)
 *   PWM                 d = clamp(512 + u, 21, 1003)
 * with conditional integration (the sum stops growing while the output saturates in
 * the error's direction) and a clamp of the integral term: together the anti-windup.
 * Positions are modular: only differences of uint32 values are used, so the loop is
 * indifferent to where the counters wrap.
 *
 * Faults (both latch until the master writes 0 to `status`): the mean of the last 16
 * current samples above `current_limit`, or |c - p| above `following_error_limit`.
 * A fault brakes the motor (H-bridge low sides on) and zeroes the set-point.
 *
 * Threading: sact_control_isr() runs in the timer interrupt; sact_poll() and the
 * Modbus handlers run in the main loop and change parameters inside hal_irq_save().
 */
#ifndef SACT_H
#define SACT_H

#include <stdbool.h>
#include <stdint.h>

#include "hal.h"
#include "modbus_rtu.h"
#include "sact_config.h"

typedef struct {
    /* parameters (registers) */
    int16_t velocity_setpoint;      /* 8.8 counts/Ts */
    uint16_t acceleration;          /* 2^-24 counts/Ts^2 */
    bool brake;
    uint16_t kp, ki, kd, integral_limit;
    uint16_t following_error_limit; /* counts */
    uint16_t current_limit_ma;

    /* derived parameter, computed in the main loop when Ki or the limit change */
    int32_t integrator_max;         /* |sum e| that makes the integral term reach the limit */

    /* control state (interrupt) */
    uint16_t last_encoder;
    uint32_t position;              /* 24.8, modular */
    uint32_t position_counts;       /* whole counts, modular: the reported position */
    uint32_t commanded;             /* 24.8, modular */
    uint32_t commanded_frac;        /* 2^-24 count remainder of the velocity integration */
    int32_t commanded_velocity;     /* 8.24 counts/Ts */
    int16_t encoder_window[SACT_WINDOW];  /* last 16 count differences */
    int32_t encoder_window_sum;
    int16_t error_window[SACT_WINDOW];    /* last 16 errors, for the derivative */
    uint8_t window_index;
    int16_t error;                  /* 12.4 counts */
    int32_t integrator;             /* sum of e, 12.4 counts x samples */
    uint16_t pwm;
    bool saturated;
    int16_t current_window[1u << SACT_CURRENT_AVG_LOG2];  /* mA */
    int32_t current_sum;
    uint8_t current_index;
    uint16_t status;                /* MB_SACT_MOTOR_STATUS_* bits */
} sact_motor_t;

typedef struct {
    uint16_t encoder_lines, gear_ratio_x100, no_load_rpm, wheel_radius_01mm;
    uint16_t max_speed_mm_s, max_accel_mm_s2, command_timeout_ms;
} sact_robot_config_t;

/* Step-response recording (map file step_capture): written in the main loop under the
 * Modbus lock, filled by the control interrupt. */
#define SACT_CAPTURE_SAMPLES MB_SACT_STEP_CAPTURE_RECORDED_MAX
typedef struct {
    uint8_t motor;                  /* index 0/1 */
    uint16_t decimation;            /* control periods per sample */
    uint16_t phase;                 /* periods until the next sample */
    uint16_t recorded;
    bool active;
    uint32_t start;                 /* position_counts at the step */
    int16_t response[SACT_CAPTURE_SAMPLES];  /* counts relative to start */
} sact_capture_t;

typedef struct {
    hal_port_t *hal;
    sact_motor_t motor[HAL_MOTORS];
    sact_robot_config_t config;
    /* limits derived from config, in register units */
    int32_t max_velocity_setpoint;  /* 8.8 counts/Ts */
    int32_t max_acceleration;       /* 2^-24 counts/Ts^2 */
    int32_t feedforward_gain;       /* PWM LSB per 8.8 velocity LSB, 16.16 */
    uint32_t last_command_us;
    bool deadman_tripped;
    sact_capture_t capture;
    /* Idempotency of write requests (config record command_sequence): the last key applied,
     * whether the request being handled repeats it (then nothing of it is applied), and how
     * many registers the request has written so far (the key must come first). */
    uint16_t last_sequence;
    bool duplicate_request;
    uint16_t request_writes;
    uint32_t duplicates;            /* requests answered but not applied again */
    uint32_t irq_state;             /* saved by the Modbus lock */
    mb_slave_t modbus;
} sact_board_t;

void sact_init(sact_board_t *b, hal_port_t *hal, uint32_t baud);

/* Timer interrupt, every Ts: both motors, then the step-response recording. */
void sact_control_isr(sact_board_t *b);

/* One control step of one motor (exposed for the callgrind measurement). */
void sact_motor_step(sact_board_t *b, unsigned m);

/* UART receive interrupt. */
void sact_uart_rx_isr(sact_board_t *b, uint8_t byte);

/* Main loop body: Modbus frames, deadman. */
void sact_poll(sact_board_t *b);

/* Writes that came through Modbus, exposed so tests can drive the board directly.
 * Return the exception the Modbus path would have answered (MB_OK = applied). */
mb_exception_t sact_write_register(sact_board_t *b, uint16_t file, uint16_t record, uint16_t value);
uint16_t sact_read_register(sact_board_t *b, uint16_t file, uint16_t record);

#endif
