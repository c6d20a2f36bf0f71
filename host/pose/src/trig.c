/* Sine, cosine and arc cosine of the project's own.
 *
 * IEEE 754 makes + − × ÷ and sqrt correctly rounded, so they give the same
 * bits everywhere; it asks no such thing of sin, cos or acos. glibc picks
 * its versions when the program starts (one for FMA and AVX2, one for
 * SSE2) and they differ in the last bit, as other C libraries and other
 * CPUs may. These three reach the state (the §6.2 sine spring, the control
 * frames' slerp, the oscillate track, the scene's Euler angles), so a
 * pinned state hash would hold only on the machine that pinned it. Built
 * from the five exact operations alone, in one fixed order, these give
 * the same bits on every CPU, compiler and C library; they are accurate to
 * about one ulp, which is all the physics asks.
 *
 * The polynomials are the Taylor series, cut where the next term is below
 * 2⁻⁵⁶ of the result over the reduced range; each coefficient is the
 * nearest double to its exact fraction, written in hex so it is exact. */
#include "mr_pose.h"

#include <math.h>

/* (−1)ⁿ/(2n+1)!, n = 1..8: sin r = r + r³ Σ c_n r²⁽ⁿ⁻¹⁾. On |r| ≤ π/4 the
 * first term left out, r¹⁹/19!, is below 2⁻⁶² r. */
static const double sin_c[] = { -0x1.5555555555555p-3,  0x1.1111111111111p-7,
                                -0x1.a01a01a01a01ap-13, 0x1.71de3a556c734p-19,
                                -0x1.ae64567f544e4p-26, 0x1.6124613a86d09p-33,
                                -0x1.ae7f3e733b81fp-41, 0x1.952c77030ad4ap-49 };

/* (−1)ⁿ/(2n)!, n = 1..9: cos r = 1 + r² Σ c_n r²⁽ⁿ⁻¹⁾; r²⁰/20! < 2⁻⁶⁷. */
static const double cos_c[] = { -0x1p-1,
                                0x1.5555555555555p-5,
                                -0x1.6c16c16c16c17p-10,
                                0x1.a01a01a01a01ap-16,
                                -0x1.27e4fb7789f5cp-22,
                                0x1.1eed8eff8d898p-29,
                                -0x1.93974a8c07c9dp-37,
                                0x1.ae7f3e733b81fp-45,
                                -0x1.6827863b97d97p-53 };

/* (2n)!/(4ⁿ (n!)² (2n+1)), n = 1..23: asin y = y + y³ Σ c_n y²⁽ⁿ⁻¹⁾. The
 * terms shrink at least fourfold each on |y| ≤ ½, where everything from
 * y⁴⁹ on sums to less than 2⁻⁵⁶ y. */
static const double asin_c[] = { 0x1.5555555555555p-3, 0x1.3333333333333p-4, 0x1.6db6db6db6db7p-5,
                                 0x1.f1c71c71c71c7p-6, 0x1.6e8ba2e8ba2e9p-6, 0x1.1c4ec4ec4ec4fp-6,
                                 0x1.c99999999999ap-7, 0x1.7a87878787878p-7, 0x1.3fde50d79435ep-7,
                                 0x1.12ef3cf3cf3cfp-7, 0x1.df3bd37a6f4dfp-8, 0x1.a6863d70a3d71p-8,
                                 0x1.782dda12f684cp-8, 0x1.51ba308d3dcb1p-8, 0x1.31683bdef7bdfp-8,
                                 0x1.15ee9d45d1746p-8, 0x1.fcaf8fb6db6dbp-9, 0x1.d3d2a8e0dd67dp-9,
                                 0x1.b026f57b13b14p-9, 0x1.90cb77f60c7cep-9, 0x1.750de64d7d05fp-9,
                                 0x1.5c5f56efaaaabp-9, 0x1.464c0950f7d47p-9 };

#define COUNT(a) (int)(sizeof(a) / sizeof(a)[0])

/* π/2 in four parts (Cody and Waite): the first three carry 30
 * significant bits, so k·p1, k·p2 and k·p3 are exact for every integer
 * k < 2²³, and x − k·p1 is exact (Sterbenz: k·p1 is within a factor 2 of
 * x); the fourth carries the next 53 bits. Their sum is π/2 to 2⁻¹⁴⁷, so
 * even an x within 2⁻⁶⁰ of a multiple of π/2 keeps its r to the last bit. */
static const double pio2_1 = 0x1.921fb548p+0;
static const double pio2_2 = -0x1.de973dc8p-31;
static const double pio2_3 = -0x1.9d9cceb8p-62;
static const double pio2_4 = -0x1.1fc8f8cbb5bf7p-93;
static const double two_over_pi = 0x1.45f306dc9c883p-1;
static const double quarter_pi = 0x1.921fb54442d18p-1;
/* π/2 and π as a double and the rest, for acos's π/2 − asin and π − 2 asin. */
static const double pio2_hi = 0x1.921fb54442d18p+0, pio2_lo = 0x1.1a62633145c07p-54;
static const double pi_hi = 0x1.921fb54442d18p+1, pi_lo = 0x1.1a62633145c07p-53;

/* Σ c_n zⁿ⁻¹ by Horner's rule, highest term first. */
static double series(const double *c, int n, double z) {
  double s = c[n - 1];
  for (int i = n - 2; i >= 0; i--) s = c[i] + z * s;
  return s;
}

/* s + e = a + b exactly, s the rounded sum (Knuth's two-sum). */
static void two_sum(double a, double b, double *s, double *e) {
  *s = a + b;
  double bb = *s - a;
  *e = (a - (*s - bb)) + (b - bb);
}

/* sin(r + lo) for |r| ≤ π/4, lo below half an ulp of r: cos r ≈ 1 there,
 * so lo adds as it is. */
static double sin_poly(double r, double lo) {
  double z = r * r;
  if (z == 0) return r; /* r³ underflows: sin r is r, and −0 stays −0 */
  return r + (r * z * series(sin_c, COUNT(sin_c), z) + lo);
}

/* cos(r + lo) = cos r − lo sin r, with sin r ≈ r at lo's scale. */
static double cos_poly(double r, double lo) {
  double z = r * r;
  return 1.0 + (z * series(cos_c, COUNT(cos_c), z) - r * lo);
}

/* x = k·π/2 + r[0] + r[1] with |r[0]| ≤ π/4 (a hair more where x·2/π
 * rounds up to a half) and r[1] the part of r below r[0]'s last bit, kept
 * so that rounding r does not add an ulp to the result: returns k mod 4,
 * or −1 when x is NaN, infinite or beyond MR_TRIG_MAX_RAD, where k·p1 is
 * no longer exact. */
static int reduce(double x, double r[2]) {
  r[0] = x;
  r[1] = 0;
  if (fabs(x) <= quarter_pi) return 0;
  if (!(fabs(x) <= MR_TRIG_MAX_RAD)) return -1;
  double k = floor(x * two_over_pi + 0.5);
  double t2, e2, t3, e3;
  two_sum(x - k * pio2_1, -(k * pio2_2), &t2, &e2);
  two_sum(t2, -(k * pio2_3), &t3, &e3);
  two_sum(t3, (e2 + e3) - k * pio2_4, &r[0], &r[1]);
  /* Converting to unsigned wraps modulo 2^N, so k mod 4 for either sign. */
  return (int)((unsigned long)(long)k & 3u);
}

/* sin(q·π/2 + r): the quarter turns swap sine and cosine and flip signs. */
static double quarter_turns(int q, const double r[2]) {
  switch (q & 3) {
  case 0:
    return sin_poly(r[0], r[1]);
  case 1:
    return cos_poly(r[0], r[1]);
  case 2:
    return -sin_poly(r[0], r[1]);
  default:
    return -cos_poly(r[0], r[1]);
  }
}

double mr_sin(double x) {
  double r[2];
  int q = reduce(x, r);
  return q < 0 ? NAN : quarter_turns(q, r);
}

/* cos x = sin(x + π/2): one quarter turn more. */
double mr_cos(double x) {
  double r[2];
  int q = reduce(x, r);
  return q < 0 ? NAN : quarter_turns(q + 1, r);
}

/* How many of asin_c a smaller y needs: where z = y² ≤ z_max, the terms
 * after the first `terms` sum to less than 2⁻⁵⁶ y (summed in exact
 * fractions, once). The slerp's nearly equal orientations put most calls
 * at y ≈ 10⁻³, where four terms do the work of twenty-three. */
static const struct {
  double z_max;
  int terms;
} asin_terms[] = { { 0x1p-30, 1 }, { 0x1p-20, 2 }, { 0x1p-16, 3 }, { 0x1p-12, 4 },
                   { 0x1p-10, 5 }, { 0x1p-8, 6 },  { 0x1p-6, 8 },  { 0x1p-4, 12 } };

/* asin y − y, for |y| ≤ ½: the caller adds y last, where it is largest. */
static double asin_rest(double y) {
  double z = y * y;
  int n = COUNT(asin_c);
  for (int i = 0; i < COUNT(asin_terms); i++) {
    if (z <= asin_terms[i].z_max) {
      n = asin_terms[i].terms;
      break;
    }
  }
  return y * z * series(asin_c, n, z);
}

/* Within ½ of 0, acos x = π/2 − asin x. Beyond, the half-angle identity
 * acos x = 2 asin √((1 − x)/2) (x > 0) and π − 2 asin √((1 + x)/2)
 * (x < 0) brings the series' argument back to ≤ ½; 1 − |x| is exact there
 * (Sterbenz), so near ±1, where the turn angles of the slerp live, the
 * only rounding before the series is the correctly rounded square root. */
double mr_acos(double x) {
  if (!(fabs(x) <= 1.0)) return NAN;
  if (fabs(x) <= 0.5) return pio2_hi - (x - (pio2_lo - asin_rest(x)));
  double s = sqrt((1.0 - fabs(x)) * 0.5);
  double half = s + asin_rest(s);
  return x > 0 ? 2.0 * half : pi_hi - (2.0 * half - pi_lo);
}
