/* Timer-triggered ADC scans moved by DMA: no polling anywhere.
 *
 * TIM3's update event (TRGO) starts a scan of the five string channels
 * FW_TICK_HZ * FW_OVERSAMPLE times a second (4 kHz by default), evenly
 * spaced. DMA2 stream 0 (channel 0 = ADC1) writes the counts into a
 * circular buffer of two tick blocks; its half- and full-transfer
 * interrupts each mark one finished tick and hand that block to the core
 * through a fw_blockq, while the DMA fills the other half. */
#include "board_f411.h"
#include "board_pins.h"
#include "fw_blockq.h"
#include "fw_hal.h"
#include "stm32f4_regs.h"

static volatile uint16_t dma_buf[2][FW_BLOCK_LEN];
static fw_blockq blocks;
static uint32_t tick_count;

static const uint8_t channels[FW_N_CH] = { ADC_CH_THUMB, ADC_CH_INDEX, ADC_CH_MIDDLE, ADC_CH_RING,
                                           ADC_CH_LITTLE };
static const uint8_t channel_pins[FW_N_CH] = { PIN_CH_THUMB, PIN_CH_INDEX, PIN_CH_MIDDLE,
                                               PIN_CH_RING, PIN_CH_LITTLE };

static void dma_start(void) {
  DMA2_S0CR = 0;
  for (uint32_t polls = 0; (DMA2_S0CR & DMA_SxCR_EN) && polls < 100000u; polls++) {
  }
  DMA2_LIFCR = DMA_LIFCR_ALL0;
  DMA2_S0PAR = (uint32_t)(uintptr_t)&ADC1_DR;
  DMA2_S0M0AR = (uint32_t)(uintptr_t)&dma_buf[0][0];
  DMA2_S0NDTR = 2u * FW_BLOCK_LEN;
  DMA2_S0CR = DMA_SxCR_CHSEL(0u) | DMA_SxCR_PL_HIGH | DMA_SxCR_MSIZE_16 | DMA_SxCR_PSIZE_16 |
              DMA_SxCR_MINC | DMA_SxCR_CIRC | DMA_SxCR_HTIE | DMA_SxCR_TCIE | DMA_SxCR_TEIE;
  DMA2_S0CR |= DMA_SxCR_EN;
}

static void adc_start(void) {
  ADC1_CR2 = 0;
  ADC1_SR = 0;
  /* Scan the five channels, one DMA request per conversion, re-armed after
   * every scan (DDS), started on TIM3's TRGO rising edge. */
  ADC1_CR1 = ADC_CR1_SCAN;
  ADC1_CR2 =
      ADC_CR2_ADON | ADC_CR2_DMA | ADC_CR2_DDS | ADC_CR2_EXTSEL_TIM3_TRGO | ADC_CR2_EXTEN_RISING;
}

void sampling_start(void) {
  fw_blockq_init(&blocks);
  RCC_AHB1ENR |= RCC_AHB1ENR_DMA2EN;
  RCC_APB2ENR |= RCC_APB2ENR_ADC1EN;
  RCC_APB1ENR |= RCC_APB1ENR_TIM3EN;
  for (unsigned c = 0; c < FW_N_CH; c++) board_pin_mode(channel_pins[c], GPIO_MODE_ANALOG, 0);

  /* ADC clock 96 MHz / 4 = 24 MHz (at most 36). 144-cycle sampling suits
   * the sensors' divider impedance: (144 + 12) / 24 MHz = 6.5 us a
   * conversion, 32.5 us a scan, well inside the 250 us between scans. */
  ADC_CCR = ADC_CCR_ADCPRE_DIV4;
  uint32_t smpr = 0, sqr3 = 0;
  for (unsigned c = 0; c < FW_N_CH; c++) {
    smpr |= (uint32_t)ADC_SMP_144 << (3u * channels[c]);
    sqr3 |= (uint32_t)channels[c] << (5u * c);
  }
  ADC1_SMPR2 = smpr; /* channels 0..9 */
  ADC1_SQR3 = sqr3;  /* sequence positions 1..5 */
  ADC1_SQR1 = ADC_SQR1_L(FW_N_CH);

  dma_start();
  NVIC_ISER(IRQ_DMA2_STREAM0 / 32u) = 1u << (IRQ_DMA2_STREAM0 % 32u);
  adc_start();

  TIM3_PSC = 0;
  TIM3_ARR = board_sysclk_hz / (FW_TICK_HZ * FW_OVERSAMPLE) - 1u; /* 23999 at 96 MHz */
  TIM3_CR2 = TIM_CR2_MMS_UPDATE;
  TIM3_EGR = TIM_EGR_UG;
  TIM3_CR1 = TIM_CR1_CEN;
}

static void hand_over(const volatile uint16_t *half) {
  uint16_t *slot = fw_blockq_slot(&blocks);
  if (slot != 0) {
    for (unsigned i = 0; i < FW_BLOCK_LEN; i++) slot[i] = half[i];
    fw_blockq_commit(&blocks, tick_count);
  }
  tick_count++;
}

void DMA2_Stream0_IRQHandler(void);
void DMA2_Stream0_IRQHandler(void) {
  uint32_t isr = DMA2_LISR;
  DMA2_LIFCR = DMA_LIFCR_ALL0;
  if (isr & DMA_LISR_HTIF0) hand_over(dma_buf[0]);
  if (isr & DMA_LISR_TCIF0) hand_over(dma_buf[1]);
  if (isr & DMA_LISR_TEIF0) {
    /* A transfer error stops the stream: restart it. The tick lost shows
     * in the core as an overrun. */
    tick_count++;
    adc_start();
    dma_start();
  }
}

int fw_hal_adc_take(uint16_t block[FW_BLOCK_LEN], uint32_t *tick) {
  /* An ADC overrun (a conversion the DMA did not collect) stops the scans;
   * restart both, and count one lost tick. */
  if (ADC1_SR & ADC_SR_OVR) {
    __asm volatile("cpsid i" ::: "memory");
    tick_count++;
    dma_start();
    adc_start();
    __asm volatile("cpsie i" ::: "memory");
  }
  return fw_blockq_take(&blocks, block, tick);
}

/* No ADC wait here: the timer starts and the DMA collects every conversion. */
uint32_t fw_hal_adc_timeouts(void) {
  return 0;
}
