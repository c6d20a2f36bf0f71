/* The glove firmware on the STM32F411 "Black Pill": clocks, pins, LED,
 * button, watchdog and the calibration flash sector. Sampling is in
 * sampling.c, the serial link in uart.c. Register-level, after RM0383. */
#include "board.h"
#include "board_f411.h"
#include "board_pins.h"
#include "clock_f411.h"
#include "fw_core.h"
#include "fw_hal.h"
#include "stm32f4_regs.h"

/* Flash sector 1 (16 KiB at 0x08004000) holds the calibration record. */
#define CAL_SECTOR 1u
#define CAL_ADDR   0x08004000u
/* Bounds on flash waits: a 16 KiB sector erase takes up to 500 ms
 * (datasheet), each poll well over 10 ns, so this outlasts it. */
#define FLASH_WAIT_POLLS 100000000u

static fw_core core;
uint32_t board_sysclk_hz = CLOCK_HSI_HZ; /* until clock_init switches to the PLL */

static void bounded_wait(volatile uint32_t *reg, uint32_t mask, uint32_t want, uint32_t polls) {
  while ((*reg & mask) != want && polls-- > 0u) {
  }
}

/* 96 MHz from the PLL, with M, N, P and Q derived from the crystal in
 * clock_f411.h (25 MHz: / 25 * 192 / 2; 8 MHz: / 4 * 96 / 2). If the
 * crystal does not start, the same PLL runs from HSI 16 MHz. */
static void clock_init(void) {
  /* The regulator resets to scale 2 (HCLK up to 84 MHz); 96 MHz needs
   * scale 1 (RM0383, PWR_CR.VOS), set before the PLL starts. */
  RCC_APB1ENR |= RCC_APB1ENR_PWREN;
  PWR_CR = (PWR_CR & ~PWR_CR_VOS_MASK) | PWR_CR_VOS_SCALE1;
  RCC_CR |= RCC_CR_HSEON;
  bounded_wait(&RCC_CR, RCC_CR_HSERDY, RCC_CR_HSERDY, 200000u);
  int hse = (RCC_CR & RCC_CR_HSERDY) != 0;
  RCC_PLLCFGR = hse ? CLOCK_PLLCFGR_HSE : CLOCK_PLLCFGR_HSI;
  /* 3 wait states for 90 < HCLK <= 100 MHz at 2.7-3.6 V (RM0383, table 5). */
  FLASH_ACR = FLASH_ACR_LATENCY(3u) | FLASH_ACR_PRFTEN | FLASH_ACR_ICEN | FLASH_ACR_DCEN;
  /* APB1 at most 50 MHz: /2 (its timers run at 2x = 96 MHz); APB2 /1. */
  RCC_CFGR = RCC_CFGR_PPRE1_DIV2 | RCC_CFGR_PPRE2_DIV1;
  RCC_CR |= RCC_CR_PLLON;
  bounded_wait(&RCC_CR, RCC_CR_PLLRDY, RCC_CR_PLLRDY, 200000u);
  if (!(RCC_CR & RCC_CR_PLLRDY)) return; /* stay on HSI 16 MHz */
  RCC_CFGR = (RCC_CFGR & ~3u) | RCC_CFGR_SW_PLL;
  bounded_wait(&RCC_CFGR, RCC_CFGR_SWS_MASK, RCC_CFGR_SWS_PLL, 200000u);
  if ((RCC_CFGR & RCC_CFGR_SWS_MASK) == RCC_CFGR_SWS_PLL) board_sysclk_hz = CLOCK_SYSCLK_HZ;
}

void board_pin_mode(unsigned pin, unsigned mode, unsigned af) {
  unsigned port = BOARD_PIN_PORT(pin), n = BOARD_PIN_NUM(pin);
  GPIO_MODER(port) = (GPIO_MODER(port) & ~(3u << (2u * n))) | (mode << (2u * n));
  if (mode == GPIO_MODE_AF) {
    unsigned shift = 4u * (n & 7u);
    GPIO_AFR(port, n) = (GPIO_AFR(port, n) & ~(15u << shift)) | (af << shift);
  }
}

static void pins_init(void) {
  RCC_AHB1ENR |= RCC_AHB1ENR_GPIOAEN | RCC_AHB1ENR_GPIOBEN | RCC_AHB1ENR_GPIOCEN;
  fw_hal_led(0);
  board_pin_mode(PIN_LED, GPIO_MODE_OUTPUT, 0);
  board_pin_mode(PIN_BUTTON, GPIO_MODE_INPUT, 0);
  unsigned bp = BOARD_PIN_PORT(PIN_BUTTON), bn = BOARD_PIN_NUM(PIN_BUTTON);
  GPIO_PUPDR(bp) = (GPIO_PUPDR(bp) & ~(3u << (2u * bn))) | (GPIO_PULL_UP << (2u * bn));
}

/* Independent watchdog from the ~32 kHz LSI: /64 and 1000 counts, about
 * 2 s, longer than the worst flash sector erase. */
static void watchdog_init(void) {
  IWDG_KR = IWDG_KEY_START;
  IWDG_KR = IWDG_KEY_ACCESS;
  IWDG_PR = 4u; /* /64 */
  IWDG_RLR = 999u;
  bounded_wait(&IWDG_SR, 3u, 0u, 100000u);
  IWDG_KR = IWDG_KEY_RELOAD;
}

void fw_hal_watchdog_kick(void) {
  IWDG_KR = IWDG_KEY_RELOAD;
}

/* PC13 drives the LED's cathode: low lights it. */
void fw_hal_led(int on) {
  unsigned port = BOARD_PIN_PORT(PIN_LED), n = BOARD_PIN_NUM(PIN_LED);
  GPIO_BSRR(port) = on ? (1u << (n + 16u)) : (1u << n);
}

/* The KEY button pulls PA0 to ground. */
int fw_hal_button(void) {
  return (GPIO_IDR(BOARD_PIN_PORT(PIN_BUTTON)) & (1u << BOARD_PIN_NUM(PIN_BUTTON))) == 0;
}

void fw_hal_uid(uint32_t uid[3]) {
  for (unsigned i = 0; i < 3; i++) uid[i] = REG32(UID_BASE + 4u * i);
}

int fw_hal_flash_read(void *data, size_t len) {
  const volatile uint8_t *src = (const volatile uint8_t *)CAL_ADDR;
  uint8_t *dst = data;
  for (size_t i = 0; i < len; i++) dst[i] = src[i];
  return 0;
}

/* Waits out a flash operation and reports its error flags. The CPU stalls
 * on flash reads meanwhile, interrupt handlers included: the DMA keeps
 * overwriting its two blocks, but only what they hold at the end is handed
 * over (one or two ticks), so the ticks of the stall (up to a sector erase,
 * hundreds of ms) are neither sampled nor counted as overruns, and the
 * device clock (tick count) falls behind by that much at each CAL_SAVE or
 * CAL_CLEAR. */
static int flash_wait(void) {
  fw_hal_watchdog_kick();
  bounded_wait(&FLASH_SR, FLASH_SR_BSY, 0u, FLASH_WAIT_POLLS);
  fw_hal_watchdog_kick();
  uint32_t sr = FLASH_SR;
  FLASH_SR = FLASH_SR_ERRORS; /* write-1-to-clear */
  return (sr & (FLASH_SR_BSY | FLASH_SR_ERRORS)) ? -1 : 0;
}

static int flash_unlock(void) {
  if (FLASH_CR & FLASH_CR_LOCK) {
    FLASH_KEYR = FLASH_KEY1;
    FLASH_KEYR = FLASH_KEY2;
  }
  FLASH_SR = FLASH_SR_ERRORS;
  return (FLASH_CR & FLASH_CR_LOCK) ? -1 : 0;
}

/* The data cache may hold the sector's old contents. */
static void flash_done(void) {
  FLASH_CR = FLASH_CR_LOCK;
  uint32_t acr = FLASH_ACR;
  FLASH_ACR = acr & ~FLASH_ACR_DCEN;
  FLASH_ACR = (acr & ~FLASH_ACR_DCEN) | FLASH_ACR_DCRST;
  FLASH_ACR = acr;
}

static int flash_erase_sector(void) {
  FLASH_CR = FLASH_CR_PSIZE_X32 | FLASH_CR_SER | FLASH_CR_SNB(CAL_SECTOR);
  FLASH_CR |= FLASH_CR_STRT;
  int r = flash_wait();
  FLASH_CR = 0;
  return r;
}

int fw_hal_flash_erase(void) {
  if (flash_unlock() != 0) return -1;
  int r = flash_erase_sector();
  flash_done();
  return r;
}

int fw_hal_flash_write(const void *data, size_t len) {
  const uint8_t *p = data;
  if (flash_unlock() != 0) return -1;
  int r = flash_erase_sector();
  for (size_t i = 0; r == 0 && i < len; i += 4u) {
    uint32_t w = 0xFFFFFFFFu;
    for (size_t k = 0; k < 4u && i + k < len; k++)
      w = (w & ~(0xFFu << (8u * k))) | ((uint32_t)p[i + k] << (8u * k));
    FLASH_CR = FLASH_CR_PSIZE_X32 | FLASH_CR_PG;
    REG32(CAL_ADDR + i) = w;
    r = flash_wait();
  }
  FLASH_CR = 0;
  flash_done();
  return r;
}

void board_main(void) {
  clock_init();
  pins_init();
  watchdog_init();
  uart_init(FW_BAUD);
  fw_core_init(&core);
  sampling_start();
  for (;;) {
    fw_core_poll(&core);
    /* Sleep until the next sampled block, received byte or sent byte. */
    __asm volatile("wfi");
  }
}
