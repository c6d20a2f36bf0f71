/* The hardware the core needs, as a handful of functions each board provides
 * (firmware/boards/<board>/) and the host tests fake (tests/firmware/).
 *
 * Everything here is non-blocking: the core calls it from its main loop and
 * never waits on hardware.
 */
#ifndef FW_HAL_H
#define FW_HAL_H

#include <stddef.h>
#include <stdint.h>

#include "fw_config.h"

/* --- sampling --------------------------------------------------------------
 * A timer drives the ADC; each tick's conversions (FW_BLOCK_LEN counts) land
 * in a fw_blockq that the board fills from its interrupt. */

/* Takes the oldest complete block, if any: copies its counts and the number
 * of the tick it was sampled on (counting from 0 at start, +1 per tick).
 * Returns 1 if a block was taken, 0 if none is ready. */
int fw_hal_adc_take(uint16_t block[FW_BLOCK_LEN], uint32_t *tick);
/* ADC waits that ran out since start (the QEMU board's bounded polls). */
uint32_t fw_hal_adc_timeouts(void);

/* --- serial link ---------------------------------------------------------- */

/* Free bytes in the transmit queue. */
size_t fw_hal_uart_tx_free(void);
/* Queues n bytes for sending; the core never passes more than
 * fw_hal_uart_tx_free() returned. */
void fw_hal_uart_write(const uint8_t *data, size_t n);
/* 1 once every queued byte has left the wire (safe to change the baud). */
int fw_hal_uart_tx_idle(void);
/* Takes one received byte: returns 1 and stores it, or 0 if none waits. */
int fw_hal_uart_read(uint8_t *byte);
/* Switches the link to baud (8N1). Called only when the link is idle. */
void fw_hal_uart_set_baud(uint32_t baud);

/* --- calibration storage -------------------------------------------------- */

/* Reads the first len bytes of the calibration page. Returns 0, or -1 if the
 * board has no storage. Erased storage reads 0xFF. */
int fw_hal_flash_read(void *data, size_t len);
/* Erases the calibration page and writes len bytes at its start.
 * Returns 0, or -1 if the write failed or the board has no storage. */
int fw_hal_flash_write(const void *data, size_t len);
/* Erases the calibration page. Returns 0, or -1 on failure. */
int fw_hal_flash_erase(void);

/* --- the rest ------------------------------------------------------------- */

void fw_hal_led(int on);
/* 1 while the calibration button is held (raw, not debounced). */
int fw_hal_button(void);
void fw_hal_watchdog_kick(void);
/* The microcontroller's 96-bit unique id. */
void fw_hal_uid(uint32_t uid[3]);

#endif
