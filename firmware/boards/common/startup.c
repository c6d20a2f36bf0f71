/* Reset and exception vectors for the Cortex-M4 glove boards: copies .data,
 * clears .bss and calls main. BOARD_N_IRQ (from the board's Makefile flags)
 * sizes the table; a board defines the handlers it uses, every other vector
 * lands in fw_default_handler, which waits for the watchdog. */
#include <stdint.h>

#include "board.h"

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;

void Reset_Handler(void);
void fw_default_handler(void);
void SysTick_Handler(void) __attribute__((weak, alias("fw_default_handler")));
void USART1_IRQHandler(void) __attribute__((weak, alias("fw_default_handler")));
void DMA2_Stream0_IRQHandler(void) __attribute__((weak, alias("fw_default_handler")));

void fw_default_handler(void) {
  /* A fault or an unexpected interrupt: stop here. On the Black Pill the
   * watchdog resets the board within its timeout. */
  for (;;) {
  }
}

typedef void (*fw_vector)(void);

__attribute__((section(".isr_vector"), used)) static const fw_vector vectors[16 + BOARD_N_IRQ] = {
  [0] = (fw_vector)(uintptr_t)&_estack,
  [1] = Reset_Handler,
  [2 ... 14] = fw_default_handler,
  [15] = SysTick_Handler,
  [16 ... 16 + 36] = fw_default_handler,
  [16 + 37] = USART1_IRQHandler, /* IRQ 37 on the F405 and the F411 */
  [16 + 38 ... 16 + 55] = fw_default_handler,
  [16 + 56] = DMA2_Stream0_IRQHandler, /* IRQ 56 on both */
  [16 + 57 ... 15 + BOARD_N_IRQ] = fw_default_handler,
};

void Reset_Handler(void) {
  uint32_t *src = &_sidata;
  for (uint32_t *dst = &_sdata; dst < &_edata;) *dst++ = *src++;
  for (uint32_t *dst = &_sbss; dst < &_ebss;) *dst++ = 0;
  board_main();
}
