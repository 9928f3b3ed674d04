/*
 * Fixed hardware constants of the SACT board, in one place.
 *
 * Values a master can change (gains, robot geometry, limits) are registers whose
 * defaults come from docs/sact-modbus-map.json (the robot's constants from docs/sabot-robot.properties,
 * which the map names); the numbers here are properties
 * of the board itself (timer, PWM, ADC, shunt) and of the fixed-point formats.
 */
#ifndef SACT_CONFIG_H
#define SACT_CONFIG_H

#include "modbus_map.h"

/* Control period Ts: the PWM period and the control interrupt (20 kHz). */
#define SACT_TS_US            MB_CONTROL_PERIOD_US

/* 10-bit locked-antiphase PWM: duty d gives a mean bridge voltage Vs*(2d/1024 - 1).
 * The limits keep a minimum on/off time for the bootstrap gate drivers. */
#define SACT_PWM_PERIOD       (1u << MB_CONTROL_PWM_BITS)
#define SACT_PWM_ZERO         MB_CONTROL_PWM_ZERO
#define SACT_PWM_MIN          MB_CONTROL_PWM_MIN
#define SACT_PWM_MAX          MB_CONTROL_PWM_MAX
#define SACT_PWM_SPAN         (SACT_PWM_MAX - SACT_PWM_ZERO)   /* 491: largest |u| */

/* Quadrature decoding counts every edge of both channels. */
#define SACT_QUADRATURE       MB_CONTROL_QUADRATURE

/* Fixed-point formats.
 *   position        : 24.8 counts in a uint32 (wraps every 2^24 counts; only differences are used)
 *   velocity set-pt : 8.8 counts per Ts (register format)
 *   velocity command: 8.24 counts per Ts in an int32 (so small accelerations still ramp)
 *   acceleration    : 2^-24 counts per Ts^2 (register format)
 *   error           : 12.4 counts in an int16 ("error reduced to 16 bits") */
#define SACT_POS_FRAC_BITS    8
#define SACT_VSET_FRAC_BITS   8
#define SACT_VCMD_FRAC_BITS   24
#define SACT_ERR_FRAC_BITS    4

/* Velocity and derivative use the change over a 16-sample window (0.8 ms), because
 * one 50 us sample sees only 0..5 counts at full speed: too coarse to differentiate. */
#define SACT_WINDOW_LOG2      4
#define SACT_WINDOW           (1u << SACT_WINDOW_LOG2)

/* PID output scaling: u = (Kp*e + Kd*de) >> 8 + (Ki*sum e) >> 16, u in PWM LSB. */
#define SACT_PD_SHIFT         8
#define SACT_I_SHIFT          16

/* Current sense: 0.05 ohm shunt, gain-5 amplifier, 3.3 V reference, 12-bit ADC, mid-rail
 * offset: 0.25 V/A, so one LSB = 3300 mV / 4096 / 0.25 V/A = 3.2227 mA. The mA conversion
 * is (raw - 2048) * 52800 >> 14 (52800 / 16384 = 3.2227). Range +-6.6 A. */
#define SACT_ADC_ZERO         2048
#define SACT_ADC_MA_NUM       52800
#define SACT_ADC_MA_SHIFT     14
#define SACT_CURRENT_AVG_LOG2 4   /* mean over 16 samples (0.8 ms) */

#define SACT_FIRMWARE_VERSION MB_SACT_CONFIG_FIRMWARE_VERSION_DEFAULT

#endif
