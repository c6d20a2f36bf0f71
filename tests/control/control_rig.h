/* What the control tests share (control_rig.c). */
#ifndef TEST_CONTROL_RIG_H
#define TEST_CONTROL_RIG_H

#include "mr_control.h"

/* A controller over defs; fails the test, naming the field, if refused. */
mr_control *make(const mr_mapping_def *defs, int n);

/* Holds the five values for `secs` at 100 Hz from t; returns the last pose. */
mr_pose hold(mr_control *c, const double v[5], double *t, double secs, mr_channel_state st[5]);

/* p must be the pose at pos (m) turned by deg (degrees, a scene's Euler
 * angles), within tol (metres and radians). */
void assert_pose(const mr_pose *p, const double pos[3], const double deg[3], double tol);

/* A mapping that drives only move_y, from channel 3, over the range
 * [low, high] about `neutral` with `dead_zone`: the frame's height is the
 * axis's value, so a test reads the axis straight off the pose. */
mr_mapping_def height_only(double low, double high, double neutral, double dead_zone);

#endif
