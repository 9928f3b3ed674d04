/* Target port: the state behind hal_port_t and the registers both target files use. */
#ifndef HAL_TARGET_H
#define HAL_TARGET_H

#include "hal.h"

#define REG32(addr) (*(volatile uint32_t *)(uintptr_t)(addr))
#define USART2_SR  REG32(0x40004400u)
#define USART2_DR  REG32(0x40004404u)
#define USART_SR_RXNE (1u << 5)
#define USART_SR_TC   (1u << 6)
#define USART_SR_TXE  (1u << 7)

struct hal_port {
    uint32_t time_high;   /* extends the 16-bit timebase */
    uint16_t time_last;
};

#endif
