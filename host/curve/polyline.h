/* Arclength bookkeeping on one closed polygon: cumulative lengths and the
 * point at any arclength (periodic). The analysis of a knot's shape works in
 * the arclength coordinate of the input polygon, so every other piece
 * (averaging, symmetry, contacts) shares these helpers. (The resamplers that
 * make new curves are tr_resample and tr_resample_smooth, curve/generate.h,
 * and the refinement's tr_refine_lowpass, engine/refine_lowpass.h.) */
#ifndef TR_POLYLINE_H
#define TR_POLYLINE_H

#include <math.h>
#include <stddef.h>

#include "util/error.h"

/* s[0..n]: s[i] = arclength of vertex i from vertex 0, s[n] = L (closing edge
 * included). Compensated summation. */
void tr_polyline_arclength(const double *x, size_t n, double *s);

/* Point at arclength l (any real; taken modulo L = s[n]) by linear
 * interpolation along the edge that holds it. */
void tr_polyline_point_at(const double *x, size_t n, const double *s, double l, double *p);

/* l modulo L into [0, L). */
static inline double tr_wrap(double l, double L)
{
    double r = fmod(l, L);
    if (r < 0)
        r += L;
    return r >= L ? 0.0 : r;
}

/* Signed periodic difference a - b into [-L/2, L/2). */
static inline double tr_wrap_signed(double d, double L)
{
    double r = tr_wrap(d + 0.5 * L, L) - 0.5 * L;
    return r;
}

#endif
