/* The glove firmware on QEMU's netduinoplus2 (STM32F405), for CI.
 *
 * What QEMU 7.2 models decides the shape (firmware/README.md, "QEMU"):
 * SysTick paces the 1 kHz tick (TIM2 interrupts starve the main loop there);
 * each tick starts FW_BLOCK_LEN ADC conversions by software and waits for
 * each with a bound, because QEMU never sets EOC: the ramp it returns is
 * read anyway and the timed-out wait is counted (STATUS.adc_timeouts). There
 * is no DMA, RCC, flash interface or watchdog in the model, so calibration
 * storage reports "none" (INFO: GP_CAL_DEFAULTS, CAL_SAVE: NACK FLASH_ERROR)
 * and the watchdog is not used. */
#include "board.h"
#include "board_pins.h"
#include "fw_blockq.h"
#include "fw_core.h"
#include "fw_hal.h"
#include "stm32f4_regs.h"

#define CPU_HZ    168000000u /* the clock QEMU's SysTick counts */
#define APB2_HZ   84000000u  /* what USART1 would see on a real F405 */
#define RXQ_BYTES 64u

static fw_blockq blocks;
static fw_core core;
static uint32_t tick_count;
static volatile uint32_t adc_timeouts;
static volatile uint8_t rxq[RXQ_BYTES];
static volatile uint32_t rx_head, rx_tail;

static const uint8_t adc_channels[FW_N_CH] = { ADC_CH_THUMB, ADC_CH_INDEX, ADC_CH_MIDDLE,
                                               ADC_CH_RING, ADC_CH_LITTLE };

static uint16_t convert(uint8_t channel) {
  ADC1_SQR3 = channel;
  ADC1_CR2 = ADC_CR2_ADON | ADC_CR2_SWSTART;
  uint32_t polls = 0;
  while (!(ADC1_SR & ADC_SR_EOC)) {
    if (++polls >= FW_ADC_WAIT_POLLS) {
      adc_timeouts++;
      break;
    }
  }
  return (uint16_t)(ADC1_DR & FW_ADC_MAX);
}

void SysTick_Handler(void);
void SysTick_Handler(void) {
  uint16_t *slot = fw_blockq_slot(&blocks);
  if (slot != 0) {
    for (unsigned s = 0; s < FW_OVERSAMPLE; s++)
      for (unsigned c = 0; c < FW_N_CH; c++) slot[s * FW_N_CH + c] = convert(adc_channels[c]);
    fw_blockq_commit(&blocks, tick_count);
  }
  tick_count++;
}

void USART1_IRQHandler(void);
void USART1_IRQHandler(void) {
  while (USART1_SR & USART_SR_RXNE) {
    uint8_t b = (uint8_t)USART1_DR;
    if (rx_head - rx_tail < RXQ_BYTES) {
      rxq[rx_head % RXQ_BYTES] = b;
      rx_head++;
    }
  }
}

int fw_hal_adc_take(uint16_t block[FW_BLOCK_LEN], uint32_t *tick) {
  return fw_blockq_take(&blocks, block, tick);
}

uint32_t fw_hal_adc_timeouts(void) {
  return adc_timeouts;
}

/* Transmission is synchronous here: QEMU takes a byte as soon as it is
 * written, so the queue is always empty. */
size_t fw_hal_uart_tx_free(void) {
  return FW_TXQ_BYTES;
}

void fw_hal_uart_write(const uint8_t *data, size_t n) {
  for (size_t i = 0; i < n; i++) {
    for (uint32_t polls = 0; !(USART1_SR & USART_SR_TXE) && polls < 100000u; polls++) {
    }
    USART1_DR = data[i];
  }
}

int fw_hal_uart_tx_idle(void) {
  return 1;
}

int fw_hal_uart_read(uint8_t *byte) {
  if (rx_head == rx_tail) return 0;
  *byte = rxq[rx_tail % RXQ_BYTES];
  rx_tail++;
  return 1;
}

void fw_hal_uart_set_baud(uint32_t baud) {
  USART1_BRR = (APB2_HZ + baud / 2u) / baud;
}

int fw_hal_flash_read(void *data, size_t len) {
  (void)data;
  (void)len;
  return -1;
}

int fw_hal_flash_write(const void *data, size_t len) {
  (void)data;
  (void)len;
  return -1;
}

/* Nothing is stored, so nothing needs erasing. */
int fw_hal_flash_erase(void) {
  return 0;
}

void fw_hal_led(int on) {
  (void)on;
}
int fw_hal_button(void) {
  return 0;
}
void fw_hal_watchdog_kick(void) {}

/* QEMU maps nothing at the unique-id address (a read faults), so the
 * emulated glove announces uid 0. */
void fw_hal_uid(uint32_t uid[3]) {
  for (unsigned i = 0; i < 3; i++) uid[i] = 0;
}

void board_main(void) {
  fw_hal_uart_set_baud(FW_BAUD);
  USART1_CR1 = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE | USART_CR1_RXNEIE;
  NVIC_ISER(IRQ_USART1 / 32u) = 1u << (IRQ_USART1 % 32u);
  ADC1_CR2 = ADC_CR2_ADON;

  fw_blockq_init(&blocks);
  fw_core_init(&core);

  SYST_RVR = CPU_HZ / FW_TICK_HZ - 1u; /* 167999: 1 kHz */
  SYST_CVR = 0;
  SYST_CSR = SYST_CSR_CLKSOURCE | SYST_CSR_TICKINT | SYST_CSR_ENABLE;
  for (;;) {
    fw_core_poll(&core);
    /* Sleep until the next tick or received byte. */
    __asm volatile("wfi");
  }
}
