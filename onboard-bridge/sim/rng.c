#include "rng.h"

#include <math.h>

static void build_gauss_table(void);

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void rng_seed(sim_rng_t *r, uint64_t seed)
{
    build_gauss_table();   /* once per process, outside any timed loop */
    for (int i = 0; i < 4; i++)
        r->s[i] = splitmix64(&seed);
}

static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t rng_next(sim_rng_t *r)
{
    uint64_t *s = r->s;
    uint64_t result = rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double rng_uniform(sim_rng_t *r) { return (double)(rng_next(r) >> 11) * 0x1.0p-53; }

double rng_gauss(sim_rng_t *r)
{
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    if (u1 < 1e-300)
        u1 = 1e-300;
    return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

#define GAUSS_TABLE 4096
static double gauss_table[GAUSS_TABLE];
static int gauss_table_ready;

static void build_gauss_table(void)
{
    if (!gauss_table_ready) {
        /* Inverse CDF at the cell midpoints: a fixed table, independent of any seed. */
        for (int i = 0; i < GAUSS_TABLE; i++) {
            double p = (i + 0.5) / GAUSS_TABLE, lo = -9.0, hi = 9.0;
            for (int it = 0; it < 60; it++) {
                double mid = 0.5 * (lo + hi);
                if (0.5 * erfc(-mid / M_SQRT2) < p)
                    lo = mid;
                else
                    hi = mid;
            }
            gauss_table[i] = 0.5 * (lo + hi);
        }
        gauss_table_ready = 1;
    }
}

double rng_gauss_fast(sim_rng_t *r)
{
    return gauss_table[rng_next(r) >> (64 - 12)];
}
