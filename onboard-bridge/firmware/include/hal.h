/*
 * Hardware abstraction of the SACT motor board.
 *
 * The firmware core calls only these functions. Two ports implement them:
 *   port/host   - the simulator: encoders, PWM and ADC are wired to the motor
 *                 physics, the UART to the simulated RS-485 bus;
 *   port/stm32f4 - register-level stubs of a Cortex-M target that only has to
 *                 compile (no hardware was available).
 * The port defines struct hal_port; the firmware treats it as opaque. Passing it
 * explicitly (instead of globals) lets the host run several robots in one process;
 * on the target it is a single static instance and the calls inline to register
 * accesses.
 */
#ifndef HAL_H
#define HAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct hal_port hal_port_t;

enum { HAL_MOTORS = 2 };

typedef enum {
    HAL_PIN_BRAKE_M1,   /* high: both low-side switches on, motor terminals shorted */
    HAL_PIN_BRAKE_M2,
    HAL_PIN_FAULT_LED,
    HAL_PIN_RS485_DE,   /* RS-485 driver enable: high while transmitting */
    HAL_PIN_COUNT
} hal_pin_t;

/* Free-running microsecond timer; wraps every 2^32 us (71.6 min): compare by difference. */
uint32_t hal_time_us(hal_port_t *port);

/* 16-bit quadrature counter of the timer in encoder mode (x4 decoding); wraps. */
uint16_t hal_encoder_count(hal_port_t *port, unsigned motor);

/* Locked-antiphase PWM compare value, 0..1023 of a 1024 period; 512 = zero mean voltage. */
void hal_pwm_set(hal_port_t *port, unsigned motor, uint16_t duty);

/* 12-bit sample of the current-sense amplifier, 2048 = zero current (see sact_config.h). */
uint16_t hal_adc_current(hal_port_t *port, unsigned motor);

void hal_gpio_write(hal_port_t *port, hal_pin_t pin, bool level);

/* Queues a frame on the RS-485 UART; the port drives DE around it. */
void hal_uart_send(hal_port_t *port, const uint8_t *frame, size_t len);

/* Critical section between the control interrupt and the main loop. */
uint32_t hal_irq_save(hal_port_t *port);
void hal_irq_restore(hal_port_t *port, uint32_t state);

#endif
