/* Takes an animator can work with: a take's frames decoded and written
 * again, punch-in of some channels from another take, filters and time
 * scaling, and a take list (a "book": a directory with takes.json and the
 * takes' files). host/take/README.md defines each operation exactly.
 *
 * A take is one .mrec per glove (mr_io, protocol/SPEC.md section 10).
 * Channels are (glove index, finger 0..4: thumb, index, middle, ring,
 * little). Values are merged and filtered as the host reads them:
 * calibrated by the INFO in effect (host/glove), then written back in the
 * raw counts of the take they land in.
 *
 * Nothing here prints or aborts: failures come back as -1 with an
 * mr_take_error naming the file and what is wrong.
 */
#ifndef MR_TAKE_H
#define MR_TAKE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "gp.h"
#include "mr_io.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MR_TAKE_CHANNELS   5
#define MR_TAKE_MAX_GLOVES 8
#define MR_TAKE_NAME_MAX   64
#define MR_TAKE_PATH_MAX   512
#define MR_TAKE_MAX_ARMS   (MR_TAKE_MAX_GLOVES * MR_TAKE_CHANNELS)

typedef enum mr_take_status {
  MR_TAKE_OK = 0,
  MR_TAKE_ERR_IO = -1,     /* a file could not be read, written or renamed */
  MR_TAKE_ERR_FORMAT = -2, /* a malformed .mrec or takes.json */
  MR_TAKE_ERR_ARG = -3,    /* an argument out of range (NaN, t_in >= t_out, ...) */
  MR_TAKE_ERR_SCENE = -4,  /* takes recorded against different scenes */
  MR_TAKE_ERR_NAME = -5,   /* an unknown, taken or malformed take name */
} mr_take_status;

typedef struct mr_take_error {
  mr_take_status status;
  char msg[640];
} mr_take_error;

/* --- one glove's recording, decoded ----------------------------------------- */

/* A calibration as the host applies it (host/glove): by INFO's range when
 * cal_state is VALID and max > min, else by the ADC's full scale. */
typedef struct mr_take_cal {
  bool ranged[MR_TAKE_CHANNELS];
  uint16_t lo[MR_TAKE_CHANNELS], hi[MR_TAKE_CHANNELS];
  double full; /* 2^adc_bits - 1 (adc_bits 1..16, else 12) */
} mr_take_cal;

/* The calibration of an INFO; NULL: none seen yet (the 12-bit full scale). */
mr_take_cal mr_take_cal_of(const gp_info *info);
/* Raw counts to the host's value. */
double mr_take_cal_value(const mr_take_cal *c, int finger, uint16_t raw);
/* A value to raw counts: the nearest count (half away from zero), clamped to
 * 0..GP_SAMPLE_CH_MAX; NaN reads as the low end. */
uint16_t mr_take_cal_raw(const mr_take_cal *c, int finger, double value);

/* A whole valid frame of the stream: its COBS run decodes, its length is its
 * type's, its CRC is good under this build's spec hash (an INFO's also
 * announces that hash). */
typedef struct mr_take_frame {
  size_t off, len; /* its wire bytes in mr_take_rec.data, delimiter included */
  size_t chunk;    /* the chunk holding its delimiter: the frame is read then */
  uint64_t t_ns;   /* that chunk's time */
  gp_msg msg;
  mr_take_cal cal; /* the calibration in effect (the newest INFO before it) */
} mr_take_frame;

typedef struct mr_take_chunk {
  uint64_t t_ns;
  size_t off, len; /* in mr_take_rec.data */
} mr_take_chunk;

typedef struct mr_take_rec {
  mr_rec_header header;
  uint8_t *data; /* every chunk's bytes, back to back */
  size_t len;
  mr_take_chunk *chunks;
  size_t n_chunks;
  mr_take_frame *frames;
  size_t n_frames;
  bool truncated; /* the file's last chunk was cut short: dropped, see note */
  char note[400]; /* "" or what was dropped, naming the file */
} mr_take_rec;

/* Reads path whole and finds its frames. A last chunk cut short is dropped
 * (truncated and note say so); anything else malformed is an error. */
int mr_take_rec_load(const char *path, mr_take_rec *r, mr_take_error *err);
/* A deep copy. */
int mr_take_rec_copy(mr_take_rec *dst, const mr_take_rec *src, mr_take_error *err);
void mr_take_rec_free(mr_take_rec *r);
/* Writes r as a new .mrec (base header fields: spec hash, start, scene). */
int mr_take_rec_write(const mr_take_rec *r, const char *path, mr_take_error *err);
/* The last chunk's time in s (0 for none). */
double mr_take_rec_duration(const mr_take_rec *r);
/* Re-encodes SAMPLE frame i with the channels ch (same seq, device time and
 * flags; CRC seeded by this build's spec hash) in place. */
int mr_take_rec_set_sample(mr_take_rec *r, size_t i, const uint16_t ch[MR_TAKE_CHANNELS],
                           mr_take_error *err);
/* The host's value of finger k in SAMPLE frame i. */
double mr_take_rec_value(const mr_take_rec *r, size_t i, int k);
/* Index of the newest SAMPLE read at or before t_ns, or -1. */
long mr_take_rec_sample_at(const mr_take_rec *r, uint64_t t_ns);

/* --- edits of one glove's recording (README.md defines each) ---------------- */

/* Seconds of show time to ns: nearest, half away from zero. */
uint64_t mr_take_ns(double t_s);

/* Within [t_in, t_out) s every SAMPLE of *base gets, in the fingers whose
 * bit is set in mask, over's value (newest SAMPLE at or before), re-expressed
 * in base's raw scale. over may be NULL (no change). Refuses different
 * scenes (both hashes nonzero). */
int mr_take_punch_rec(mr_take_rec *base, const mr_take_rec *over, unsigned mask, double t_in,
                      double t_out, mr_take_error *err);
/* The chunks of src in [t0, t1) s (t1 may be INFINITY), times less t0,
 * led by the newest INFO before t0 as a chunk at 0. */
int mr_take_trim_rec(const mr_take_rec *src, double t0, double t1, mr_take_rec *out,
                     mr_take_error *err);
/* One Euro on the host's values of the fingers in mask, over the SAMPLEs'
 * show times. */
int mr_take_smooth_rec(mr_take_rec *r, unsigned mask, double min_cutoff, double beta,
                       double d_cutoff, mr_take_error *err);
/* Finger k's value at t becomes the value at t - offset_s[k]. */
int mr_take_offset_rec(mr_take_rec *r, const double offset_s[MR_TAKE_CHANNELS], mr_take_error *err);
/* Every chunk time multiplied by factor (> 0), rounded as mr_take_ns does. */
int mr_take_scale_rec(mr_take_rec *r, double factor, mr_take_error *err);

/* --- the take list ("book") ------------------------------------------------- */

typedef enum mr_take_how {
  MR_TAKE_RECORDED = 0,
  MR_TAKE_PUNCHED,
  MR_TAKE_SPLIT,
  MR_TAKE_TRIMMED,
  MR_TAKE_SMOOTHED,
  MR_TAKE_OFFSET,
  MR_TAKE_SCALED,
} mr_take_how;

/* "recorded", "punch", ... as takes.json spells it. */
const char *mr_take_how_name(mr_take_how how);

typedef struct mr_take_arm {
  int glove;  /* 0..MR_TAKE_MAX_GLOVES-1 */
  int finger; /* 0..4: thumb, index, middle, ring, little */
} mr_take_arm;

/* Parses "G:F[,G:F...]" (F a number 0..4 or thumb, index, middle, ring,
 * little). 0 or -1. */
int mr_take_arms_parse(const char *text, mr_take_arm *arms, size_t cap, size_t *n,
                       mr_take_error *err);

typedef struct mr_take_entry {
  char name[MR_TAKE_NAME_MAX];
  int id; /* stable: file names and sources use it, renames do not move it */
  size_t n_files;
  char files[MR_TAKE_MAX_GLOVES][MR_TAKE_NAME_MAX]; /* inside the book's directory */
  mr_take_how how;
  int source_id, over_id; /* 0: none */
  double t0, t1;          /* punch in/out, trim from/to, split at (t0) */
  int part;               /* split: 1 the part before the cut, 2 the part after */
  mr_take_arm arms[MR_TAKE_MAX_ARMS];
  size_t n_arms; /* punch's arm set; smooth's channels */
  double min_cutoff, beta, d_cutoff;
  double offset[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS];
  double factor;
  double duration;
  uint64_t scene_hash;
  int64_t created_unix; /* s */
  bool deleted;         /* hidden from the list; files kept */
} mr_take_entry;

typedef struct mr_take_book {
  char dir[MR_TAKE_PATH_MAX];
  mr_take_entry *takes;
  size_t n;
  int next_id;
} mr_take_book;

/* Opens the book in dir (reading dir/takes.json); with create, makes dir
 * and an empty list when there is none. */
int mr_take_book_open(const char *dir, bool create, mr_take_book *b, mr_take_error *err);
void mr_take_book_close(mr_take_book *b);
/* The entry named name (hidden ones too), or NULL. */
const mr_take_entry *mr_take_book_find(const mr_take_book *b, const char *name);
const mr_take_entry *mr_take_book_find_id(const mr_take_book *b, int id);
/* 0 if name can be a take's name in b (not empty, no '/', not taken). */
int mr_take_book_check_name(const mr_take_book *b, const char *name, mr_take_error *err);
/* The full paths of a take's files (a hidden take resolves too). */
int mr_take_book_paths(const mr_take_book *b, const char *name, char paths[][MR_TAKE_PATH_MAX],
                       size_t cap, size_t *n, mr_take_error *err);

/* Every operation that makes a take takes its name (NULL or "": the first
 * free take-N) and writes the name it used into made (may be NULL). A note
 * (a cut-off input used up to its last whole chunk) goes into note, "" if
 * none (may be NULL). */
typedef struct mr_take_made {
  char name[MR_TAKE_NAME_MAX];
  char name2[MR_TAKE_NAME_MAX]; /* split's second take */
  char note[800];
} mr_take_made;

/* Adds recorded .mrec files (one per glove, in glove order), copied in
 * (move: renamed in when on the same file system, else copied and
 * removed). */
int mr_take_book_add(mr_take_book *b, const char *name, const char *const *paths, size_t n,
                     bool move, mr_take_made *made, mr_take_error *err);

typedef struct mr_take_punch_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_take_punch_def() */
  const char *base, *over, *name;
  mr_take_arm arms[MR_TAKE_MAX_ARMS];
  size_t n_arms;
  double t_in, t_out; /* s of show time; default NaN: must be given */
} mr_take_punch_def;
mr_take_punch_def mr_default_take_punch_def(void);
int mr_take_book_punch(mr_take_book *b, const mr_take_punch_def *d, mr_take_made *made,
                       mr_take_error *err);

/* Two new takes: [0, at) and [at, end), the second's times from 0. */
int mr_take_book_split(mr_take_book *b, const char *source, double at, const char *name1,
                       const char *name2, mr_take_made *made, mr_take_error *err);
int mr_take_book_trim(mr_take_book *b, const char *source, double t0, double t1, const char *name,
                      mr_take_made *made, mr_take_error *err);

typedef struct mr_take_smooth_def {
  uint32_t cookie;                   /* MR_DEF_COOKIE, set by mr_default_take_smooth_def() */
  double min_cutoff, beta, d_cutoff; /* default 1 Hz, 0, 1 Hz */
  mr_take_arm channels[MR_TAKE_MAX_ARMS];
  size_t n_channels; /* 0: every channel (default) */
} mr_take_smooth_def;
mr_take_smooth_def mr_default_take_smooth_def(void);
int mr_take_book_smooth(mr_take_book *b, const char *source, const mr_take_smooth_def *d,
                        const char *name, mr_take_made *made, mr_take_error *err);

/* offset[glove][finger] in s (0 default). */
int mr_take_book_offset(mr_take_book *b, const char *source,
                        const double offset[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS], const char *name,
                        mr_take_made *made, mr_take_error *err);
int mr_take_book_scale(mr_take_book *b, const char *source, double factor, const char *name,
                       mr_take_made *made, mr_take_error *err);

int mr_take_book_delete(mr_take_book *b, const char *name, mr_take_error *err);
int mr_take_book_restore(mr_take_book *b, const char *name, mr_take_error *err);
int mr_take_book_rename(mr_take_book *b, const char *name, const char *new_name,
                        mr_take_error *err);

/* A take argument of run --replay, render --take, export: "DIR:NAME", where
 * DIR holds a takes.json, names the take NAME of that book. 1 with the
 * take's files in paths, 0 when ref is not such a reference (a plain file),
 * -1 on an error (no such take, a broken book). */
int mr_take_resolve(const char *ref, char paths[][MR_TAKE_PATH_MAX], size_t cap, size_t *n,
                    mr_take_error *err);

#ifdef __cplusplus
}
#endif

#endif
