/* What the Black Pill's driver files share. */
#ifndef BOARD_F411_H
#define BOARD_F411_H

#include <stdint.h>

/* The system clock clock_init reached: 96 MHz, or 16 MHz if the PLL failed.
 * APB2 (USART1, ADC) runs at it; APB1's timers too (APB1 /2, timers x2). */
extern uint32_t board_sysclk_hz;

/* Sets a pin's mode (GPIO_MODE_*) and, for GPIO_MODE_AF, its function. */
void board_pin_mode(unsigned pin, unsigned mode, unsigned af);
/* USART1 on PA9/PA10, 8N1, interrupt-driven queues. */
void uart_init(uint32_t baud);
/* TIM3 paces ADC1 scans; DMA2 stream 0 moves them; its interrupt hands each
 * tick's block to the core. */
void sampling_start(void);

#endif
