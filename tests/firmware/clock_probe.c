/* Compiled, never run, with a crystal the Black Pill's PLL cannot use: the
 * build must stop with clock_f411.h's message (tests/firmware/CMakeLists.txt). */
#include "clock_f411.h"

int clock_probe_hse_hz = FW_HSE_HZ;
