/* tightrope measure --invariants: the knot type of a curve as its Alexander
 * polynomial, determinant and diagram size (topology/alexander.h), so that
 * a tightened curve's type is checked, never assumed (issue 47). */
#ifndef TR_MEASURE_INVARIANTS_H
#define TR_MEASURE_INVARIANTS_H

#include "curve/curve.h"
#include "util/text_file.h"

/* Appends to t the invariants of c (one closed component): the table's
 * line "alexander 1 -1 1  determinant 3  crossings 3\n" (Conway's
 * normalisation, coefficients of t^-h .. t^h; crossings of the diagram
 * after removing kinks), or with json the keys
 * , "alexander": [1, -1, 1], "determinant": 3, "crossings": 3,
 *   "projected_crossings": 3
 * to go inside the file's object. Returns tr_knot_invariants_of's status
 * (TR_EUNSUPPORTED for a link, TR_EINVAL for an open rope, TR_EGEOMETRY
 * for a curve through itself) with its message; nothing is appended then. */
int tr_measure_invariants_append(tr_text *t, const tr_curve *c, int json, tr_error *err);

#endif
