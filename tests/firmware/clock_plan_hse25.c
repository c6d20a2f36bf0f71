/* The clock plan for the 25 MHz crystal of WeAct's Black Pill (the
 * blackpill_f411 image). */
#define FW_HSE_HZ 25000000u
#include "clock_f411.h"
#include "clock_plan.h"

CLOCK_PLAN_DEFINE(clock_plan_hse25)
