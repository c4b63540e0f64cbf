/* The closure of a braid as a smooth space curve: the start of a knot or
 * link given by name or by a braid word (issue 47).
 *
 * The strands run counterclockwise (seen from +z) around the z axis at
 * radii R0, R0 + 1, ..., R0 + s - 1 (position p at radius R0 + p) in the
 * plane z = 0. The word's letters take equal slots of angle 2 pi / L one
 * after another; in the slot of sigma_i (+-i) the strands at positions
 * i-1 and i exchange radii along (1 - cos pi u) / 2 (u from 0 to 1 across
 * the slot), the one moving outwards lifted to z = +H sin^2 pi u and the
 * other lowered to -H sin^2 pi u for +i, the other way round for -i, so that
 * seen from +z sigma_i is a right-handed (positive) crossing. Every other
 * strand keeps its radius and z = 0. Radius, height and slot change with
 * zero slope at the slot ends, so the curve is C^1 and its curvature is
 * bounded. After the last slot position p has moved to perm(p); a
 * component is a cycle of the permutation, traced through as many turns
 * as it has strands. R0 = max(1.2, 2 L / (2 pi)) keeps a slot >= 2 long
 * at the innermost strand, H = 0.5: the two strands of a crossing are 1
 * apart there, as neighbouring strands are; the curve is then thick
 * (about 0.3 at unit strand spacing) and scales to any rope. */
#ifndef TR_BRAID_CLOSURE_H
#define TR_BRAID_CLOSURE_H

#include "curve/curve.h"

/* The closure of word[0..len-1] on `strands` strands (2 <= strands <= 64,
 * 1 <= |word[k]| <= strands - 1), as a closed polygon per component with
 * `samples` vertices per slot and strand (not equilateral: tr_resample
 * makes it so), components ordered by their smallest starting position.
 * TR_EINVAL for a bad word. */
int tr_make_braid_closure(tr_curve *out, int strands, const int *word, int len, int samples, tr_error *err);

#endif
