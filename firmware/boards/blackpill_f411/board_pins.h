/* Pin map of the STM32F411 "Black Pill" glove board.
 *
 * The one place the firmware takes its pins from. hardware/pinout.csv
 * states the same map for makers, and a test checks that the two agree.
 * BOARD_PIN(port, n) names pin n of GPIO port 'A'..'C'.
 */
#ifndef BOARD_PINS_H
#define BOARD_PINS_H

#define BOARD_PIN(port, n) ((((port) - 'A') << 4) | (n))
#define BOARD_PIN_PORT(p)  ((p) >> 4)
#define BOARD_PIN_NUM(p)   ((p)&15)

/* Five string-stretch sensors, one ADC1 input each (PA0 is the KEY button,
 * so the channels start at PA1). */
#define PIN_CH_THUMB  BOARD_PIN('A', 1) /* ADC1_IN1 */
#define PIN_CH_INDEX  BOARD_PIN('A', 2) /* ADC1_IN2 */
#define PIN_CH_MIDDLE BOARD_PIN('A', 3) /* ADC1_IN3 */
#define PIN_CH_RING   BOARD_PIN('A', 4) /* ADC1_IN4 */
#define PIN_CH_LITTLE BOARD_PIN('A', 5) /* ADC1_IN5 */
#define ADC_CH_THUMB  1
#define ADC_CH_INDEX  2
#define ADC_CH_MIDDLE 3
#define ADC_CH_RING   4
#define ADC_CH_LITTLE 5

/* USART1 to the host through a USB-serial adapter (AF7). */
#define PIN_UART_TX BOARD_PIN('A', 9)
#define PIN_UART_RX BOARD_PIN('A', 10)

/* On-board blue LED, lit when driven low. */
#define PIN_LED BOARD_PIN('C', 13)
/* On-board KEY button to ground; internal pull-up; pressed reads low. */
#define PIN_BUTTON BOARD_PIN('A', 0)

/* PA11/PA12 stay free for the USB DFU bootloader. */

#endif
