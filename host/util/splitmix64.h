/* This file contains splitmix64, the seeded random stream of the curve
 * perturbations (curve/perturb.c) and the crankshaft shuffle
 * (tighten/shuffle.c): the same seed gives the same numbers on every
 * machine, where libc's rand() does not. */
#ifndef TR_SPLITMIX64_H
#define TR_SPLITMIX64_H

#include <stdint.h>

/* splitmix64 (Steele, Lea and Flood 2014): the next number of the stream
 * whose state is the caller's, so two users never share one */
static inline uint64_t tr_splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

#endif
