/* Rotational symmetry of a closed knot (docs/physics.md 4): the threefold axis
 * (a rotation taking l to l + L/3), the twofold axes (rotations by pi that
 * reverse the direction of travel, l -> 2 l* - l, where l* is a point where
 * the axis meets the curve), a verdict, the paper's arclength origin and the
 * map of any l onto the representative interval [0, L/6).
 *
 * Residuals are RMS distances (length units) between the rotated curve and
 * the curve, over equal-arclength samples; an element counts as present when
 * its residual is below tol times the radius of gyration (default tol 1e-3:
 * a tight trefoil with N = 400 vertices sits near 1e-4 to 1e-3 from its
 * discretisation alone, a random perturbation of 1% of the size well above). */
#ifndef TR_SYMMETRY_H
#define TR_SYMMETRY_H

#include <stddef.h>

#include "analysis/arc_profile.h"
#include "util/error.h"
#include "analysis/rotation_fit.h"

typedef enum tr_symmetry_kind {
    TR_SYM_NONE = 0,
    TR_SYM_C2 = 1, /* at least one twofold axis, no threefold one */
    TR_SYM_C3 = 2, /* a threefold axis, no twofold axis perpendicular to it */
    TR_SYM_D3 = 3  /* threefold axis and twofold axes perpendicular to it */
} tr_symmetry_kind;

const char *tr_symmetry_name(tr_symmetry_kind k);

typedef struct tr_symmetry_opts {
    double tol;      /* relative residual threshold; <= 0: 1e-3 */
    size_t samples;  /* equal-arclength samples for the fits; 0: max(600, nearest multiple of 6 >= n) up to 3000 */
} tr_symmetry_opts;

#define TR_MAX_TWOFOLD 12

typedef struct tr_twofold {
    double l;        /* input arclength of the point where the axis meets the curve */
    double axis[3];  /* unit, from the centroid towards that point */
    double angle;    /* fitted rotation angle (pi for a true twofold axis) */
    double rms;      /* residual, length units */
} tr_twofold;

typedef struct tr_symmetry {
    double L;
    double centroid[3];
    double rg;             /* radius of gyration about the centroid */
    double tol;            /* the relative threshold used */
    tr_rotation c3;        /* best rotation for l -> l + L/3 (axis oriented so the angle is +) */
    int has_c3;
    size_t n_twofold;      /* accepted twofold points, sorted by l */
    tr_twofold twofold[TR_MAX_TWOFOLD];
    double twofold_rms_max;    /* worst accepted twofold residual (0 if none) */
    double twofold_rms_best;   /* best twofold residual seen, accepted or not (INFINITY if no candidate) */
    tr_symmetry_kind verdict;
    double origin;         /* input arclength of the chosen origin; NAN until chosen */
} tr_symmetry;

/* x: closed polygon of n vertices (one component). */
int tr_symmetry_find(const double *x, size_t n, const tr_symmetry_opts *opts, tr_symmetry *out,
                     tr_error *err);

/* The paper's origin: among the twofold points, the one where the curvature
 * is highest in a window of +-L/60 (for the tight trefoil: the curvature
 * minimum flanked by the two kappa = 1 plateaus at |l| ~ 0.16..0.32, not the
 * straighter passage between them); ties go to the smallest l. Without
 * twofold points the origin is vertex 0 (l = 0). */
void tr_symmetry_choose_origin(tr_symmetry *s, const tr_arc_profile *p);

/* l (input arclength) -> distance from the origin along the curve, in [0, L). */
double tr_symmetry_from_origin(const tr_symmetry *s, double l);

/* Representative position in [0, L/6) of l measured from the origin
 * (docs/physics.md 4.4); *sector receives k = 0..5 (may be NULL). */
double tr_symmetry_reduce(double l_from_origin, double L, int *sector);

#endif
