/* USART1 (PA9 TX, PA10 RX, AF7), 8N1, with interrupt-driven queues so the
 * main loop never waits on the line. */
#include "board_f411.h"
#include "board_pins.h"
#include "clock_f411.h"
#include "fw_hal.h"
#include "stm32f4_regs.h"

#define RXQ_BYTES 64u

static volatile uint8_t txq[FW_TXQ_BYTES];
static volatile uint32_t tx_head, tx_tail; /* head: main loop, tail: interrupt */
static volatile uint8_t rxq[RXQ_BYTES];
static volatile uint32_t rx_head, rx_tail; /* head: interrupt, tail: main loop */

void fw_hal_uart_set_baud(uint32_t baud) {
  /* At 96 MHz every rate in FW_BAUD_LIST is within 0.2 % (checked in
   * clock_f411.h); on the HSI alone (a PLL that never locked) the fast ones
   * are not. */
  USART1_BRR = CLOCK_USART_BRR(board_sysclk_hz, baud);
}

void uart_init(uint32_t baud) {
  RCC_APB2ENR |= RCC_APB2ENR_USART1EN;
  board_pin_mode(PIN_UART_TX, GPIO_MODE_AF, 7u);
  board_pin_mode(PIN_UART_RX, GPIO_MODE_AF, 7u);
  fw_hal_uart_set_baud(baud);
  USART1_CR1 = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE | USART_CR1_RXNEIE;
  NVIC_ISER(IRQ_USART1 / 32u) = 1u << (IRQ_USART1 % 32u);
}

void USART1_IRQHandler(void);
void USART1_IRQHandler(void) {
  uint32_t sr = USART1_SR;
  if (sr & (USART_SR_RXNE | USART_SR_ORE)) {
    /* Reading DR clears RXNE and, after the SR read, an overrun. */
    uint8_t b = (uint8_t)USART1_DR;
    if (rx_head - rx_tail < RXQ_BYTES) {
      rxq[rx_head % RXQ_BYTES] = b;
      rx_head++;
    }
  }
  if ((sr & USART_SR_TXE) && (USART1_CR1 & USART_CR1_TXEIE)) {
    if (tx_tail != tx_head) {
      USART1_DR = txq[tx_tail % FW_TXQ_BYTES];
      tx_tail++;
    } else {
      USART1_CR1 &= ~USART_CR1_TXEIE;
    }
  }
}

size_t fw_hal_uart_tx_free(void) {
  return FW_TXQ_BYTES - (tx_head - tx_tail);
}

void fw_hal_uart_write(const uint8_t *data, size_t n) {
  for (size_t i = 0; i < n; i++) {
    txq[tx_head % FW_TXQ_BYTES] = data[i];
    tx_head++;
  }
  /* The interrupt is the only other writer of CR1's TXEIE: mask it while
   * setting the bit. */
  __asm volatile("cpsid i" ::: "memory");
  USART1_CR1 |= USART_CR1_TXEIE;
  __asm volatile("cpsie i" ::: "memory");
}

int fw_hal_uart_tx_idle(void) {
  return tx_head == tx_tail && (USART1_SR & USART_SR_TC);
}

int fw_hal_uart_read(uint8_t *byte) {
  if (rx_head == rx_tail) return 0;
  *byte = rxq[rx_tail % RXQ_BYTES];
  rx_tail++;
  return 1;
}
