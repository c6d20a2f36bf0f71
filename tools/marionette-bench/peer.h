/* Item 2: the stick marionette described once, as our scene and as a
 * MuJoCo model (peer_model.c), and the side-by-side runs (peer.c). */
#ifndef MARIONETTE_BENCH_PEER_H
#define MARIONETTE_BENCH_PEER_H

#include <stddef.h>

/* The bar's track: an oscillation with a roll, ramped in over `ramp` s. */
typedef struct peer_track {
  double amplitude[3], roll_deg, frequency, ramp;
} peer_track;

/* MuJoCo's settings: step, integrator, and the tendon limits' time
 * constant (solreflimit; MuJoCo needs it at least twice the step). */
typedef struct peer_mj_setting {
  double dt, timeconst;
  int rk4;
  int hard; /* solimplimit 0.99 0.999 (default 0.9 0.95): a stiffer limit */
} peer_mj_setting;

/* Our scene (YAML) and MuJoCo's model (MJCF) from the one description;
 * malloc'd text. */
char *peer_scene(const peer_track *tr, size_t *len);
char *peer_mjcf(const peer_mj_setting *s);
int peer_effector(void);       /* the end effector's particle (hand_l) */
double peer_limb_length(void); /* an upper arm, m */
int peer_string_count(void);
/* Every point mass, each named p_<name> as a MuJoCo site. */
int peer_point_count(void);
const char *peer_point_name(int i);
/* Viscous drag on every point mass, N·s/m (hard case 01's). */
#define PEER_DRAG 0.2

#endif
