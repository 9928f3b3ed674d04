/*
 * Seeded pseudo-random numbers for the simulator: xoshiro256** (Blackman & Vigna),
 * seeded through splitmix64, so every run with the same seed is identical.
 */
#ifndef SIM_RNG_H
#define SIM_RNG_H

#include <stdint.h>

typedef struct {
    uint64_t s[4];
} sim_rng_t;

void rng_seed(sim_rng_t *r, uint64_t seed);
uint64_t rng_next(sim_rng_t *r);
double rng_uniform(sim_rng_t *r);          /* [0, 1) */
double rng_gauss(sim_rng_t *r);            /* N(0, 1), Box-Muller */
/* N(0, 1) from a 4096-entry table: for per-step noise (ADC) where Box-Muller would
 * cost more than the control step it perturbs. */
double rng_gauss_fast(sim_rng_t *r);

#endif
