/* The QEMU board's inputs: the ADC1 channel each string is converted on.
 *
 * QEMU's ADC returns the same ramp whatever the channel, and its USART1 has
 * no pins to set up, so channels are all this board names. They are the
 * ones a real F405 carries on PA1..PA5, the Black Pill's sensor pins
 * (boards/blackpill_f411/board_pins.h), so the image would read the same
 * inputs on silicon.
 */
#ifndef BOARD_PINS_H
#define BOARD_PINS_H

#define ADC_CH_THUMB  1
#define ADC_CH_INDEX  2
#define ADC_CH_MIDDLE 3
#define ADC_CH_RING   4
#define ADC_CH_LITTLE 5

#endif
