/* mr_glove: a glove as a live object.
 *
 * A glove is a byte source (a serial port, a pty, a file, stdin, TCP, or
 * a topic of an MQTT broker through mr_net)
 * with the protocol's decoder on it (protocol/SPEC.md). It keeps the INFO
 * the glove announced (uid, hand, firmware, spec hash, calibration range,
 * rates), the latest five values calibrated to 0..1 with their device and
 * host times, an estimate of the device-to-host clock offset, and the
 * decoder's counters.
 *
 * A glove that stops sending, or whose port goes away, is marked lost; its
 * port is tried again every retry_every seconds (at least once a second)
 * and the stream resumes without a restart. A glove built from another
 * protocol definition is a state of its own, shown, never swallowed.
 *
 * Time is an argument: every call that needs it takes the caller's `now`
 * (the theater's clock), so tests drive losses and retries on a virtual
 * clock. The library never prints and never aborts.
 */
#ifndef MR_GLOVE_H
#define MR_GLOVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"
#include "gp.h"
#include "mr_io.h"
#include "mr_net.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { MR_GLOVE_CHANNELS = 5, MR_GLOVE_SOURCE_MAX = 256 };

typedef enum mr_glove_state {
  MR_GLOVE_CONNECTING = 0, /* not open yet, or opened and waiting for bytes */
  MR_GLOVE_LIVE,           /* samples arriving */
  MR_GLOVE_LOST,           /* port gone or silent: retrying, last values held */
  MR_GLOVE_MISMATCH        /* built from another protocol definition: reflash */
} mr_glove_state;
const char *mr_glove_state_name(mr_glove_state s);

typedef struct mr_glove_def {
  uint32_t cookie;                  /* MR_DEF_COOKIE, set by mr_default_glove_def() */
  char source[MR_GLOVE_SOURCE_MAX]; /* serial:DEV[@BAUD], serial:auto, pty:PATH,
                                       pty (a new one, for a writer to open),
                                       file:PATH, PATH, -, tcp:HOST:PORT,
                                       tcp-listen:[HOST:]PORT (127.0.0.1
                                       unless HOST is named); a take (.mrec),
                                       as a file or on a stream, plays its
                                       bytes at their recorded times;
                                       take:PATH and a file named *.mrec
                                       must be takes;
                                       mqtt[s]://[USER@]HOST[:PORT]/TOPIC
                                       a glove's topic on a broker
                                       (mr_net.h, host/net/README.md) */
  double lost_after;  /* s without a sample before a live glove is lost; default 0.5 */
  double retry_every; /* s between attempts to reopen; default 0.5, at most 1 */
  /* After a hang-up: < 0 the glove ends there; 0 (default) its port is
   * retried for ever; > 0 retried this long, then the glove ends. A stream
   * that comes to its end (a file, stdin, a FIFO) ends the glove. */
  double reconnect;
  double cmd_timeout; /* s before an unanswered command is sent again; default 0.25 */
  int cmd_tries;      /* sends before a command is given up; default 5 */
} mr_glove_def;
mr_glove_def mr_default_glove_def(void);

/* The latest reading. */
typedef struct mr_glove_reading {
  double values[MR_GLOVE_CHANNELS]; /* calibrated, nominally 0..1 */
  uint16_t seq;
  double device_t;  /* the sample's device time, s, unwrapped */
  double host_t;    /* when its bytes were read, the caller's clock */
  uint64_t samples; /* SAMPLEs taken so far */
} mr_glove_reading;

typedef struct mr_glove_counters {
  gp_counters decoder; /* over every connection */
  uint64_t opens, open_failures, losses;
} mr_glove_counters;

typedef enum mr_glove_status {
  MR_GLOVE_OK = 0,
  MR_GLOVE_ERR_ARG = -1 /* a NULL, a def not made by its maker, a bad source */
} mr_glove_status;

typedef struct mr_glove mr_glove;

/* Every chunk of bytes the glove reads, with the `now` it was read at: a
 * take records them (mr_rec_writer) so that a replay feeds the same bytes
 * at the same times. */
typedef void (*mr_glove_tap_fn)(void *user, double now, const uint8_t *bytes, size_t len);

/* What mr_glove_source_check found. */
typedef struct mr_glove_source_report {
  mr_io_status status; /* MR_IO_OK; MR_IO_ERR_SPEC: the user named a source
                          that cannot be (bad usage); another MR_IO_ERR_*:
                          it is there but cannot be used (a damaged take) */
  char msg[400];       /* what is wrong, naming the source or file; "" if OK */
  char note[320];      /* a sound source worth one line to the user, told
                          once (tcp-listen beyond the loopback: plain TCP
                          has no authentication); "" if none */
} mr_glove_source_report;

/* Checks a glove source before anything starts, as mr_glove_create and
 * the first poll would take it, without opening a device: the spec
 * parses (ports, baud rates), a named device or file is there (and is not
 * a directory), and a take's header reads. Returns out->status. Programs
 * call it before a show or a dump and treat MR_IO_ERR_SPEC as bad usage;
 * mr_glove_create does not, so that a glove may be created before its
 * device appears. */
mr_io_status mr_glove_source_check(const char *source, mr_glove_source_report *out);

/* Checks the definition; the source is opened at the first poll. */
mr_glove_status mr_glove_create(const mr_glove_def *def, mr_glove **out, char *msg,
                                size_t msg_size);
void mr_glove_destroy(mr_glove *g);
void mr_glove_set_tap(mr_glove *g, mr_glove_tap_fn tap, void *user);
/* For a take: true once every chunk has been fed (the take is over). */
bool mr_glove_take_done(const mr_glove *g);

/* Reads what the source has (waiting up to timeout_ms for the first byte;
 * a take with nothing due yet sleeps up to timeout_ms, or until its next
 * chunk is due if `now` runs at wall pace), decodes it and updates the
 * state, at the caller's time `now`. A `now` past any take's end (over
 * 2^64 ns, e.g. 1e12 s) plays every chunk at once. Opens or
 * reopens the source when it is due. Returns how many new SAMPLEs were
 * taken. */
int mr_glove_poll(mr_glove *g, double now, int timeout_ms);

mr_glove_state mr_glove_get_state(const mr_glove *g);
/* The glove's INFO, or NULL before one arrived. */
const gp_info *mr_glove_info(const mr_glove *g);
void mr_glove_latest(const mr_glove *g, mr_glove_reading *out);
void mr_glove_get_counters(const mr_glove *g, mr_glove_counters *out);
/* host time − device time, the smallest seen (the path's fixed delay
 * included) since the device clock last started afresh (a START flag, a
 * reconnect, a new INFO uid, a sequence restart), s; NAN before a sample. A sample's latency is its host time
 * minus its device time minus this. */
double mr_glove_clock_offset(const mr_glove *g);
/* One line for the user: the source, the state and what to do about it.
 * Returns out. */
const char *mr_glove_describe(const mr_glove *g, double now, char *out, size_t size);

/* ------------------------------------------------------------ commands */

enum { MR_GLOVE_MAX_PENDING = 16 };

typedef struct mr_glove_cmd {
  uint8_t type;           /* GP_PING, GP_GET_INFO, GP_SET_RATE, GP_STREAM_ON, GP_STREAM_OFF,
                             GP_CAL_START, GP_CAL_SAVE, GP_CAL_CLEAR or GP_GET_STATUS */
  uint16_t frame_rate_hz; /* SET_RATE */
  uint32_t baud;          /* SET_RATE; 0 keeps the baud */
} mr_glove_cmd;

typedef enum mr_glove_cmd_state {
  MR_GLOVE_CMD_UNKNOWN = 0, /* no command with that tag is remembered */
  MR_GLOVE_CMD_PENDING,     /* sent (or waiting for the port), no answer yet */
  MR_GLOVE_CMD_ACKED,
  MR_GLOVE_CMD_NACKED,   /* refused: nack_reason says why (GP_NACK_*) */
  MR_GLOVE_CMD_TIMED_OUT /* cmd_tries sends, no answer */
} mr_glove_cmd_state;

typedef struct mr_glove_cmd_result {
  mr_glove_cmd_state state;
  uint8_t type, tag, nack_reason;
  int sends; /* how many times it went out */
} mr_glove_cmd_result;

/* Queues cmd under a fresh tag and sends it at once when the port is open.
 * Returns the tag (1..255) to follow it by, or −1 with msg naming the
 * glove and why (a take, a file or stdin carries no commands; a type that
 * is not a command). The oldest answered commands make room for new ones;
 * at most MR_GLOVE_MAX_PENDING wait at once. */
int mr_glove_command(mr_glove *g, const mr_glove_cmd *cmd, double now, char *msg, size_t msg_size);
/* Writes len bytes, whole frames a host built (a relay's commands from
 * afar), to the glove as they are, untracked: the answers come in the
 * stream as any. 0, or −1 with msg (a source that carries no commands,
 * or is not open: the bytes are dropped). */
int mr_glove_send_raw(mr_glove *g, const uint8_t *bytes, size_t len, char *msg, size_t msg_size);
/* Where the command sent under tag stands. */
mr_glove_cmd_result mr_glove_command_result(const mr_glove *g, int tag);
/* "GET_INFO", ...; "BAD_ARGUMENT", ... */
const char *mr_glove_cmd_name(uint8_t type);
const char *mr_glove_nack_reason_name(uint8_t reason);
/* The latest STATUS frame, or NULL before one arrived. */
const gp_status *mr_glove_status_frame(const mr_glove *g);

/* ------------------------------------------------------- for a stream dump */

/* Every frame and every error the decoder meets, as it meets it: the
 * event, the message for the events that carry one (else NULL), and the
 * count of bytes fed when it ended. */
typedef void (*mr_glove_observer_fn)(void *user, gp_event ev, const gp_msg *m, uint64_t byte);
void mr_glove_set_observer(mr_glove *g, mr_glove_observer_fn fn, void *user);
/* True once the source has ended for good (def.reconnect, a stream's end,
 * a take played out): polling reads nothing more. */
bool mr_glove_ended(const mr_glove *g);
/* Where the open source is (a created pty's slave path, a listening
 * socket's HOST:PORT); "" before it opened. */
const char *mr_glove_io_path(const mr_glove *g);
/* Bytes of a frame the decoder holds, begun but not ended. */
size_t mr_glove_unfinished(const mr_glove *g);
/* The last thing that went wrong with the source, "" if nothing, and in
 * *status (if given) its kind: an open's failure (MR_IO_ERR_SPEC for a
 * source that does not parse), a take's early end (MR_IO_ERR_FORMAT,
 * MR_IO_ERR_TRUNCATED); MR_IO_OK when nothing failed. */
const char *mr_glove_last_error(const mr_glove *g, mr_io_status *status);
/* A glove over a broker: its link's counters (garbage and oversized
 * messages, a second publisher) into *out, and true; false for any other
 * source, or before the link opened (*out zeroed). */
bool mr_glove_net_counters(const mr_glove *g, mr_net_counters *out);
/* The same glove: the stamps of two publishers on its topic, and true,
 * once a second one was seen while the first sent (mr_net_publishers). */
bool mr_glove_net_publishers(const mr_glove *g, char *first, char *second, size_t size);

/* True when the source turned out to be a take (by name or by its magic). */
bool mr_glove_is_take(const mr_glove *g);
/* The hash a foreign glove announced, 0 before one did. */
uint32_t mr_glove_foreign_hash(const mr_glove *g);

/* Listens on source (as a glove source names it) for up to wait_s seconds
 * of real time, writing nothing, and reports whether a glove announced
 * itself: 1 with its INFO (a glove of another definition too: *foreign is
 * then set), 0 when the port said nothing a glove would, −1 when it could
 * not be opened (msg says why). Any other device is left alone. */
int mr_glove_probe(const char *source, double wait_s, gp_info *info, bool *foreign, char *msg,
                   size_t msg_size);

#ifdef __cplusplus
}
#endif

#endif /* MR_GLOVE_H */
