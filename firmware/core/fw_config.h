/* The glove's rates, filter and defaults: the one file makers edit.
 *
 * Everything here is checked at compile time (end of file), so an edit that
 * cannot work fails the build instead of misbehaving on the glove. The README
 * (firmware/README.md, "Rates" and "Filter") shows the arithmetic behind the
 * defaults.
 */
#ifndef FW_CONFIG_H
#define FW_CONFIG_H

/* Firmware version, announced in INFO. */
#define FW_VERSION_MAJOR 0
#define FW_VERSION_MINOR 1
#define FW_VERSION_PATCH 0

/* Which hand the glove is worn on: GP_HAND_LEFT (0) or GP_HAND_RIGHT (1). */
#define FW_HAND 1

/* Five strings, thumb .. little finger, 12-bit ADC: the width and count of
 * SAMPLE's ch field in protocol/messages.def, not a choice made here. */
#include "gp_messages.h"
#define FW_N_CH     GP_SAMPLE_CH_COUNT
#define FW_ADC_BITS GP_SAMPLE_CH_BITS
#define FW_ADC_MAX  GP_SAMPLE_CH_MAX

/* The sampling tick: every channel gets one filtered sample per tick. */
#define FW_TICK_HZ 1000u
#define FW_TICK_US (1000000u / FW_TICK_HZ)

/* Conversions per channel per tick, averaged into one sample (oversampling).
 * The Black Pill spreads them evenly over the tick (timer-triggered scans);
 * the QEMU board converts them back to back. */
#define FW_OVERSAMPLE 4u

/* First-order low-pass (exponential moving average) on the 1 kHz samples:
 * y += (x - y) / 2^FW_FILTER_SHIFT. Shift 3 (alpha = 1/8): -3 dB at 21 Hz,
 * 7 ms lag at low frequencies, 90 % of a step after 18 ticks. 0 turns the
 * filter off (oversampling only). */
#define FW_FILTER_SHIFT 3u
/* Fractional bits the filter keeps, so small steps still arrive in full. */
#define FW_FILTER_FRAC_BITS 8u

/* SAMPLE frames per second at boot; SET_RATE accepts any divisor of
 * FW_TICK_HZ that the link can carry. */
#define FW_FRAME_RATE_HZ 250u
/* Serial link at boot: 8N1 at this baud rate. */
#define FW_BAUD 115200u
/* Baud rates SET_RATE accepts (SPEC.md lists them). The Black Pill's build
 * checks that its USART1 reaches each within 0.2 %. */
#define FW_BAUD_LIST(X) \
  X(9600u) X(19200u) X(38400u) X(57600u) X(115200u) X(230400u) X(460800u) X(921600u)
#define FW_BAUD_ITEM(b) b,
#define FW_BAUDS \
  { FW_BAUD_LIST(FW_BAUD_ITEM) }
/* SET_RATE refuses a SAMPLE stream that would fill more than this share of
 * the link, leaving room for INFO, replies and clock error. */
#define FW_LINK_MAX_PERCENT 50u

/* The crystal on the Black Pill (HSE), in Hz. WeAct's boards carry 25 MHz,
 * many clones 8 MHz: the marking on the silver can says which
 * (hardware/troubleshooting.md). The clock tree is derived from it and
 * checked at compile time (boards/blackpill_f411/clock_f411.h); the build
 * makes an image for each (`make firmware`: blackpill_f411 uses this value,
 * blackpill_f411_8mhz sets 8 MHz). The QEMU board has no crystal. */
#ifndef FW_HSE_HZ
#define FW_HSE_HZ 25000000u
#endif

/* INFO is repeated this often (and sent on GET_INFO). */
#define FW_INFO_PERIOD_TICKS FW_TICK_HZ

/* Calibration: a channel must move at least this many counts between
 * CAL_START and CAL_SAVE, or CAL_SAVE is refused. */
#define FW_CAL_MIN_SPAN 64u
/* The button must read the same for this many ticks to count (debounce). */
#define FW_BUTTON_DEBOUNCE_TICKS 20u

/* Transmit queue the board's UART driver keeps, in bytes. */
#define FW_TXQ_BYTES 256u
/* Sampled blocks the timer interrupt may queue ahead of the main loop. */
#define FW_BLOCKQ_DEPTH 4u
/* Bound on every ADC wait on the QEMU board (polls of the status register). */
#define FW_ADC_WAIT_POLLS 32u

/* --- checks --------------------------------------------------------------- */
#if FW_TICK_HZ % FW_FRAME_RATE_HZ != 0
#error "FW_FRAME_RATE_HZ must divide FW_TICK_HZ"
#endif
#if FW_OVERSAMPLE < 1 || FW_OVERSAMPLE > 16
#error "FW_OVERSAMPLE must be 1..16"
#endif
#if FW_FILTER_SHIFT > 8
#error "FW_FILTER_SHIFT must be 0..8"
#endif
#if FW_FILTER_FRAC_BITS < 1 || FW_FILTER_FRAC_BITS > 16
#error "FW_FILTER_FRAC_BITS must be 1..16"
#endif
#if FW_BUTTON_DEBOUNCE_TICKS < 1
#error "FW_BUTTON_DEBOUNCE_TICKS must be at least 1"
#endif
#if FW_BLOCKQ_DEPTH < 2 || (FW_BLOCKQ_DEPTH & (FW_BLOCKQ_DEPTH - 1)) != 0
#error "FW_BLOCKQ_DEPTH must be a power of two, at least 2"
#endif
/* The UART queues index with free-running 32-bit counters modulo their
 * size, which stays right across the counters' wrap only for a power of two;
 * and the largest frame (INFO, 59 bytes on the wire) must fit. */
#if FW_TXQ_BYTES < 64 || (FW_TXQ_BYTES & (FW_TXQ_BYTES - 1)) != 0
#error "FW_TXQ_BYTES must be a power of two, at least 64"
#endif

/* Samples in one tick's block: FW_OVERSAMPLE scans of FW_N_CH channels,
 * scan after scan (ch0 ch1 .. ch4 ch0 ch1 ..). */
#define FW_BLOCK_LEN (FW_OVERSAMPLE * FW_N_CH)

#endif
