/* A tolerance assertion with the numbers in its message (the packaged
 * cmocka predates assert_double_equal). Include after <cmocka.h>. */
#ifndef SOLVER_ASSERT_H
#define SOLVER_ASSERT_H

#include <math.h>

#define assert_near(a, b, tol)                                                     \
  do {                                                                             \
    double a_ = (a), b_ = (b);                                                     \
    if (!(fabs(a_ - b_) <= (tol)))                                                 \
      fail_msg("%s = %.17g, expected %.17g within %g", #a, a_, b_, (double)(tol)); \
  } while (0)

#endif
