/* mr_control: five values become the control frame (§3.2, §6.2).
 *
 * A glove gives five calibrated values in 0..1, one per finger string. A
 * mapping turns each into one degree of freedom of the control frame: a
 * turn about x, y or z, or a move along x, y or z, around a neutral pose.
 * The paper drives the three rotation axes, the vertical axis and
 * forward/backward with its five fingers; mr_default_mapping_def() does
 * the same. Each channel is smoothed by a One Euro filter (Casiez, Roussel
 * and Vogel, CHI 2012), and a channel that is not finite, or stuck at 0 or
 * at 1 for longer than a set time, is flagged and held at its neutral
 * value, so a broken string cannot throw the puppet.
 *
 * Manners: definition structs from default makers; mr_control_verb names;
 * the library never prints, never aborts and never reads a clock.
 */
#ifndef MR_CONTROL_H
#define MR_CONTROL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"
#include "mr_pose.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { MR_CONTROL_CHANNELS = 5, MR_CONTROL_MAX_MAPPINGS = 8 };

/* The frame's degrees of freedom, in its own axes around the neutral pose:
 * turns in degrees, moves in metres. y is up, the puppet faces +z. */
typedef enum mr_dof {
  MR_DOF_TURN_X, /* pitch: nod forward and back */
  MR_DOF_TURN_Y, /* yaw: turn left and right */
  MR_DOF_TURN_Z, /* roll: tilt sideways */
  MR_DOF_MOVE_X, /* sideways */
  MR_DOF_MOVE_Y, /* up and down */
  MR_DOF_MOVE_Z, /* forward and back */
  MR_DOF_COUNT
} mr_dof;

const char *mr_dof_name(mr_dof d); /* "turn_x", ...; "unknown" out of range */
int mr_dof_parse(const char *name, mr_dof *out);

/* One degree of freedom driven by one channel. The input u in 0..1 (after
 * smoothing) maps linearly to the range: from `low` at u = 0 to `high` at
 * u = 1 (swapped with invert). Within dead_zone of `neutral` (input units)
 * the input reads as `neutral` exactly, so a relaxed hand holds still. */
typedef struct mr_axis_def {
  int channel;      /* 0..4, or −1: this degree of freedom is not driven */
  double low, high; /* degrees or metres at u = 0 and u = 1 */
  bool invert;
  double neutral;   /* the input of the relaxed hand, 0..1; default 0.5 */
  double dead_zone; /* 0..0.5, input units; default 0.02 */
} mr_axis_def;

typedef struct mr_mapping_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_mapping_def() */
  char name[32];   /* e.g. "walk", "head-only" */
  mr_pose neutral; /* the frame's pose when every driven axis reads 0 */
  mr_axis_def axes[MR_DOF_COUNT];
  /* One Euro filter, per channel: the cutoff at rest (Hz) and how fast it
   * opens with speed (s/unit); the derivative's own cutoff (Hz). */
  double min_cutoff, beta, d_cutoff;
  /* A channel at 0 or 1 for longer than this (s) is taken as broken. */
  double stuck_after;
} mr_mapping_def;

/* The paper's five degrees of freedom: thumb → turn about z (±30°), index
 * → turn about x (±30°), middle → turn about y (±45°), ring → up and down
 * (±0.15 m), little → forward and back (±0.2 m); sideways not driven
 * (±0.15 m if a mapping drives it); neutral 0.5, dead zone
 * 0.02; One Euro min_cutoff 1 Hz, beta 0.7, d_cutoff 1 Hz; stuck after
 * 2 s. The neutral pose is the identity: a scene places it. */
mr_mapping_def mr_default_mapping_def(void);

/* What happened to each channel in the latest update. */
typedef enum mr_channel_state {
  MR_CHANNEL_OK = 0,
  MR_CHANNEL_NOT_FINITE, /* NaN or Inf: held at neutral */
  MR_CHANNEL_STUCK       /* at 0 or 1 past stuck_after: held at neutral */
} mr_channel_state;
const char *mr_channel_state_name(mr_channel_state s);

typedef enum mr_control_status {
  MR_CONTROL_OK = 0,
  MR_CONTROL_ERR_ARG = -1, /* a NULL, a def not made by its maker, a bad field */
  MR_CONTROL_ERR_TIME = -2 /* time went backwards or is not finite */
} mr_control_status;

typedef struct mr_control mr_control;

/* A controller over n mappings (1..MR_CONTROL_MAX_MAPPINGS), the first
 * selected. On a bad field *out is NULL and msg (if given) names it. */
mr_control_status mr_control_create(const mr_mapping_def *defs, int n, mr_control **out, char *msg,
                                    size_t msg_size);
void mr_control_destroy(mr_control *c);

/* Switches to mapping i (or the one named), keeping the filters' state so
 * the frame does not jump; the pose moves to the new mapping's reading of
 * the same inputs. */
mr_control_status mr_control_select(mr_control *c, int i);
int mr_control_find(const mr_control *c, const char *name); /* index or −1 */
int mr_control_selected(const mr_control *c);

/* Feeds the five values read at time t (s, non-decreasing) and writes the
 * frame's pose. Values outside 0..1 are clamped; a value that is not
 * finite, or one stuck at an end, is held at its axis's neutral (states,
 * if not NULL, says which). */
mr_control_status mr_control_update(mr_control *c, const double values[MR_CONTROL_CHANNELS],
                                    double t, mr_pose *out,
                                    mr_channel_state states[MR_CONTROL_CHANNELS]);

/* The smoothed value of each channel after the latest update, 0..1. */
void mr_control_values(const mr_control *c, double out[MR_CONTROL_CHANNELS]);

/* One Euro filter on its own, for anything else that needs it. */
typedef struct mr_one_euro {
  double min_cutoff, beta, d_cutoff;
  double x, dx, t; /* state: last output, its rate, its time */
  bool started;
} mr_one_euro;
void mr_one_euro_init(mr_one_euro *f, double min_cutoff, double beta, double d_cutoff);
/* The filtered value of sample x at time t (> the last t, or the first). */
double mr_one_euro_filter(mr_one_euro *f, double x, double t);

#ifdef __cplusplus
}
#endif

#endif /* MR_CONTROL_H */
