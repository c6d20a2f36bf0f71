/* What the show tells the user about its gloves: a glove's state once it
 * has held a moment, silence, corrupt frames at most once a second, a
 * channel gone bad or back, and a second publisher on a glove's topic. */
#include <stdio.h>
#include <string.h>

#include "show_internal.h"

void mr_show_note(const show *s, const char *line) {
  if (s->hooks.note != NULL) s->hooks.note(s->hooks.user, line);
}

/* A channel that went bad or came back, told once, not every frame. */
void mr_show_tell_states(show *s, show_frame *f, const mr_channel_state now[MR_CONTROL_CHANNELS]) {
  static const char *const finger[MR_CONTROL_CHANNELS] = { "thumb", "index", "middle", "ring",
                                                           "little" };
  for (int c = 0; c < MR_CONTROL_CHANNELS; c++) {
    if (now[c] == f->states[c]) continue;
    f->states[c] = now[c];
    char line[400];
    const char *what = now[c] == MR_CHANNEL_NOT_FINITE ? "is not a finite number: held at neutral"
                       : now[c] == MR_CHANNEL_STUCK
                           ? "is stuck at 0 or at full scale: held at neutral (a broken or "
                             "unplugged sensor?)"
                           : "reads again";
    snprintf(line, sizeof line, "glove %d on %.200s: channel %d (%s finger) %s", f->glove + 1,
             s->sources[f->glove], c, finger[c], what);
    mr_show_note(s, line);
  }
}

/* A state must hold this long to be told: one foreign frame in a noisy
 * stream flips a glove to a mismatch until the next good frame, which is
 * noise, not news. */
#define TELL_AFTER_S 0.25

/* Corrupt frames since the last telling, at most once a second. */
static void tell_errors(show *s, size_t g, double now) {
  show_glove *sg = &s->gloves[g];
  mr_glove_counters c;
  mr_glove_get_counters(sg->glove, &c);
  const gp_counters *n = &c.decoder, *o = &sg->told;
  uint32_t crc = n->crc_errors - o->crc_errors, framing = n->framing_errors - o->framing_errors,
           big = n->oversize - o->oversize, unknown = n->unknown_type - o->unknown_type,
           foreign = n->spec_mismatch - o->spec_mismatch;
  uint64_t bad = (uint64_t)crc + framing + big + unknown + foreign;
  if (bad == 0 || now - sg->told_at < 1.0) return;
  char line[600];
  snprintf(line, sizeof line,
           "glove on %.200s: %llu corrupt frames in %.1f s (%u bad crc, %u cut short, %u "
           "oversize, %u of unknown type, %u foreign); the show reads on: a loose cable, "
           "noise or the wrong baud?",
           s->sources[g], (unsigned long long)bad, now - sg->told_at, crc, framing, big, unknown,
           foreign);
  mr_show_note(s, line);
  sg->told = *n;
  sg->told_at = now;
}

/* A second publisher on a glove's topic, told when it appears (not only
 * when the glove's state changes: a glove fed by two keeps its state) and
 * again if it comes back after it was gone. */
static void tell_publishers(show *s, size_t g) {
  show_glove *sg = &s->gloves[g];
  char a[MR_NET_NAME_MAX + 64], b[MR_NET_NAME_MAX + 64], line[700];
  bool two = mr_glove_net_publishers(sg->glove, a, b, sizeof a);
  if (two && !sg->told_two) {
    snprintf(line, sizeof line,
             "glove on %.200s: two publishers on its topic, %s and %s; the show reads both "
             "as one glove (two relays of one glove, or two gloves on one topic?)",
             s->sources[g], a, b);
    mr_show_note(s, line);
  }
  sg->told_two = two;
}

/* What changed about glove g, told once: its state (live, lost, a spec
 * mismatch) once it has held a moment, and silence since it was opened. */
void mr_show_tell_glove(show *s, size_t g, double now) {
  show_glove *sg = &s->gloves[g];
  char line[600], said[420];
  mr_glove_state st = mr_glove_get_state(sg->glove);
  if (st != sg->seen_state) {
    sg->seen_state = st;
    sg->seen_since = now;
  }
  mr_glove_describe(sg->glove, now, said, sizeof said);
  if (st != sg->told_state && now - sg->seen_since >= TELL_AFTER_S) {
    sg->told_state = st;
    mr_show_note(s, said);
  } else if (st == MR_GLOVE_CONNECTING && now >= 2.0 && !sg->told_silent) {
    sg->told_silent = true;
    snprintf(line, sizeof line, "%s; nothing a glove sends has come in %.0f s", said, now);
    mr_show_note(s, line);
  }
  tell_errors(s, g, now);
  tell_publishers(s, g);
}
