/* This file declares the seeded smooth perturbation of a start curve, the
 * other roads of tighten --tries. */
#ifndef TR_PERTURB_H
#define TR_PERTURB_H

#include <stdint.h>

#include "curve/curve.h"
#include "util/error.h"

/* Moves every vertex of every closed component by a smooth displacement
 * along the curve: a sum of the first TR_PERTURB_MODES Fourier modes in
 * arclength, each mode's two 3-vectors drawn uniformly from [-1, 1]^3 by a
 * generator seeded with seed and weighted 1/m, the whole scaled so that the
 * largest displacement is amplitude. Smooth, so that the curve stays a
 * rope that scaling makes thick again (a vertex-level noise would bend it
 * at every vertex), and low in frequency, so that it moves the knot's
 * strands against each other, which is what leaves a local minimum. Open
 * components are left alone (their ends sit on constraint planes). The
 * same seed gives the same curve on every machine (splitmix64, no libc
 * random). */
#define TR_PERTURB_MODES 4
int tr_curve_perturb(tr_curve *c, double amplitude, uint64_t seed, tr_error *err);

#endif
