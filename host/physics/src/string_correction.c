/* String-length correction (§6.2, after [19]): springs stretch under the
 * puppet's weight and under fast pulls, which shows as rubbery strings. After
 * each step, every string longer than (1 + max_stretch)·rest is shortened by
 * moving its puppet end back towards the frame, and the part of the puppet
 * end's velocity that lengthens the string is removed (the same principle
 * applied to the damper). Strings sharing a particle disturb each other, so
 * the sweep repeats until none is over length or the iteration budget is
 * spent. The constraint correction of eq. 8 then settles the joints. */
#include "internal.h"

#include <math.h>

void mr_strings_correct(mr_world *w)
{
  w->pass_calls[MR_PASS_STRING_CORRECTION]++;
  const double limit = 1.0 + w->def.string_max_stretch;
  for (int it = 0; it < w->def.string_correction_iterations; it++) {
    int moved = 0;
    for (int i = 0; i < w->nstr; i++) {
      const mr_string *s = &w->strings[i];
      double *xp = &w->x[3 * s->puppet_particle], *vp = &w->v[3 * s->puppet_particle];
      const double *xf = &w->x[3 * s->frame_particle], *vf = &w->v[3 * s->frame_particle];
      double d[3] = {xp[0] - xf[0], xp[1] - xf[1], xp[2] - xf[2]};
      double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      double max = s->rest * limit;
      if (!(len > max) || !(len > 0))
        continue;
      double u[3] = {d[0] / len, d[1] / len, d[2] / len};
      double rate = 0;
      for (int k = 0; k < 3; k++) {
        xp[k] = xf[k] + u[k] * max;
        rate += (vp[k] - vf[k]) * u[k];
      }
      if (rate > 0)
        for (int k = 0; k < 3; k++)
          vp[k] -= rate * u[k];
      moved = 1;
    }
    if (!moved)
      break;
  }
}
