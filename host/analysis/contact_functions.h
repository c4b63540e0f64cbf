/* Contacts of a tight knot and the contact functions (docs/physics.md 5):
 * every strut joins two points of the rope at arclengths (l_i, l_j); read as
 * a relation on the circle of length L, the struts trace two monotone
 * functions sigma-(l) and sigma+(l), the two partners of the point at l. */
#ifndef TR_CONTACT_FUNCTIONS_H
#define TR_CONTACT_FUNCTIONS_H

#include <stddef.h>

#include "util/error.h"
#include "oracle/thickness.h"

typedef struct tr_contact_pair {
    double li, lj;  /* arclengths of the two ends on the input polygon */
    double dist;
} tr_contact_pair;

/* Struts of the oracle whose both edges lie in vertices [base, base + n) of a
 * closed component with coordinates x (n vertices, local indexing), and whose
 * length is at most dist_max. *out is allocated (free()). */
int tr_contact_pairs_from_struts(const double *x, size_t n, size_t base, const tr_strut *s,
                                 size_t ns, double dist_max, tr_contact_pair **out, size_t *nout,
                                 tr_error *err);

/* A monotone map of the circle [0, L) to itself, piecewise linear through
 * knots l[k] (increasing, in [0, L)) with lifted values u[k]: sigma(l) =
 * u(l) mod L, u nondecreasing, u(l + L) = u(l) + L. */
typedef struct tr_contact_fn {
    size_t n;
    double L;
    double *l, *u;
} tr_contact_fn;

/* From samples (l_k, u_k) in any order (l_k any real, u_k - l_k the forward
 * offset): sorts them, and makes u nondecreasing by isotonic regression
 * (pool adjacent violators). */
int tr_contact_fn_from_samples(const double *l, const double *u, size_t n, double L,
                               tr_contact_fn *out, tr_error *err);
void tr_contact_fn_free(tr_contact_fn *f);
double tr_contact_fn_lift(const tr_contact_fn *f, double l);
double tr_contact_fn_eval(const tr_contact_fn *f, double l); /* in [0, L) */
double tr_contact_fn_slope(const tr_contact_fn *f, double l);

/* Both contact functions from a contact set. Each strut gives the oriented
 * pixels (li, lj) and (lj, li); pixels are binned along t = l + partner (bin
 * width `bin` in t) and, within a bin, split at the largest gap of the
 * forward offsets (partner - l mod L) into the two partners. sigma- is the
 * branch with the smaller forward offset, sigma+ the larger: the two partners
 * of a point never coincide, so the offsets never cross and the naming is
 * consistent along the knot (for the tight trefoil it gives the paper's
 * sigma-(0.189) = 15.674 < sigma+(0.189) = 21.455). A bin with one cluster is
 * given to the branch whose nearest two-cluster bin it is closer to. */
int tr_contact_functions_build(const tr_contact_pair *p, size_t np, double L, double bin,
                               tr_contact_fn *minus, tr_contact_fn *plus, tr_error *err);

/* Range of the bin width of tr_contact_functions_build, relative to L: below
 * L * 1e-7 a bin is far under any polygon's resolution (and the bin index of
 * t in [0, 2L) would lose its meaning); above L/8 the two branches merge.
 * Outside it the function returns TR_EINVAL. */
#define TR_CONTACT_BIN_MIN_REL 1e-7
#define TR_CONTACT_BIN_MAX_REL 0.125

typedef struct tr_fixed_point {
    double l;       /* fixed point of f^power, in [0, L) */
    double slope;   /* derivative of f^power there (chain rule along the orbit) */
    int stable;     /* |slope| < 1 */
    int cycle;      /* index of the cycle (orbit under f) it belongs to */
    int order;      /* position in that cycle, in the order of successive actions of f */
} tr_fixed_point;

typedef struct tr_cycle {
    int period;    /* members (power / period divides ...) */
    int stable;    /* 1 all members stable, 0 all unstable, -1 mixed */
    size_t first;  /* index (into the fixed-point array) of its member with the smallest l */
} tr_cycle;

/* Largest functional power tr_power_fixed_points accepts (the paper's is 9;
 * each grid point costs `power` evaluations of f). */
#define TR_CONTACT_POWER_MAX 100

/* Fixed points of f^power: roots of ((f^power(l) - l + L/2) mod L) - L/2 on a
 * grid of `grid` points refined by bisection; then grouped into orbits of f.
 * power in [1, TR_CONTACT_POWER_MAX], grid >= 8, else TR_EINVAL.
 * Arrays allocated (free()). */
int tr_power_fixed_points(const tr_contact_fn *f, int power, size_t grid, tr_fixed_point **fp,
                          size_t *nfp, tr_cycle **cyc, size_t *ncyc, tr_error *err);

#endif
