/* The clock plan for the 8 MHz crystal of many Black Pill clones (the
 * blackpill_f411_8mhz image). */
#define FW_HSE_HZ 8000000u
#include "clock_f411.h"
#include "clock_plan.h"

CLOCK_PLAN_DEFINE(clock_plan_hse8)
