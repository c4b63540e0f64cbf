/* tightrope make knot / make link: starts from a name, a braid word or a
 * PD code, their type checked before anything is written (issue 47). */
#ifndef TR_CLI_MAKE_KNOT_H
#define TR_CLI_MAKE_KNOT_H

#include <stddef.h>

#include "curve/curve.h"
#include "util/error.h"

/* A start that tighten would refuse is not written by any make: the
 * engine's own checks (edges short enough, no overlap, MinRad) on the
 * reference. Returns the engine's error (TR_OK: tighten accepts c). */
int tr_make_start_check(const tr_curve *c, tr_error *err);

/* What make was asked: exactly one of name, braid, pd (pd: knots only);
 * n = 0 for the default vertex count. Prints its line or its error and
 * returns make's exit status: 0 written; 2 bad notation, an unknown name
 * (the nearest names suggested), an unusable --n or output; 1 a made curve
 * whose type is not the one asked for (nothing written), out of memory. */
int tr_make_knot_command(int is_link, const char *name, const char *braid, const char *pd, size_t n,
                         int as_drawn, const char *outpath, const char *version);

#endif
