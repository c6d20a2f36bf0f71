/* The STM32F4 registers the glove boards touch, by address and bit, from the
 * reference manuals (RM0383 for the F411, RM0090 for the F405; the blocks
 * used here sit at the same addresses on both). Only what the firmware uses
 * is named: no vendor header is needed. */
#ifndef STM32F4_REGS_H
#define STM32F4_REGS_H

#include <stdint.h>

#define REG32(addr) (*(volatile uint32_t *)(uintptr_t)(addr))

/* --- Cortex-M4 core (ARMv7-M architecture reference) ---------------------- */
#define SYST_CSR           REG32(0xE000E010u)
#define SYST_RVR           REG32(0xE000E014u)
#define SYST_CVR           REG32(0xE000E018u)
#define SYST_CSR_ENABLE    (1u << 0)
#define SYST_CSR_TICKINT   (1u << 1)
#define SYST_CSR_CLKSOURCE (1u << 2) /* processor clock */
#define NVIC_ISER(n)       REG32(0xE000E100u + 4u * (n))
#define NVIC_IPR_BYTE(irq) (*(volatile uint8_t *)(uintptr_t)(0xE000E400u + (irq)))
#define SCB_VTOR           REG32(0xE000ED08u)
#define SCB_AIRCR          REG32(0xE000ED0Cu)
#define SCB_AIRCR_RESET    (0x05FA0000u | (1u << 2)) /* VECTKEY | SYSRESETREQ */

/* --- RCC ------------------------------------------------------------------ */
#define RCC_BASE             0x40023800u
#define RCC_CR               REG32(RCC_BASE + 0x00u)
#define RCC_PLLCFGR          REG32(RCC_BASE + 0x04u)
#define RCC_CFGR             REG32(RCC_BASE + 0x08u)
#define RCC_AHB1ENR          REG32(RCC_BASE + 0x30u)
#define RCC_APB1ENR          REG32(RCC_BASE + 0x40u)
#define RCC_APB2ENR          REG32(RCC_BASE + 0x44u)
#define RCC_CSR              REG32(RCC_BASE + 0x74u)
#define RCC_CR_HSEON         (1u << 16)
#define RCC_CR_HSERDY        (1u << 17)
#define RCC_CR_PLLON         (1u << 24)
#define RCC_CR_PLLRDY        (1u << 25)
#define RCC_PLLCFGR_M(m)     ((uint32_t)(m) << 0)
#define RCC_PLLCFGR_N(n)     ((uint32_t)(n) << 6)
#define RCC_PLLCFGR_P2       (0u << 16)
#define RCC_PLLCFGR_SRC_HSE  (1u << 22)
#define RCC_PLLCFGR_Q(q)     ((uint32_t)(q) << 24)
#define RCC_CFGR_SW_PLL      (2u << 0)
#define RCC_CFGR_SWS_MASK    (3u << 2)
#define RCC_CFGR_SWS_PLL     (2u << 2)
#define RCC_CFGR_PPRE1_DIV2  (4u << 10)
#define RCC_CFGR_PPRE2_DIV1  (0u << 13)
#define RCC_AHB1ENR_GPIOAEN  (1u << 0)
#define RCC_AHB1ENR_GPIOBEN  (1u << 1)
#define RCC_AHB1ENR_GPIOCEN  (1u << 2)
#define RCC_AHB1ENR_DMA2EN   (1u << 22)
#define RCC_APB1ENR_TIM3EN   (1u << 1)
#define RCC_APB1ENR_PWREN    (1u << 28)
#define RCC_APB2ENR_USART1EN (1u << 4)
#define RCC_APB2ENR_ADC1EN   (1u << 8)
#define RCC_CSR_LSION        (1u << 0)

/* --- PWR ------------------------------------------------------------------ */
#define PWR_CR            REG32(0x40007000u)
#define PWR_CR_VOS_MASK   (3u << 14)
#define PWR_CR_VOS_SCALE1 (3u << 14) /* F411: HCLK up to 100 MHz */

/* --- FLASH interface ------------------------------------------------------ */
#define FLASH_BASE_R          0x40023C00u
#define FLASH_ACR             REG32(FLASH_BASE_R + 0x00u)
#define FLASH_KEYR            REG32(FLASH_BASE_R + 0x04u)
#define FLASH_SR              REG32(FLASH_BASE_R + 0x0Cu)
#define FLASH_CR              REG32(FLASH_BASE_R + 0x10u)
#define FLASH_ACR_LATENCY(ws) ((uint32_t)(ws) << 0)
#define FLASH_ACR_PRFTEN      (1u << 8)
#define FLASH_ACR_ICEN        (1u << 9)
#define FLASH_ACR_DCEN        (1u << 10)
#define FLASH_ACR_DCRST       (1u << 12)
#define FLASH_KEY1            0x45670123u
#define FLASH_KEY2            0xCDEF89ABu
#define FLASH_SR_ERRORS       (0xF2u) /* OPERR, WRPERR, PGAERR, PGPERR, PGSERR */
#define FLASH_SR_BSY          (1u << 16)
#define FLASH_CR_PG           (1u << 0)
#define FLASH_CR_SER          (1u << 1)
#define FLASH_CR_SNB(n)       ((uint32_t)(n) << 3)
#define FLASH_CR_PSIZE_X32    (2u << 8)
#define FLASH_CR_STRT         (1u << 16)
#define FLASH_CR_LOCK         (1u << 31)

/* --- GPIO ----------------------------------------------------------------- */
#define GPIO_BASE(port)    (0x40020000u + 0x400u * (uint32_t)(port))
#define GPIO_MODER(port)   REG32(GPIO_BASE(port) + 0x00u)
#define GPIO_OTYPER(port)  REG32(GPIO_BASE(port) + 0x04u)
#define GPIO_OSPEEDR(port) REG32(GPIO_BASE(port) + 0x08u)
#define GPIO_PUPDR(port)   REG32(GPIO_BASE(port) + 0x0Cu)
#define GPIO_IDR(port)     REG32(GPIO_BASE(port) + 0x10u)
#define GPIO_BSRR(port)    REG32(GPIO_BASE(port) + 0x18u)
#define GPIO_AFR(port, n)  REG32(GPIO_BASE(port) + 0x20u + 4u * ((n) >> 3))
#define GPIO_MODE_INPUT    0u
#define GPIO_MODE_OUTPUT   1u
#define GPIO_MODE_AF       2u
#define GPIO_MODE_ANALOG   3u
#define GPIO_PULL_UP       1u

/* --- USART1 --------------------------------------------------------------- */
#define USART1_BASE      0x40011000u
#define USART1_SR        REG32(USART1_BASE + 0x00u)
#define USART1_DR        REG32(USART1_BASE + 0x04u)
#define USART1_BRR       REG32(USART1_BASE + 0x08u)
#define USART1_CR1       REG32(USART1_BASE + 0x0Cu)
#define USART_SR_ORE     (1u << 3)
#define USART_SR_RXNE    (1u << 5)
#define USART_SR_TC      (1u << 6)
#define USART_SR_TXE     (1u << 7)
#define USART_CR1_RE     (1u << 2)
#define USART_CR1_TE     (1u << 3)
#define USART_CR1_RXNEIE (1u << 5)
#define USART_CR1_TXEIE  (1u << 7)
#define USART_CR1_UE     (1u << 13)
#define IRQ_USART1       37u

/* --- ADC1 ----------------------------------------------------------------- */
#define ADC1_BASE                0x40012000u
#define ADC1_SR                  REG32(ADC1_BASE + 0x00u)
#define ADC1_CR1                 REG32(ADC1_BASE + 0x04u)
#define ADC1_CR2                 REG32(ADC1_BASE + 0x08u)
#define ADC1_SMPR2               REG32(ADC1_BASE + 0x10u)
#define ADC1_SQR1                REG32(ADC1_BASE + 0x2Cu)
#define ADC1_SQR3                REG32(ADC1_BASE + 0x34u)
#define ADC1_DR                  REG32(ADC1_BASE + 0x4Cu)
#define ADC_CCR                  REG32(0x40012300u + 0x04u)
#define ADC_SR_EOC               (1u << 1)
#define ADC_SR_OVR               (1u << 5)
#define ADC_CR1_SCAN             (1u << 8)
#define ADC_CR2_ADON             (1u << 0)
#define ADC_CR2_DMA              (1u << 8)
#define ADC_CR2_DDS              (1u << 9)
#define ADC_CR2_EXTSEL_TIM3_TRGO (8u << 24)
#define ADC_CR2_EXTEN_RISING     (1u << 28)
#define ADC_CR2_SWSTART          (1u << 30)
#define ADC_SQR1_L(n)            ((uint32_t)((n)-1u) << 20) /* n conversions */
#define ADC_CCR_ADCPRE_DIV4      (1u << 16)
#define ADC_SMP_144              6u /* sampling time code: 144 ADC clock cycles */

/* --- DMA2 stream 0 (ADC1 on channel 0) -------------------------------------- */
#define DMA2_BASE         0x40026400u
#define DMA2_LISR         REG32(DMA2_BASE + 0x00u)
#define DMA2_LIFCR        REG32(DMA2_BASE + 0x08u)
#define DMA2_S0CR         REG32(DMA2_BASE + 0x10u)
#define DMA2_S0NDTR       REG32(DMA2_BASE + 0x14u)
#define DMA2_S0PAR        REG32(DMA2_BASE + 0x18u)
#define DMA2_S0M0AR       REG32(DMA2_BASE + 0x1Cu)
#define DMA_SxCR_EN       (1u << 0)
#define DMA_SxCR_TEIE     (1u << 2)
#define DMA_SxCR_HTIE     (1u << 3)
#define DMA_SxCR_TCIE     (1u << 4)
#define DMA_SxCR_CIRC     (1u << 8)
#define DMA_SxCR_MINC     (1u << 10)
#define DMA_SxCR_PSIZE_16 (1u << 11)
#define DMA_SxCR_MSIZE_16 (1u << 13)
#define DMA_SxCR_PL_HIGH  (2u << 16)
#define DMA_SxCR_CHSEL(n) ((uint32_t)(n) << 25)
#define DMA_LISR_TEIF0    (1u << 3)
#define DMA_LISR_HTIF0    (1u << 4)
#define DMA_LISR_TCIF0    (1u << 5)
#define DMA_LIFCR_ALL0    (0x3Du) /* CFEIF0 CDMEIF0 CTEIF0 CHTIF0 CTCIF0 */
#define IRQ_DMA2_STREAM0  56u

/* --- TIM3 ----------------------------------------------------------------- */
#define TIM3_BASE          0x40000400u
#define TIM3_CR1           REG32(TIM3_BASE + 0x00u)
#define TIM3_CR2           REG32(TIM3_BASE + 0x04u)
#define TIM3_EGR           REG32(TIM3_BASE + 0x14u)
#define TIM3_PSC           REG32(TIM3_BASE + 0x28u)
#define TIM3_ARR           REG32(TIM3_BASE + 0x2Cu)
#define TIM_CR1_CEN        (1u << 0)
#define TIM_CR2_MMS_UPDATE (2u << 4)
#define TIM_EGR_UG         (1u << 0)

/* --- IWDG ----------------------------------------------------------------- */
#define IWDG_KR         REG32(0x40003000u)
#define IWDG_PR         REG32(0x40003004u)
#define IWDG_RLR        REG32(0x40003008u)
#define IWDG_SR         REG32(0x4000300Cu)
#define IWDG_KEY_ACCESS 0x5555u
#define IWDG_KEY_RELOAD 0xAAAAu
#define IWDG_KEY_START  0xCCCCu

/* --- device electronic signature ------------------------------------------ */
#define UID_BASE 0x1FFF7A10u

#endif
