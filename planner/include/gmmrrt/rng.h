/*
 * rng.h - explicit random-number state (like SQLite's random.c): one small struct per
 * planner, seeded from its config, so the same seed gives the same tree. No global state.
 * Generator: xoshiro256** seeded through splitmix64 (Blackman & Vigna).
 */
#ifndef GMMRRT_RNG_H
#define GMMRRT_RNG_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    uint64_t s[4];
    double spare_normal;  /* second value of the last polar Box-Muller pair */
    int has_spare_normal;
} gmmrrt_rng_t;

/* Any seed (0 included) gives a valid, distinct stream. */
void gmmrrt_rng_seed(gmmrrt_rng_t *rng, uint64_t seed);
uint64_t gmmrrt_rng_next_u64(gmmrrt_rng_t *rng);
/* Uniform in [0, 1), 53 random bits. */
double gmmrrt_rng_uniform(gmmrrt_rng_t *rng);
/* Standard normal N(0, 1). */
double gmmrrt_rng_normal(gmmrrt_rng_t *rng);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_RNG_H */
