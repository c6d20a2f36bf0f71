/* What the on-screen display says of a show over takes (issue 23): the
 * marks on its first line (SPEED, REC), the take beneath, and each
 * layered glove's line (the fingers from the glove, the fingers the take
 * plays, * on the glove the keys arm). Text only, apart from the stage, so
 * that a test reads the very strings the stage draws. */
#ifndef MR_TAKES_OSD_H
#define MR_TAKES_OSD_H

#include <stdbool.h>
#include <stddef.h>

typedef struct mr_takes_osd {
  double speed;        /* 1, 0.5 or 0.25 */
  bool recording;      /* between a punch-in and a punch-out */
  const char *beneath; /* the take beneath; NULL or "": none */
  size_t glove_sel;    /* the glove whose channels F2-F6 arm */
} mr_takes_osd;

/* "  SPEED 50 %  REC": what of them holds, "" at full speed, not
 * recording. */
void mr_takes_osd_marks(const mr_takes_osd *o, char *out, size_t size);

/* "over NAME" (the name cut to 20 characters), "" without a take
 * beneath. */
void mr_takes_osd_beneath(const mr_takes_osd *o, char *out, size_t size);

/* Glove g's line, g from 0, armed its channels armed (bit 0 the thumb to
 * bit 4 the little finger): "glove 2* live T---- take -IMRL". */
void mr_takes_osd_glove(const mr_takes_osd *o, size_t g, unsigned armed, char *out, size_t size);

#endif
