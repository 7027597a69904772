/*
 * rng.c - explicit random-number state (rng.h): xoshiro256** 1.0 by Blackman & Vigna
 * (https://prng.di.unimi.it/), seeded through splitmix64 so any 64-bit seed, 0 included,
 * gives a non-zero state. Uniforms take the top 53 bits; normals use the polar
 * (Marsaglia) Box-Muller method and keep the second value of each pair.
 * Used by the mixture sampler (paper Sect. 4) and the RRT* sampler; no global state.
 */
#include "gmmrrt/rng.h"

#include <math.h>

static uint64_t rotl(uint64_t x, int k)
{
    return (x << k) | (x >> (64 - k));
}

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void gmmrrt_rng_seed(gmmrrt_rng_t *rng, uint64_t seed)
{
    uint64_t x = seed;
    for (int i = 0; i < 4; ++i)
        rng->s[i] = splitmix64(&x);
    rng->spare_normal = 0.0;
    rng->has_spare_normal = 0;
}

uint64_t gmmrrt_rng_next_u64(gmmrrt_rng_t *rng)
{
    uint64_t *s = rng->s;
    const uint64_t result = rotl(s[1] * 5u, 7) * 9u;
    const uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double gmmrrt_rng_uniform(gmmrrt_rng_t *rng)
{
    return (double)(gmmrrt_rng_next_u64(rng) >> 11) * 0x1.0p-53;
}

double gmmrrt_rng_normal(gmmrrt_rng_t *rng)
{
    if (rng->has_spare_normal) {
        rng->has_spare_normal = 0;
        return rng->spare_normal;
    }
    double u, v, s;
    do {
        u = 2.0 * gmmrrt_rng_uniform(rng) - 1.0;
        v = 2.0 * gmmrrt_rng_uniform(rng) - 1.0;
        s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double m = sqrt(-2.0 * log(s) / s);
    rng->spare_normal = v * m;
    rng->has_spare_normal = 1;
    return u * m;
}
