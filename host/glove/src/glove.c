/* A glove as a live object: source, decoder, INFO, calibrated values,
 * loss and reconnection (protocol/SPEC.md, "Receiver rules"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "glove_internal.h"

const char *mr_glove_state_name(mr_glove_state s) {
  switch (s) {
  case MR_GLOVE_CONNECTING:
    return "connecting";
  case MR_GLOVE_LIVE:
    return "live";
  case MR_GLOVE_LOST:
    return "lost";
  case MR_GLOVE_MISMATCH:
    return "spec mismatch";
  }
  return "unknown";
}

mr_glove_def mr_default_glove_def(void) {
  mr_glove_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  snprintf(d.source, sizeof d.source, "serial:auto");
  d.lost_after = 0.5;
  d.retry_every = 0.5;
  d.cmd_timeout = 0.25;
  d.cmd_tries = 5;
  return d;
}

/* A glove source as an mr_io spec: pty:PATH is a tty opened through
 * termios, which mr_io does for a serial spec naming a pty; take:PATH is
 * a file that must be a take. */
int mr_glove_io_spec(const char *source, char *out, size_t size) {
  static const char *const prefixes[] = { "serial:", "file:", "tcp:", "tcp-listen:", NULL };
  if (strncmp(source, "pty:", 4) == 0)
    return source[4] != '\0' && snprintf(out, size, "serial:%s", source + 4) < (int)size ? 0 : -1;
  if (strncmp(source, "take:", 5) == 0)
    return source[5] != '\0' && snprintf(out, size, "file:%s", source + 5) < (int)size ? 0 : -1;
  if (strcmp(source, "serial:auto") == 0) return -1; /* probing comes with the port list */
  if (strcmp(source, "pty") == 0) return snprintf(out, size, "pty") < (int)size ? 0 : -1;
  if (mr_net_is_url(source)) return snprintf(out, size, "%s", source) < (int)size ? 0 : -1;
  /* A bare path (no prefix) is a file or a device, as mr_io takes it. */
  bool known = strcmp(source, "-") == 0 || source[0] == '/' ||
               (source[0] != '\0' && strchr(source, ':') == NULL);
  for (int i = 0; prefixes[i] != NULL && !known; i++) {
    size_t n = strlen(prefixes[i]);
    known = strncmp(source, prefixes[i], n) == 0 && source[n] != '\0';
  }
  return known && snprintf(out, size, "%s", source) < (int)size ? 0 : -1;
}

/* The file a file source names (take:, file: or a bare path), else NULL. */
static const char *file_path(const char *source) {
  if (strncmp(source, "take:", 5) == 0 || strncmp(source, "file:", 5) == 0) return source + 5;
  bool bare = source[0] == '/' || (strchr(source, ':') == NULL && strcmp(source, "-") != 0);
  return bare ? source : NULL;
}

/* A take by name: take:PATH, or a file named *.mrec. Its magic is then
 * required: a damaged take is reported, not read as a raw stream. */
static bool named_take(const char *source) {
  const char *path = file_path(source);
  size_t n = path != NULL ? strlen(path) : 0;
  return strncmp(source, "take:", 5) == 0 || (n > 5 && strcmp(path + n - 5, ".mrec") == 0);
}

/* A file source that is a take: by name, or a regular file that starts
 * with the recording magic. */
static bool file_is_take(const char *source) {
  const char *path = file_path(source);
  struct stat st;
  if (named_take(source)) return true;
  /* Regular files only: reading a device to look would take its bytes. */
  if (path == NULL || stat(path, &st) != 0 || !S_ISREG(st.st_mode)) return false;
  FILE *f = fopen(path, "rb");
  if (f == NULL) return false;
  char magic[8];
  size_t n = fread(magic, 1, sizeof magic, f);
  fclose(f);
  return mr_rec_is_recording(magic, n) != 0;
}

#define SOURCES_EXPECTED                                                              \
  "expected serial:DEV[@BAUD], serial:auto, pty:PATH, pty, file:PATH, take:PATH, -, " \
  "tcp:HOST:PORT, tcp-listen:[HOST:]PORT or mqtt[s]://[USER@]HOST[:PORT]/TOPIC"

mr_io_status mr_glove_source_check(const char *source, mr_glove_source_report *out) {
  char spec[MR_GLOVE_SOURCE_MAX + 16];
  mr_io_error err;
  memset(out, 0, sizeof *out);
  out->status = MR_IO_ERR_SPEC;
  if (source == NULL || strlen(source) >= MR_GLOVE_SOURCE_MAX) {
    snprintf(out->msg, sizeof out->msg, "glove source is %s",
             source == NULL ? "missing" : "longer than 255 characters");
    return out->status;
  }
  if (strcmp(source, "serial:auto") == 0) return out->status = MR_IO_OK;
  if (mr_glove_io_spec(source, spec, sizeof spec) != 0) {
    snprintf(out->msg, sizeof out->msg, "glove source '%.200s': " SOURCES_EXPECTED, source);
    return out->status;
  }
  if (mr_net_is_url(source)) return out->status = mr_glove_net_check(source, out);
  if (mr_io_spec_check(spec, MR_IO_READ, out->note, sizeof out->note, &err) != 0) {
    /* In the user's words: pty:PATH, not the serial: it is opened as. */
    size_t n = strlen(spec);
    bool same = strncmp(err.msg, spec, n) == 0 && strcmp(spec, source) != 0;
    snprintf(out->msg, sizeof out->msg, "%s%s", same ? source : "", err.msg + (same ? n : 0));
    return out->status = err.status;
  }
  if (file_is_take(source)) {
    /* The header is read now: a take that is no take fails before the
     * show; a chunk's defect is found where the replay reaches it. */
    mr_rec_reader r;
    if (mr_rec_reader_open(&r, file_path(source), &err) != 0) {
      snprintf(out->msg, sizeof out->msg, "%s", err.msg);
      return out->status = err.status;
    }
    mr_rec_reader_close(&r);
  }
  return out->status = MR_IO_OK;
}

mr_glove_status mr_glove_create(const mr_glove_def *def, mr_glove **out, char *msg,
                                size_t msg_size) {
  char dummy[8];
  if (msg == NULL || msg_size == 0) {
    msg = dummy;
    msg_size = sizeof dummy;
  }
  if (out != NULL) *out = NULL;
  if (def == NULL || out == NULL || def->cookie != MR_DEF_COOKIE) {
    snprintf(msg, msg_size, "expected a glove definition made by mr_default_glove_def");
    return MR_GLOVE_ERR_ARG;
  }
  if (!(def->lost_after > 0) || !(def->retry_every > 0 && def->retry_every <= 1.0)) {
    snprintf(msg, msg_size,
             "glove %s: expected lost_after > 0 and retry_every in (0, 1] s, got %g and %g",
             def->source, def->lost_after, def->retry_every);
    return MR_GLOVE_ERR_ARG;
  }
  if (!isfinite(def->reconnect)) {
    snprintf(msg, msg_size, "glove %s: expected a finite reconnect time", def->source);
    return MR_GLOVE_ERR_ARG;
  }
  if (!(def->cmd_timeout > 0 && def->cmd_timeout <= 60) || def->cmd_tries < 1 ||
      def->cmd_tries > 100) {
    snprintf(msg, msg_size,
             "glove %s: expected cmd_timeout in (0, 60] s and cmd_tries in 1..100, got %g and %d",
             def->source, def->cmd_timeout, def->cmd_tries);
    return MR_GLOVE_ERR_ARG;
  }
  mr_glove *g = calloc(1, sizeof *g);
  if (g == NULL) {
    snprintf(msg, msg_size, "out of memory");
    return MR_GLOVE_ERR_ARG;
  }
  g->def = *def;
  g->def.source[MR_GLOVE_SOURCE_MAX - 1] = '\0';
  g->is_auto = strcmp(g->def.source, "serial:auto") == 0;
  g->is_net = mr_net_is_url(g->def.source);
  if (!g->is_auto && mr_glove_io_spec(g->def.source, g->spec, sizeof g->spec) != 0) {
    snprintf(msg, msg_size, "glove source '%s': " SOURCES_EXPECTED, g->def.source);
    free(g);
    return MR_GLOVE_ERR_ARG;
  }
  gp_decoder_init(&g->dec, GP_SPEC_HASH);
  g->offset = NAN;
  g->next_open = -INFINITY;
  g->is_take = file_is_take(g->def.source);
  g->writable = !g->is_take &&
                (g->is_auto || strncmp(g->def.source, "serial:", 7) == 0 ||
                 strncmp(g->def.source, "pty:", 4) == 0 || strncmp(g->def.source, "tcp:", 4) == 0 ||
                 strncmp(g->def.source, "tcp-listen:", 11) == 0 ||
                 strcmp(g->def.source, "pty") == 0 || mr_net_is_url(g->def.source));
  g->next_tag = 1;
  *out = g;
  return MR_GLOVE_OK;
}

static void close_source(mr_glove *g) {
  if (g->take_open) {
    mr_rec_reader_close(&g->take);
    g->take_open = false;
  }
  if (!g->open) return;
  if (g->net != NULL)
    mr_net_close(g->net);
  else
    mr_io_close(&g->io);
  g->net = NULL;
  g->open = false;
}

void mr_glove_set_tap(mr_glove *g, mr_glove_tap_fn tap, void *user) {
  if (g == NULL) return;
  g->tap = tap;
  g->tap_user = user;
}

void mr_glove_destroy(mr_glove *g) {
  if (g == NULL) return;
  close_source(g);
  free(g->take_prefix);
  free(g);
}

static bool is_stream(const mr_glove *g) {
  return g->net == NULL && !g->is_net &&
         (g->io.kind == MR_IO_FILE || g->io.kind == MR_IO_FIFO || g->io.kind == MR_IO_STDIO);
}

/* The source hung up (or ended, when at_end). A frame cut short by it ends
 * here, as one error, rather than fusing with the first bytes after the
 * replug; the delimiter is the host's, not the glove's, so it is not
 * counted as received. What comes next comes over a new link, which
 * repeats nothing from this one: a glove that counts its sequence again
 * from below where it was is a restart, not a run of duplicates (a TCP
 * glove whose connections were shorter than the sequence window gave no
 * samples at all after a reconnect). A listening socket waits for the next peer on the
 * same port; anything else is closed and retried, or the glove ends, as
 * def.reconnect says. */
void mr_glove_mark_lost(mr_glove *g, double now, const char *why, bool at_end) {
  bool ends = at_end || g->def.reconnect < 0;
  if (!ends && g->open && (g->dec.len > 0 || g->dec.overflow)) {
    mr_glove_feed(g, (const uint8_t *)"", 1, now);
    g->dec.c.bytes--;
  }
  /* A broker's link reconnects by itself, unless it was refused. */
  bool rearmed =
      !ends && g->open && (g->is_net ? g->net != NULL && !g->net_failed : mr_io_rearm(&g->io) == 0);
  if (!rearmed) close_source(g);
  if (g->state != MR_GLOVE_LOST) {
    g->counters.losses++;
    g->lost_since = now;
    if (g->def.reconnect > 0) g->give_up_at = now + g->def.reconnect;
  }
  if (g->state != MR_GLOVE_MISMATCH) g->state = MR_GLOVE_LOST;
  if (why != g->last_error) snprintf(g->last_error, sizeof g->last_error, "%s", why);
  g->clock_fresh = true;
  gp_decoder_new_link(&g->dec);
  g->next_open = now + g->def.retry_every;
  if (ends) g->ended = true;
}

static void try_open(mr_glove *g, double now) {
  if (g->ended || g->open || now < g->next_open) return;
  if (g->give_up_at > 0 && now >= g->give_up_at) {
    snprintf(g->last_error, sizeof g->last_error, "not back within %g s", g->def.reconnect);
    g->ended = true;
    return;
  }
  if (g->is_auto && mr_glove_find(g) != 0) {
    g->counters.open_failures++;
    g->next_open = now + g->def.retry_every;
    return;
  }
  mr_io_error err;
  int opened = g->is_net ? mr_glove_net_open(g, &err)
                         : mr_io_open(&g->io, g->spec,
                                      g->writable ? MR_IO_READ | MR_IO_WRITE : MR_IO_READ, &err);
  if (opened != 0) {
    g->counters.open_failures++;
    snprintf(g->last_error, sizeof g->last_error, "%s", err.msg);
    g->take_error = err.status;
    g->next_open = now + g->def.retry_every;
    return;
  }
  g->take_error = MR_IO_OK;
  g->open = true;
  g->clock_fresh = true;
  g->counters.opens++;
  g->last_bytes = now;
  g->sniffing = !g->is_take && is_stream(g);
  g->sniffed = 0;
  /* The decoder carries on: the loss ended any frame it held and marked
   * a new link (mark_lost), so the new stream's first frame is read whole,
   * a glove that kept its sequence through the unplug shows what it lost
   * meanwhile, and one that counts again is a restart. */
}

/* Raw ADC counts to 0..1: by the glove's own calibrated range when its INFO
 * says the range is valid, else by the ADC's full scale. */
static double calibrate(const mr_glove *g, int k, uint16_t raw) {
  if (g->have_info && g->info.cal_state == GP_CAL_VALID && g->info.cal_max[k] > g->info.cal_min[k])
    return ((double)raw - g->info.cal_min[k]) / (double)(g->info.cal_max[k] - g->info.cal_min[k]);
  int bits = g->have_info && g->info.adc_bits > 0 && g->info.adc_bits <= 16 ? g->info.adc_bits : 12;
  return (double)raw / (double)((1u << bits) - 1u);
}

static void take_sample(mr_glove *g, const gp_sample *s, double now) {
  /* A restarted device clock is no wrap, and the smallest offset seen
   * before it says nothing of the new one (it left "ms late" seconds off
   * for the rest of a show after a replug). A restart is a reconnect, a
   * new INFO uid, or what the decoder counts as a sequence restart: a
   * START flag, or a sequence that started again (SPEC.md, rule 8). */
  if (g->clock_fresh || g->dec.c.seq_restarts != g->seen_restarts) {
    g->have_t = false;
    g->device_base = 0;
    g->offset = NAN;
    g->clock_fresh = false;
  }
  g->seen_restarts = g->dec.c.seq_restarts;
  if (g->have_t && s->t_us < g->last_t_us && g->last_t_us - s->t_us > 0x80000000u)
    g->device_base += 4294.967296; /* the µs counter wrapped */
  g->last_t_us = s->t_us;
  g->have_t = true;
  mr_glove_reading *r = &g->latest;
  for (int k = 0; k < MR_GLOVE_CHANNELS; k++) r->values[k] = calibrate(g, k, s->ch[k]);
  r->seq = s->seq;
  r->device_t = g->device_base + (double)s->t_us * 1e-6;
  r->host_t = now;
  r->samples++;
  double off = now - r->device_t;
  if (!(g->offset <= off)) g->offset = off;
  /* A frame that passed our CRC comes from a glove of our definition: a
   * stray foreign frame in the stream was noise, not the glove. */
  g->state = MR_GLOVE_LIVE;
}

int mr_glove_feed(mr_glove *g, const uint8_t *buf, size_t n, double now) {
  int taken = 0;
  while (n > 0) {
    gp_msg m;
    gp_event ev;
    size_t used = gp_decoder_feed(&g->dec, buf, n, &m, &ev);
    buf += used;
    n -= used;
    if (ev != GP_EV_NONE && g->observer != NULL) {
      bool carries = ev == GP_EV_FRAME || ev == GP_EV_FRAME_LATE || ev == GP_EV_DUPLICATE ||
                     (ev == GP_EV_SPEC_MISMATCH && m.type == GP_INFO);
      g->observer(g->observer_user, ev, carries ? &m : NULL, g->dec.c.bytes);
    }
    if (ev == GP_EV_SPEC_MISMATCH) {
      g->state = MR_GLOVE_MISMATCH;
      g->mismatch_hash = g->dec.peer_known ? g->dec.peer_hash : 0;
    } else if (ev == GP_EV_FRAME && m.type == GP_INFO) {
      if (g->have_info && memcmp(g->info.uid, m.u.info.uid, sizeof g->info.uid) != 0)
        g->clock_fresh = true; /* another glove on this source */
      g->info = m.u.info;
      g->have_info = true;
    } else if ((ev == GP_EV_FRAME) && m.type == GP_SAMPLE) {
      take_sample(g, &m.u.sample, now);
      taken++;
    } else if (ev == GP_EV_FRAME) {
      mr_glove_cmd_reply(g, &m);
    }
  }
  return taken;
}

/* After SET_RATE's ACK the glove talks at the new baud: the port is
 * reopened at it, at once. A TCP link has no baud to follow. */
static void follow_baud(mr_glove *g, double now) {
  uint32_t baud = g->follow_baud;
  g->follow_baud = 0;
  if (strncmp(g->spec, "serial:", 7) != 0) return;
  char *at = strchr(g->spec + 7, '@');
  if (at != NULL) *at = '\0';
  size_t len = strlen(g->spec);
  snprintf(g->spec + len, sizeof g->spec - len, "@%u", (unsigned)baud);
  close_source(g);
  g->next_open = now;
  try_open(g, now);
}

/* A stream's first bytes: a take's magic makes it a take (1), whether its
 * reader then opens or fails (a damaged take is reported as a take, with
 * its reader's message, never read on as a glove's bytes); a part of the
 * magic waits for more (−1); anything else is a glove's bytes, the ones
 * held back first (0, with them fed). */
static int sniff(mr_glove *g, const uint8_t *buf, size_t got, double now) {
  size_t k = got < sizeof g->sniff - g->sniffed ? got : sizeof g->sniff - g->sniffed;
  memcpy(g->sniff + g->sniffed, buf, k);
  g->sniffed += k;
  if (memcmp(g->sniff, MR_REC_MAGIC, g->sniffed) == 0 && g->sniffed < sizeof g->sniff && k == got)
    return -1;
  g->sniffing = false;
  if (mr_rec_is_recording(g->sniff, g->sniffed)) {
    /* The take's reader goes on from here; what came after the magic in
     * this read is the start of its header. */
    uint8_t head[4096 + 8];
    memcpy(head, g->sniff, g->sniffed);
    memcpy(head + g->sniffed, buf + k, got - k);
    mr_glove_take_from_stream(g, head, g->sniffed + got - k, now);
    return 1;
  }
  size_t held = g->sniffed - k;
  if (held > 0) {
    if (g->tap != NULL) g->tap(g->tap_user, now, g->sniff, held);
    mr_glove_feed(g, g->sniff, held, now);
  }
  return 0;
}

/* Reads what a byte source has into the decoder, adding to *taken the
 * SAMPLEs it took. True when the source was lost or turned out a take
 * (the poll ends there). */
static bool read_io(mr_glove *g, double now, int timeout_ms, int *taken) {
  uint8_t buf[4096];
  for (int round = 0; round < 64; round++) {
    size_t got = 0;
    mr_io_error err;
    mr_io_status st = mr_io_read(&g->io, buf, sizeof buf, round == 0 ? timeout_ms : 0, &got, &err);
    if (got > 0) {
      g->last_bytes = now;
      g->give_up_at = 0;
      if (g->sniffing) {
        int k = sniff(g, buf, got, now);
        if (k < 0) continue;
        if (k > 0) {
          *taken += mr_glove_take_play(g, now);
          return true;
        }
      }
      if (g->tap != NULL) g->tap(g->tap_user, now, buf, got);
      *taken += mr_glove_feed(g, buf, got, now);
    }
    if (st == MR_IO_TIMEOUT) break;
    if (st == MR_IO_EOF || st == MR_IO_HANGUP || mr_io_failed(st)) {
      mr_glove_mark_lost(g, now,
                         st == MR_IO_EOF      ? "the stream ended"
                         : st == MR_IO_HANGUP ? "the port went away"
                                              : err.msg,
                         st == MR_IO_EOF && is_stream(g));
      return true;
    }
    if (got < sizeof buf) break;
  }
  return false;
}

int mr_glove_poll(mr_glove *g, double now, int timeout_ms) {
  if (g == NULL || !isfinite(now)) return 0;
  if (g->ended && !g->is_take) return 0;
  /* A listener waiting for its next peer gives up as def.reconnect says. */
  if (g->open && g->give_up_at > 0 && now >= g->give_up_at) {
    snprintf(g->last_error, sizeof g->last_error, "nothing came back within %g s",
             g->def.reconnect);
    close_source(g);
    g->ended = true;
    return 0;
  }
  if (g->is_take) {
    int taken = mr_glove_take_play(g, now);
    if (taken == 0) mr_glove_take_wait(g, now, timeout_ms);
    /* Lost only after lost_after, as a live glove: the frame that read the
     * last chunk must take its samples, as it did live. A take that failed
     * keeps its reader's message. */
    if (now - g->last_bytes > g->def.lost_after && g->state != MR_GLOVE_MISMATCH &&
        g->state != MR_GLOVE_LOST)
      mr_glove_mark_lost(g, now,
                         !g->take_done                 ? "no bytes for longer than lost_after"
                         : mr_io_failed(g->take_error) ? g->last_error
                                                       : "the take ended",
                         g->take_done);
    return taken;
  }
  try_open(g, now);
  mr_glove_cmd_poll(g, now);
  if (!g->open) return 0;
  int taken = 0;
  bool gone = g->is_net ? mr_glove_net_read(g, now, timeout_ms, &taken)
                        : read_io(g, now, timeout_ms, &taken);
  if (gone) return taken;
  if (g->follow_baud != 0) follow_baud(g, now);
  /* With the stream off a glove sends INFO once a second, no more. */
  double quiet = g->stream_off ? fmax(g->def.lost_after, 1.5) : g->def.lost_after;
  /* A broker's loss keeps its own words ("the broker went away"). */
  bool told = g->is_net && g->state == MR_GLOVE_LOST;
  if (now - g->last_bytes > quiet && g->state != MR_GLOVE_MISMATCH && !told)
    mr_glove_mark_lost(g, now, "no bytes for longer than lost_after", false);
  return taken;
}

mr_glove_state mr_glove_get_state(const mr_glove *g) {
  return g != NULL ? g->state : MR_GLOVE_CONNECTING;
}

const gp_info *mr_glove_info(const mr_glove *g) {
  return g != NULL && g->have_info ? &g->info : NULL;
}

void mr_glove_latest(const mr_glove *g, mr_glove_reading *out) {
  if (g != NULL && out != NULL) *out = g->latest;
}

void mr_glove_get_counters(const mr_glove *g, mr_glove_counters *out) {
  if (g == NULL || out == NULL) return;
  *out = g->counters;
  out->decoder = g->dec.c;
}

double mr_glove_clock_offset(const mr_glove *g) {
  return g != NULL ? g->offset : NAN;
}

const char *mr_glove_describe(const mr_glove *g, double now, char *out, size_t size) {
  if (out == NULL || size == 0) return out;
  if (g == NULL) {
    snprintf(out, size, "no glove");
    return out;
  }
  const char *src = g->def.source;
  switch (g->state) {
  case MR_GLOVE_MISMATCH:
    snprintf(out, size,
             "glove on %s was built from protocol 0x%08X, this host speaks 0x%08X: reflash it", src,
             (unsigned)g->mismatch_hash, (unsigned)GP_SPEC_HASH);
    break;
  case MR_GLOVE_LOST:
    if (mr_glove_ended(g))
      snprintf(out, size, "glove on %s: ended %.1f s ago (%s)", src, now - g->lost_since,
               g->last_error);
    else
      snprintf(out, size, "glove on %s: lost %.1f s ago (%s); retrying every %.1f s", src,
               now - g->lost_since, g->last_error, g->def.retry_every);
    break;
  case MR_GLOVE_LIVE:
    if (g->have_info)
      snprintf(out, size, "glove on %s: live, uid %08X, %s hand, %u Hz, %llu samples", src,
               (unsigned)g->info.uid[0], g->info.hand == GP_HAND_LEFT ? "left" : "right",
               (unsigned)g->info.frame_rate_hz, (unsigned long long)g->latest.samples);
    else
      snprintf(out, size, "glove on %s: live, %llu samples, no INFO yet", src,
               (unsigned long long)g->latest.samples);
    mr_glove_net_note(g, out + strlen(out), size - strlen(out));
    break;
  default:
    snprintf(out, size, "glove on %s: connecting%s%s", src, g->last_error[0] ? " (" : "",
             g->last_error[0] ? g->last_error : "");
    if (g->last_error[0]) snprintf(out + strlen(out), size - strlen(out), ")");
    break;
  }
  return out;
}

void mr_glove_set_observer(mr_glove *g, mr_glove_observer_fn fn, void *user) {
  if (g == NULL) return;
  g->observer = fn;
  g->observer_user = user;
}

bool mr_glove_ended(const mr_glove *g) {
  return g != NULL && (g->ended || (g->is_take && g->take_done));
}

const char *mr_glove_io_path(const mr_glove *g) {
  if (g == NULL || !g->open) return "";
  return g->net != NULL ? mr_net_where(g->net) : mr_io_path(&g->io);
}

size_t mr_glove_unfinished(const mr_glove *g) {
  return g != NULL && !g->dec.overflow ? g->dec.len : 0;
}

const char *mr_glove_last_error(const mr_glove *g, mr_io_status *status) {
  if (status != NULL) *status = g != NULL ? g->take_error : MR_IO_OK;
  return g != NULL ? g->last_error : "";
}

bool mr_glove_is_take(const mr_glove *g) {
  return g != NULL && g->is_take;
}

uint32_t mr_glove_foreign_hash(const mr_glove *g) {
  return g != NULL && g->dec.peer_known ? g->dec.peer_hash : 0;
}
