#include "hal_host.h"

uint32_t hal_time_us(hal_port_t *port) { return port->time_us; }

uint16_t hal_encoder_count(hal_port_t *port, unsigned motor) { return port->encoder[motor]; }

void hal_pwm_set(hal_port_t *port, unsigned motor, uint16_t duty) { port->pwm[motor] = duty; }

uint16_t hal_adc_current(hal_port_t *port, unsigned motor) { return port->adc_current[motor]; }

void hal_gpio_write(hal_port_t *port, hal_pin_t pin, bool level) { port->pin[pin] = level; }

void hal_uart_send(hal_port_t *port, const uint8_t *frame, size_t len)
{
    if (port->uart_send)
        port->uart_send(port->uart_ctx, frame, len);
}

/* The simulator calls the interrupt and the main loop from one thread. */
uint32_t hal_irq_save(hal_port_t *port)
{
    (void)port;
    return 0;
}

void hal_irq_restore(hal_port_t *port, uint32_t state)
{
    (void)port;
    (void)state;
}
