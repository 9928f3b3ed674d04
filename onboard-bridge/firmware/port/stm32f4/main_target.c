/*
 * Target entry points: the control interrupt at 20 kHz (TIM1 update), the UART
 * receive interrupt and the main loop. Compiled but never run (no hardware).
 */
#include "hal_target.h"
#include "sact.h"

static hal_port_t port;
static sact_board_t board;

void TIM1_UP_TIM10_IRQHandler(void);
void USART2_IRQHandler(void);
int main(void);

void TIM1_UP_TIM10_IRQHandler(void)
{
    sact_control_isr(&board);
}

void USART2_IRQHandler(void)
{
    if (USART2_SR & USART_SR_RXNE)
        sact_uart_rx_isr(&board, (uint8_t)USART2_DR);
}

int main(void)
{
    sact_init(&board, &port, MB_SERIAL_BAUD);
    for (;;)
        sact_poll(&board);
}
