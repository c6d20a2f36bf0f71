/* The glove's state, shared by its files. Private to mr_glove. */
#ifndef GLOVE_INTERNAL_H
#define GLOVE_INTERNAL_H

#include "mr_glove.h"
#include "mr_io.h"
#include "mr_net.h"

/* A command in flight or answered: its bytes, so a retry resends them. */
typedef struct mr_glove_pending {
  bool used;
  uint64_t serial;
  mr_glove_cmd cmd;
  mr_glove_cmd_result result;
  uint8_t wire[GP_MAX_WIRE];
  size_t len;
  double next_send;
} mr_glove_pending;

struct mr_glove {
  mr_glove_def def;
  char spec[MR_GLOVE_SOURCE_MAX + 16]; /* the source as mr_io reads it */
  mr_glove_state state;
  bool open, have_info;
  mr_io io;
  gp_decoder dec;
  gp_info info;
  mr_glove_reading latest;
  double last_bytes; /* when bytes last arrived */
  double next_open;  /* when to try the source again */
  double lost_since;
  double offset;      /* min(host − device), NAN before a sample */
  uint32_t last_t_us; /* for unwrapping device time */
  double device_base; /* s added for the wraps seen */
  bool have_t;
  /* The device clock starts afresh (a START flag, a reconnect, a new INFO
   * uid, a sequence restart): the next sample re-estimates the offset and
   * is not taken for a wrap. */
  bool clock_fresh;
  uint32_t seen_restarts; /* the decoder's seq_restarts at the last sample */
  uint32_t mismatch_hash;
  mr_glove_counters counters;
  char last_error[sizeof(((mr_io_error *)0)->msg)];
  mr_glove_tap_fn tap;
  void *tap_user;
  /* A take: chunks fed at their recorded times instead of a live source. */
  bool is_take, take_open, take_done, have_chunk;
  /* serial:auto: every serial port probed for a glove's INFO; once one
   * was found, only a glove of the same uid is taken again. */
  bool is_auto, have_uid;
  uint32_t uid[3];
  mr_rec_reader take;
  mr_io_status take_error; /* the last open's or take's failure, MR_IO_OK if none */
  bool sniffing;           /* a stream source's first bytes: is it a take? */
  uint8_t sniff[8];
  uint8_t *take_prefix; /* a stream take's first bytes, read by the sniff */
  size_t sniffed;
  bool ended;        /* the source ended, or was not back in time: no more retries */
  double give_up_at; /* def.reconnect > 0: the end of the wait for the source */
  mr_glove_observer_fn observer;
  void *observer_user;
  uint64_t chunk_t_ns;
  const uint8_t *chunk;
  size_t chunk_len;
  /* Commands (glove_cmd.c). */
  bool writable;        /* the source carries bytes both ways */
  uint32_t follow_baud; /* a SET_RATE's new baud, to reopen the port at */
  bool stream_off;      /* STREAM_OFF acknowledged: only INFO, once a second */
  mr_glove_pending cmds[MR_GLOVE_MAX_PENDING];
  uint8_t next_tag;
  uint64_t cmd_serial; /* orders the table's entries, oldest first */
  bool have_status;
  gp_status status;
  /* A glove over a broker (glove_net.c): its link instead of io. */
  bool is_net, net_failed;
  mr_net *net;
};

/* glove.c: a glove source as an mr_io spec into out: 0, or -1 for a
 * source that names none (serial:auto, a prefix unknown). */
int mr_glove_io_spec(const char *source, char *out, size_t size);

/* glove_probe.c: serial:auto's search, into g->spec: 0, or -1 with
 * g->last_error saying what was searched. */
int mr_glove_find(mr_glove *g);

/* glove.c: the source is lost (or ended, when at_end), why says why. */
void mr_glove_mark_lost(mr_glove *g, double now, const char *why, bool at_end);

/* glove_net.c: a broker's URL checked as mr_glove_source_check does
 * (into out; its status); the link opened (0, or -1 with err); what came
 * decoded, the SAMPLEs added to *taken, true when the link was lost. */
mr_io_status mr_glove_net_check(const char *source, mr_glove_source_report *out);
int mr_glove_net_open(mr_glove *g, mr_io_error *err);
bool mr_glove_net_read(mr_glove *g, double now, int timeout_ms, int *taken);
/* "; two publishers on TOPIC: A and B" when it is so, else nothing. */
void mr_glove_net_note(const mr_glove *g, char *out, size_t size);

/* glove.c: decodes bytes into the glove's state; how many SAMPLEs. */
int mr_glove_feed(mr_glove *g, const uint8_t *buf, size_t n, double now);

/* glove_take.c: plays what is due of a take; takes the stream the source
 * opened on as a take whose first len bytes were read already. */
int mr_glove_take_play(mr_glove *g, double now);
/* Sleeps up to timeout_ms while the take's next chunk is not due. */
void mr_glove_take_wait(const mr_glove *g, double now, int timeout_ms);
/* A take whose reader fails to open is done at once, the reader's message
 * the glove's last error. */
void mr_glove_take_from_stream(mr_glove *g, const uint8_t *prefix, size_t len, double now);

/* glove_cmd.c: sends what is due and retires what timed out (each poll);
 * takes an ACK, NACK or STATUS that arrived. */
void mr_glove_cmd_poll(mr_glove *g, double now);
void mr_glove_cmd_reply(mr_glove *g, const gp_msg *m);

#endif
