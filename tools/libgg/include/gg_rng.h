/* A small deterministic generator (splitmix64): the same --seed gives the
 * same stream on every machine, which libc's rand() does not promise. */
#ifndef GG_RNG_H
#define GG_RNG_H

#include <stdint.h>

typedef struct gg_rng {
  uint64_t s;
} gg_rng;

static inline void gg_rng_seed(gg_rng *r, uint64_t seed) {
  r->s = seed;
}

static inline uint64_t gg_rng_u64(gg_rng *r) {
  uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static inline double gg_rng_unit(gg_rng *r) {
  return (double)(gg_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform integer in [lo, hi]. */
static inline uint32_t gg_rng_range(gg_rng *r, uint32_t lo, uint32_t hi) {
  return lo + (uint32_t)(gg_rng_u64(r) % ((uint64_t)hi - lo + 1u));
}

#endif
