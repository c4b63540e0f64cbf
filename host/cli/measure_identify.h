/* tightrope measure FILE --identify [NAME]: the knot or link type of a curve
 * against the embedded tables (issue 47: checked, never assumed). */
#ifndef TR_MEASURE_IDENTIFY_H
#define TR_MEASURE_IDENTIFY_H

#include "curve/curve.h"

/* Computes c's invariants (tighten/knot_start.h tr_type_check_of) and prints to
 * stdout, for NAME, whether they are NAME's, and in every case the table's
 * knots or links with the same invariants (candidates: the invariants do
 * not tell every two knots apart, nor a knot from its mirror image).
 * Returns the exit status: 0 a match (with NAME) or at least one
 * candidate (without), 1 none; 2 an unknown NAME (the nearest suggested)
 * or a curve whose type cannot be computed (an open rope, a curve through
 * itself), with its one line on stderr. */
int tr_measure_identify(const char *file, const tr_curve *c, const char *name);

#endif
