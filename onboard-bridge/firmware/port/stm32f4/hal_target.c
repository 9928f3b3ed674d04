/*
 * Target port of the SACT HAL: register-level sketch for an STM32F4-class MCU
 * (TIM2/TIM5 in encoder mode, TIM1 centre-aligned PWM at 20 kHz for the two
 * locked-antiphase bridges, ADC1 injected channels triggered by TIM1, USART2 with
 * the RS-485 driver enable on a GPIO). No hardware was available: this port only has
 * to compile, so that the core stays free of host assumptions. Addresses follow the
 * STM32F405 reference manual (RM0090); they are not exercised by any test.
 */
#include "hal_target.h"

#define TIM2_CNT   REG32(0x40000024u)
#define TIM5_CNT   REG32(0x40000C24u)
#define TIM1_CCR1  REG32(0x40010034u)
#define TIM1_CCR2  REG32(0x40010038u)
#define TIM6_CNT   REG32(0x40001024u)   /* 1 MHz free-running timebase (16-bit, extended below) */
#define ADC1_JDR1  REG32(0x4001203Cu)
#define ADC1_JDR2  REG32(0x40012040u)
#define GPIOB_BSRR REG32(0x40020418u)

static const uint8_t pin_bit[HAL_PIN_COUNT] = { 0, 1, 2, 3 };   /* PB0..PB3 */

uint32_t hal_time_us(hal_port_t *port)
{
    uint16_t now = (uint16_t)TIM6_CNT;
    if (now < port->time_last)
        port->time_high += 0x10000u;
    port->time_last = now;
    return port->time_high | now;
}

uint16_t hal_encoder_count(hal_port_t *port, unsigned motor)
{
    (void)port;
    return (uint16_t)(motor == 0 ? TIM2_CNT : TIM5_CNT);
}

void hal_pwm_set(hal_port_t *port, unsigned motor, uint16_t duty)
{
    (void)port;
    if (motor == 0)
        TIM1_CCR1 = duty;
    else
        TIM1_CCR2 = duty;
}

uint16_t hal_adc_current(hal_port_t *port, unsigned motor)
{
    (void)port;
    return (uint16_t)(motor == 0 ? ADC1_JDR1 : ADC1_JDR2);
}

void hal_gpio_write(hal_port_t *port, hal_pin_t pin, bool level)
{
    (void)port;
    GPIOB_BSRR = level ? (1u << pin_bit[pin]) : (1u << (pin_bit[pin] + 16u));
}

void hal_uart_send(hal_port_t *port, const uint8_t *frame, size_t len)
{
    hal_gpio_write(port, HAL_PIN_RS485_DE, true);
    for (size_t i = 0; i < len; i++) {
        while (!(USART2_SR & USART_SR_TXE)) {
        }
        USART2_DR = frame[i];
    }
    while (!(USART2_SR & USART_SR_TC)) {
    }
    hal_gpio_write(port, HAL_PIN_RS485_DE, false);
}

uint32_t hal_irq_save(hal_port_t *port)
{
    (void)port;
    uint32_t primask = 0;
#if defined(__arm__)
    __asm volatile("mrs %0, primask\n cpsid i" : "=r"(primask)::"memory");
#endif
    return primask;
}

void hal_irq_restore(hal_port_t *port, uint32_t state)
{
    (void)port;
#if defined(__arm__)
    __asm volatile("msr primask, %0" ::"r"(state) : "memory");
#else
    (void)state;
#endif
}
