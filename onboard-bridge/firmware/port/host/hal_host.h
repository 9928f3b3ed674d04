/*
 * Host port of the SACT HAL: the "hardware" is a plain struct that the simulator
 * fills before each control interrupt (encoders, ADC, time) and reads after it
 * (PWM, GPIO). One instance per simulated robot.
 */
#ifndef HAL_HOST_H
#define HAL_HOST_H

#include "hal.h"

struct hal_port {
    uint32_t time_us;                 /* simulated microsecond timer */
    uint16_t encoder[HAL_MOTORS];     /* 16-bit quadrature counters */
    uint16_t adc_current[HAL_MOTORS]; /* 12-bit current-sense samples */
    uint16_t pwm[HAL_MOTORS];         /* last compare values */
    bool pin[HAL_PIN_COUNT];
    /* UART transmit: the simulated RS-485 bus takes the whole frame */
    void (*uart_send)(void *ctx, const uint8_t *frame, size_t len);
    void *uart_ctx;
};

#endif
