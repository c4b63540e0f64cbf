/* Low-pass resampling for refinement: a coarse optimum carries vertex-level
 * curvature noise that plain resampling would hand to the finer level
 * (MinRad far below 1); a Fourier low-pass in arclength removes it. */
#ifndef TR_REFINE_LOWPASS_H
#define TR_REFINE_LOWPASS_H

#include "curve/curve.h"

/* Resamples every component of in to n vertices at equal arclength.
 * Closed components: the coordinates, sampled at equal arclength, are
 * Fourier-transformed, modes above cut * (n_old / 2) are removed with a
 * raised-cosine taper starting at taper_from * cut * (n_old/2), and the
 * series is evaluated at the n new points. Open components: equal
 * arclength along arcs inscribed at the vertices (refine_arcs.h: no new
 * vertex more curved than the old ones beside it), end vertices (and their
 * constraints) kept. Constraints on other vertices are dropped. */
int tr_refine_lowpass(const tr_curve *in, size_t n, double cut, double taper_from, tr_curve *out,
                       tr_error *err);

#endif
