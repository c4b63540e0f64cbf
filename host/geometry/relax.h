/* The relaxation of a loose start, as KnotPlot relaxes its knots: every
 * vertex pushes every other (but its neighbours) away with a force of
 * 1/r^5 (the gradient of a 1/r^4 energy), springs keep the edges at their
 * component's mean length. The closest two edges that share no vertex are
 * measured every TR_RELAX_STEPS_BETWEEN steps, and no vertex moves more
 * than a tenth of their distance a step: between two measures two strands
 * close by at most 0.8 of it, so no strand passes through another, and the
 * knot (the link, its components' knots and linking) is the one given.
 *
 * Why: a braid closure (curve/braid_closure.h) is a rope wound round a
 * cylinder, 2.8 to 5 times its tight length at thickness 1.25 for the
 * nine-crossing knots, and the tightening from it ends in basins 0.5 to
 * 4 % above KnotInfo's ropelengths; relaxed, its thickness per length is
 * 1.3 to 2.5 times larger (bench/notes/2026-11-30-relaxed-starts.md). */
#ifndef TR_RELAX_H
#define TR_RELAX_H

#include <stddef.h>

#include "curve/curve.h"
#include "util/error.h"

/* the steps between two measures of the closest non-adjacent edges */
#define TR_RELAX_STEPS_BETWEEN 4

/* Relaxes c in place for the given number of steps. Every component closed,
 * at least 4 vertices each. TR_EINVAL otherwise, TR_ENOMEM. */
int tr_curve_relax(tr_curve *c, int steps, tr_error *err);

#endif
