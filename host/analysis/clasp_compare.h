/* How alike the clasp's halves and ropes are (docs/physics.md 6.2): each rope
 * symmetric about its tip, the two ropes congruent. Compared from the tip,
 * where both ropes' pieces start: the ropes' free ends are not, since the
 * clasp can slide between the walls (one rope's legs grow by what the
 * other's lose, the total length unchanged), and their ends' distance from
 * the tip with it. */
#ifndef TR_CLASP_COMPARE_H
#define TR_CLASP_COMPARE_H

#include "analysis/arc_profile.h"
#include "analysis/clasp_anatomy.h"
#include "util/error.h"

typedef struct tr_clasp_match {
    /* the pieces' boundaries (E|S, the ends of S and G, the starts of G and K)
     * as distances from the tip: the largest difference, the boundary it is
     * at, and that boundary's uncertainties combined */
    double boundary_diff, boundary_err;
    const char *boundary;
    /* the curvature at equal distances from the tip, neighbouring arcs
     * averaged in pairs (the period-2 alternation of a tight polygon would
     * otherwise dominate), the second interpolated linearly onto the first,
     * over distances 0 .. span */
    double kappa_max_diff, kappa_max_at, kappa_rms_diff, span;
    double length_diff;      /* of the halves (symmetry) or the ropes (congruence) */
} tr_clasp_match;

/* Half 0 of a rope against its half 1; r found on p. */
int tr_clasp_symmetry(const tr_arc_profile *p, const tr_clasp_rope *r, tr_clasp_match *out, tr_error *err);

/* Rope a against rope b, half by half (each found on its profile). */
int tr_clasp_congruence(const tr_arc_profile *pa, const tr_clasp_rope *a, const tr_arc_profile *pb,
                        const tr_clasp_rope *b, tr_clasp_match *out, tr_error *err);

#endif
