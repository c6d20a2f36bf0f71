/* A take beneath a live glove: per channel (finger), the take's values or
 * the live glove's (issue 23, layered takes). */
#include <stdio.h>
#include <string.h>

#include "theater_internal.h"

int mr_layer_open(mr_layer *l, const char *path, unsigned armed, char *msg, size_t size) {
  memset(l, 0, sizeof *l);
  l->armed = armed & ((1u << MR_GLOVE_CHANNELS) - 1u);
  if (path == NULL) return 0;
  mr_glove_def gd = mr_default_glove_def();
  int n = snprintf(gd.source, sizeof gd.source, "take:%s", path);
  if (n < 0 || (size_t)n >= sizeof gd.source) {
    snprintf(msg, size, "take beneath: the path is too long: %.200s", path);
    return -1;
  }
  mr_glove_source_report rep;
  if (mr_glove_source_check(gd.source, &rep) != MR_IO_OK) {
    snprintf(msg, size, "take beneath: %s", rep.msg);
    return -1;
  }
  if (mr_glove_create(&gd, &l->take, msg, size) != MR_GLOVE_OK) return -1;
  return 0;
}

void mr_layer_close(mr_layer *l) {
  mr_glove_destroy(l->take);
  l->take = NULL;
}

void mr_layer_poll(mr_layer *l, double t) {
  if (l->take != NULL) mr_glove_poll(l->take, t, 0);
}

bool mr_layer_read(const mr_layer *l, const mr_glove *live, mr_glove_reading *out) {
  mr_glove_reading own;
  mr_glove_latest(live, &own);
  bool live_on = mr_glove_get_state(live) == MR_GLOVE_LIVE;
  if (l->take == NULL) {
    *out = own;
    return live_on;
  }
  mr_glove_reading under;
  mr_glove_latest(l->take, &under);
  *out = under;
  /* A channel armed before the live glove sent anything keeps the take's
   * value: the puppet does not drop to zero while the glove connects. */
  if (own.samples > 0)
    for (int c = 0; c < MR_GLOVE_CHANNELS; c++)
      if (l->armed & (1u << c)) out->values[c] = own.values[c];
  if (l->armed != 0 && own.host_t > out->host_t) out->host_t = own.host_t;
  out->samples = under.samples + (l->armed != 0 ? own.samples : 0);
  return mr_glove_get_state(l->take) == MR_GLOVE_LIVE || (l->armed != 0 && live_on);
}

bool mr_layer_over(const mr_layer *l) {
  return l->take != NULL && mr_glove_take_done(l->take) &&
         mr_glove_get_state(l->take) == MR_GLOVE_LOST;
}

/* --- arming and punches -------------------------------------------------- */

void mr_punch_init(mr_punch *p, double punch_in, double punch_out) {
  memset(p, 0, sizeof *p);
  p->def_in = punch_in;
  p->def_out = punch_out;
  p->punch_in = p->punch_out = -1.0;
}

void mr_punch_ask_arm(mr_punch *p, size_t glove, unsigned armed) {
  if (glove >= MR_SHOW_MAX_GLOVES) return;
  p->arm_asked[glove] = armed & ((1u << MR_GLOVE_CHANNELS) - 1u);
  p->arm_pending[glove] = true;
}

typedef void (*note_fn)(void *user, const char *line);

static void tell_armed(const mr_layer *l, size_t g, const char *what, note_fn note, void *user) {
  static const char *const finger[MR_GLOVE_CHANNELS] = { "thumb", "index", "middle", "ring",
                                                         "little" };
  char line[240];
  int n = snprintf(line, sizeof line, "glove %zu: %s", g + 1, what);
  for (int c = 0; c < MR_GLOVE_CHANNELS && n > 0 && (size_t)n < sizeof line; c++)
    if (l->armed & (1u << c)) n += snprintf(line + n, sizeof line - (size_t)n, " %s", finger[c]);
  if (l->armed == 0 && n > 0 && (size_t)n < sizeof line)
    snprintf(line + n, sizeof line - (size_t)n, " none");
  if (note != NULL) note(user, line);
}

/* In: the channels armed now are the ones recorded; out: the take is
 * done, and the show ends with this frame. */
static void punch(mr_punch *p, const mr_layer *layers, size_t n, double t, note_fn note,
                  void *user) {
  if (p->punched_out) return;
  char line[80];
  if (!p->recording) {
    p->recording = true;
    p->punch_in = t;
    for (size_t g = 0; g < n; g++) p->punched[g] = layers[g].armed;
    snprintf(line, sizeof line, "punch-in at %.3f s", t);
  } else {
    p->recording = false;
    p->punched_out = true;
    p->punch_out = t;
    snprintf(line, sizeof line, "punch-out at %.3f s", t);
  }
  if (note != NULL) note(user, line);
}

void mr_punch_asks(mr_punch *p, mr_layer *layers, size_t n, double t, note_fn note, void *user) {
  for (size_t g = 0; g < n; g++) {
    if (!p->arm_pending[g]) continue;
    p->arm_pending[g] = false;
    if (p->recording) {
      tell_armed(&layers[g], g,
                 "recording, so the channels stay those armed at the punch-in:", note, user);
      continue;
    }
    layers[g].armed = p->arm_asked[g];
    tell_armed(&layers[g], g, "armed:", note, user);
  }
  for (; p->punches_asked > 0; p->punches_asked--) punch(p, layers, n, t, note, user);
  /* The definition's times: the first frames at or past them. */
  if (!p->recording && p->punch_in < 0 && p->def_in >= 0 && t >= p->def_in - 1e-9)
    punch(p, layers, n, t, note, user);
  if (p->recording && p->def_out >= 0 && t >= p->def_out - 1e-9) punch(p, layers, n, t, note, user);
}
