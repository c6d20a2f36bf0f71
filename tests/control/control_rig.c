/* What the control tests share (control_rig.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "control_rig.h"

mr_control *make(const mr_mapping_def *defs, int n) {
  mr_control *c = NULL;
  char msg[160];
  if (mr_control_create(defs, n, &c, msg, sizeof msg) != MR_CONTROL_OK) fail_msg("%s", msg);
  return c;
}

mr_pose hold(mr_control *c, const double v[5], double *t, double secs, mr_channel_state st[5]) {
  mr_pose p = mr_pose_identity();
  for (int i = 0; i < (int)(secs * 100 + 0.5); i++) {
    *t += 0.01;
    assert_int_equal(mr_control_update(c, v, *t, &p, st), MR_CONTROL_OK);
  }
  return p;
}

void assert_pose(const mr_pose *p, const double pos[3], const double deg[3], double tol) {
  mr_pose want = mr_pose_from_euler_deg(pos, deg);
  for (int k = 0; k < 3; k++)
    if (!(fabs(p->position[k] - want.position[k]) < tol))
      fail_msg("position[%d] %.9f, expected %.9f", k, p->position[k], want.position[k]);
  double axis[3];
  double angle = mr_pose_turn(p->orientation, want.orientation, axis);
  if (!(angle < tol)) fail_msg("orientation off by %.3g rad", angle);
}

mr_mapping_def height_only(double low, double high, double neutral, double dead_zone) {
  mr_mapping_def d = mr_default_mapping_def();
  for (int a = 0; a < MR_DOF_COUNT; a++) d.axes[a].channel = -1;
  d.axes[MR_DOF_MOVE_Y] = (mr_axis_def){ 3, low, high, false, neutral, dead_zone };
  return d;
}
