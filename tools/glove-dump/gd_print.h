/* glove-dump's output: one readable line or one CSV row per frame. */
#ifndef GD_PRINT_H
#define GD_PRINT_H

#include <stdio.h>

#include "gp.h"

/* "SAMPLE seq=1 t_us=4000 ch=1,2,3,4,5 flags=0x0", any type, from the
 * message tables, so a new message prints without code here. */
void gd_print_msg(FILE *f, const gp_msg *m, const char *suffix);

void gd_print_csv_header(FILE *f);
void gd_print_csv_sample(FILE *f, const gp_sample *s, int late);

/* key=value lines, the same keys glove-gen --truth writes. */
void gd_print_counters(FILE *f, const gp_counters *c);

#endif
