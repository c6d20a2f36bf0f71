/* The start configuration a diverged world starts again from (§7).
 *
 * §7 returns the puppet to its start configuration. A puppet hangs from
 * its control frame, and the frame is wherever the hand has taken it by
 * then: put back where it started, the puppet would hang metres from the
 * bar on strings stretched to several times their length, a deviation
 * past the divergence bound before any step, and the world would reset
 * again at every step from then on (four puppets whose frames had jumped
 * 2 m: 18 280 resets in 4 s, the strings 9.9× their rest). So a puppet
 * that hangs from one frame alone starts again in its start configuration
 * as that frame carries it: moved and turned as the frame has been since
 * it was made, at the frame's velocity there,
 *
 *   x = p + R r,   r = R_home⁻¹ (x_start − p_home),   v = ṗ + ω × R r + R v_start',
 *
 * with R the frame's orientation now and v_start' = R_home⁻¹ v_start, so
 * its strings and links have their start lengths and lengthen at no rate.
 * A frame lowered since may have taken it into the floor: it is lifted
 * out along the plane's normal, its strings then slack, as a puppet set
 * down under a low bar stands. A puppet held to the world (a pin or a
 * curve), hung from several frames or from none starts again where it
 * started, as §7 says. */
#include "internal.h"

#include <string.h>

enum { CARRIER_NONE = -2, CARRIER_SEVERAL = -1 };

/* Puppet p hangs from frame f (one more string or link to it). */
static void hangs_from(int *carrier, int p, int f) {
  if (carrier[p] == CARRIER_NONE)
    carrier[p] = f;
  else if (carrier[p] != f)
    carrier[p] = CARRIER_SEVERAL;
}

/* Each puppet's carrier: the frame its strings, and links to a frame's
 * particles, all come from, or −1. Needs w->npuppets. */
int mr_restart_carriers(mr_world *w) {
  int cap = w->cap_carrier;
  if (mr_grow((void **)&w->carrier, &cap, w->npuppets > 0 ? w->npuppets : 1, sizeof(int)) != 0)
    return -1;
  w->cap_carrier = cap;
  int *carrier = w->carrier;
  for (int p = 0; p < w->npuppets; p++) carrier[p] = CARRIER_NONE;
  const mr_list *strings = MR_FORCES(w, STRINGS);
  for (int i = 0; i < strings->n; i++) {
    const mr_string *s = &MR_AT(*strings, mr_string, i);
    const int f = w->frame[s->frame_particle], pp = s->puppet_particle;
    if (f >= 0 && w->frame[pp] < 0) hangs_from(carrier, w->puppet[pp], f);
  }
  for (int i = 0; i < w->distances.n; i++) {
    const mr_distance *d = &MR_AT(w->distances, mr_distance, i);
    const int fa = w->frame[d->a], fb = w->frame[d->b];
    if (fa >= 0 && fb < 0) hangs_from(carrier, w->puppet[d->b], fa);
    if (fb >= 0 && fa < 0) hangs_from(carrier, w->puppet[d->a], fb);
  }
  for (int i = 0; i < w->pins.n; i++)
    carrier[w->puppet[MR_AT(w->pins, mr_pin, i).particle]] = CARRIER_SEVERAL;
  for (int i = 0; i < w->curves.n; i++)
    carrier[w->puppet[MR_AT(w->curves, mr_curve, i).particle]] = CARRIER_SEVERAL;
  for (int p = 0; p < w->npuppets; p++)
    if (carrier[p] == CARRIER_NONE) carrier[p] = CARRIER_SEVERAL;
  return 0;
}

/* Particle i's start state carried by frame fr, whose pose, velocity and
 * angular velocity at the world's time are now, vel, om. */
static void carried(mr_world *w, int i, const mr_frame *fr, const mr_pose *now, const double vel[3],
                    const double om[3]) {
  const double *home = fr->home.position, *hq = fr->home.orientation;
  const double d[3] = { w->x_start[3 * i] - home[0], w->x_start[3 * i + 1] - home[1],
                        w->x_start[3 * i + 2] - home[2] };
  double local[3], r[3], spin[3], vl[3], vs[3];
  mr_pose_unrotate(hq, d, local);
  mr_pose_rotate(now->orientation, local, r);
  mr_cross3(om, r, spin);
  mr_pose_unrotate(hq, &w->v_start[3 * i], vl);
  mr_pose_rotate(now->orientation, vl, vs);
  for (int k = 0; k < 3; k++) {
    w->x[3 * i + k] = now->position[k] + r[k];
    w->v[3 * i + k] = vel[k] + spin[k] + vs[k];
  }
}

/* Carried puppet p, where a particle of it is inside a plane: moved out
 * along that plane's normal by the deepest depth; again for the next
 * plane it is in, a few times at most (a corner). */
static void lift_out(mr_world *w, int p) {
  if (!(w->def.effects & MR_EFFECT_PLANES)) return;
  for (int round = 0; round < 4; round++) {
    double deepest = 0.0;
    const mr_plane *out = NULL;
    for (int j = 0; j < w->planes.n; j++)
      for (int i = 0; i < w->n; i++) {
        if (w->frame[i] >= 0 || w->puppet[i] != p || !(w->inv_mass[i] > 0)) continue;
        const mr_contact c = { MR_CONTACT_PLANE, i, j, 0.0, 0.0 };
        const double d = -mr_contact_gap(w, &c, w->x);
        if (d > deepest) {
          deepest = d;
          out = &MR_AT(w->planes, mr_plane, j);
        }
      }
    if (!out) return;
    for (int i = 0; i < w->n; i++)
      if (w->frame[i] < 0 && w->puppet[i] == p)
        for (int k = 0; k < 3; k++) w->x[3 * i + k] += deepest * out->n[k];
  }
}

void mr_restart_place(mr_world *w) {
  for (int i = 0; i < w->n; i++) {
    if (w->frame[i] >= 0) continue;
    const int p = w->puppet[i], f = p < w->npuppets ? w->carrier[p] : CARRIER_SEVERAL;
    if (f < 0) {
      memcpy(&w->x[3 * i], &w->x_start[3 * i], 3 * sizeof(double));
      memcpy(&w->v[3 * i], &w->v_start[3 * i], 3 * sizeof(double));
      continue;
    }
    const mr_frame *fr = &MR_AT(w->frames, mr_frame, f);
    mr_pose now;
    double vel[3], om[3];
    mr_frame_eval(fr, w->t, &now, vel, om);
    carried(w, i, fr, &now, vel, om);
  }
  for (int p = 0; p < w->npuppets; p++)
    if (w->carrier[p] >= 0) lift_out(w, p);
}
