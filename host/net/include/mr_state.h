/* mr_state: a show's state over a broker (host/net/STATE.md).
 *
 * A show publishes each simulated frame on TOPIC as a FRAME message (its
 * time, its control poses, its particles quantised to 16 bits per axis
 * over the frame's own box), and keeps its scene retained on TOPIC/scene
 * as a SCENE message (the scene file and the files beside it that it
 * uses), so that a watcher who joins late builds the same scene and
 * stage. The messages are defined once, in host/net/state.def, with a
 * version and a spec hash; mr_state_messages.h is generated from it.
 *
 * The publisher (mr_state_out) never waits: a frame the network cannot
 * take at once is dropped and counted. The watcher's side (mr_state_in)
 * decodes, checks every message (CRC, length, spec hash) and counts what
 * it lost, what was corrupt and what it refused. Nothing here prints or
 * aborts. */
#ifndef MR_STATE_H
#define MR_STATE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"
#include "mr_io.h"
#include "mr_state_messages.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
  MR_STATE_MAX_FRAMES = 255,       /* control frames in a FRAME (n_frames is a u8) */
  MR_STATE_MAX_POINTS = 65535,     /* particles in a FRAME (n_points is a u16) */
  MR_STATE_NAME_MAX = 256,         /* a file's name in a SCENE, with its NUL */
  MR_STATE_DEFAULT_SCENE = 1 << 24 /* the largest SCENE a watcher takes by default: 16 MiB */
};

/* xyz (3 n) quantised: origin and step (per axis, step 0 on a flat axis)
 * and q (3 n), so that origin + q step is within step / 2 of each value
 * (rounding to float aside). */
void mr_state_quantise(const double *xyz, size_t n, float origin[3], float step[3], uint16_t *q);
/* Point i of a decoded frame, back in metres. */
void mr_state_point(const mr_state_frame *m, size_t i, double out[3]);

/* The files of a SCENE as they are built: records of a u16 name length,
 * the name, a u32 data length and the data (state.def). */
typedef struct mr_state_bundle {
  uint8_t *data;
  size_t size, cap;
  uint16_t n_files;
} mr_state_bundle;
/* One file added: 0, or -1 for a name that is empty, absolute, holds
 * "..", or is MR_STATE_NAME_MAX long, or when memory runs out. */
int mr_state_bundle_add(mr_state_bundle *b, const char *name, const void *data, size_t len);
void mr_state_bundle_free(mr_state_bundle *b);
/* FNV-1a 64 of the records: a SCENE's scene_hash. */
uint64_t mr_state_bundle_hash(const uint8_t *files, size_t size);

/* One file of a received SCENE. */
typedef struct mr_state_file {
  char name[MR_STATE_NAME_MAX];
  const uint8_t *data; /* into the message */
  size_t len;
} mr_state_file;
/* The file at *off of files (size bytes) into f, *off moved past it: 1;
 * 0 at the end; -1 for a record cut short or a name that is not safe to
 * write under a folder (empty, absolute, "..", a NUL). */
int mr_state_bundle_next(const uint8_t *files, size_t size, size_t *off, mr_state_file *f);

/* ---- The show's side ---------------------------------------------- */

typedef struct mr_state_out_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_state_out_def() */
  const char *url; /* mqtt[s]://[USER@]HOST[:PORT]/TOPIC[?...] (host/net/README.md) */
  /* The scene: its files (the scene file first), the show's rate and
   * what each frame holds. */
  const mr_state_bundle *scene;
  double fps;
  int n_frames, n_points;
  /* Frames waiting for the socket at the most, past which the next is
   * dropped (default 16: a quarter second at 60 fps). */
  int max_unsent;
  int connect_wait_ms; /* default 3000; a broker that has not answered by then: an error */
} mr_state_out_def;
mr_state_out_def mr_default_state_out_def(void);

typedef struct mr_state_out_counters {
  uint64_t frames;         /* handed in */
  uint64_t sent;           /* published */
  uint64_t bytes;          /* in the FRAME messages published (payloads) */
  uint64_t dropped_behind; /* dropped: max_unsent were waiting */
  uint64_t dropped_away;   /* dropped: the broker was away */
  uint64_t scenes;         /* SCENE messages published (again after each reconnection) */
  size_t scene_bytes;      /* the SCENE message's size */
} mr_state_out_counters;

typedef struct mr_state_out mr_state_out;

/* Connects and publishes the retained SCENE. 0, or -1 with err (a URL,
 * a refusal, no broker, a scene too large). */
int mr_state_out_open(const mr_state_out_def *def, mr_state_out **out, mr_io_error *err);
/* Frame seq: its time t (s), its control poses (7 n_frames: position,
 * then orientation w x y z) and its particles (3 n_points). 0 when
 * published, 1 when dropped (counted), -1 with err when the broker
 * refused the show for good (its ACL). Never waits for the network. */
int mr_state_out_frame(mr_state_out *o, double t, const double *poses, const double *xyz,
                       mr_io_error *err);
void mr_state_out_get_counters(const mr_state_out *o, mr_state_out_counters *out);
/* Clears the retained scene (the show is over), disconnects, frees. */
void mr_state_out_close(mr_state_out *o);

/* ---- The watcher's side ------------------------------------------- */

typedef struct mr_state_in_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_state_in_def() */
  const char *url;
  size_t max_scene;    /* the largest SCENE taken; default MR_STATE_DEFAULT_SCENE */
  int queue_messages;  /* received messages held; default 1024 */
  int connect_wait_ms; /* default 3000 */
} mr_state_in_def;
mr_state_in_def mr_default_state_in_def(void);

typedef enum mr_state_event_kind {
  MR_STATE_NOTHING = 0, /* nothing within the timeout */
  MR_STATE_GOT_SCENE,   /* ev->scene */
  MR_STATE_GOT_FRAME,   /* ev->frame and its arrays */
  MR_STATE_REFUSED,     /* a message from another state.def: ev->hash is its spec hash */
  MR_STATE_BROKER_LOST  /* the broker went away (the link reconnects by itself) */
} mr_state_event_kind;

/* What one read gave: its arrays are the reader's, good until the next read. */
typedef struct mr_state_event {
  mr_state_event_kind kind;
  uint8_t type;         /* REFUSED: the message's type byte */
  uint32_t hash;        /* REFUSED: its spec hash */
  mr_state_scene scene; /* GOT_SCENE: files point into the reader */
  mr_state_frame frame; /* GOT_FRAME: as decoded */
  double t;             /* GOT_FRAME: its time, s */
  double lag;           /* GOT_FRAME: received (wall clock) minus sent, s */
  double *poses;        /* GOT_FRAME: 7 n_frames */
  double *xyz;          /* GOT_FRAME: 3 n_points, back in metres */
} mr_state_event;

typedef struct mr_state_in_counters {
  uint64_t messages;    /* taken from the link */
  uint64_t frames;      /* FRAMEs decoded and handed out */
  uint64_t scenes;      /* SCENEs decoded and handed out */
  uint64_t lost;        /* FRAMEs never received: the gaps in seq */
  uint64_t corrupt;     /* a CRC that did not match, a length its fields do not
                           make, an unknown type */
  uint64_t refused;     /* built from another state.def (another spec hash) */
  uint64_t stale;       /* a FRAME older than one already handed out, or of
                           another scene than the one received: dropped */
  uint64_t oversized;   /* over max_scene bytes: dropped by the link */
  uint64_t queue_full;  /* dropped by the link: the reader fell behind */
  uint64_t empty;       /* empty messages (a cleared scene) */
  uint64_t broker_lost; /* times the broker went away */
  uint64_t bytes;       /* in the messages taken */
} mr_state_in_counters;

typedef struct mr_state_in mr_state_in;

int mr_state_in_open(const mr_state_in_def *def, mr_state_in **out, mr_io_error *err);
/* The next event, waiting up to timeout_ms (0: not at all). MR_IO_OK
 * with ev filled (kind NOTHING when nothing came), or a failure with err
 * (the broker refused the link for good). */
mr_io_status mr_state_in_read(mr_state_in *in, int timeout_ms, mr_state_event *ev,
                              mr_io_error *err);
void mr_state_in_get_counters(mr_state_in *in, mr_state_in_counters *out);
void mr_state_in_close(mr_state_in *in);

#ifdef __cplusplus
}
#endif

#endif /* MR_STATE_H */
