/* The on-screen display's text for a show over takes (takes_osd.h). */
#include "takes_osd.h"

#include <stdio.h>

void mr_takes_osd_marks(const mr_takes_osd *o, char *out, size_t size) {
  char speed[32] = "";
  if (o->speed < 1.0) snprintf(speed, sizeof speed, "  SPEED %.0f %%", o->speed * 100.0);
  snprintf(out, size, "%s%s", speed, o->recording ? "  REC" : "");
}

void mr_takes_osd_beneath(const mr_takes_osd *o, char *out, size_t size) {
  if (o->beneath == NULL || o->beneath[0] == '\0')
    snprintf(out, size, "%s", "");
  else
    snprintf(out, size, "over %.20s", o->beneath);
}

void mr_takes_osd_glove(const mr_takes_osd *o, size_t g, unsigned armed, char *out, size_t size) {
  static const char letters[] = "TIMRL";
  char live[6], take[6];
  for (int c = 0; c < 5; c++) {
    bool on = (armed & (1u << c)) != 0;
    live[c] = on ? letters[c] : '-';
    take[c] = on ? '-' : letters[c];
  }
  live[5] = take[5] = '\0';
  snprintf(out, size, "glove %zu%s live %s take %s", g + 1, g == o->glove_sel ? "*" : "", live,
           take);
}
