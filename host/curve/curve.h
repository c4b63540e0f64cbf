/* A curve: one or more polygonal components (a knot, a link, open ropes),
 * stored flat so that every backend sees one array of vertices.
 *
 * Vertices of component k are x[3*i .. 3*i+2] for i in [start[k], start[k+1]).
 * A closed component does not repeat its first vertex.
 * Vertices may carry a constraint (plCurve convention): a fixed point, a line
 * or a plane the vertex must stay on; vcst[i] is an index into cst[] or -1. */
#ifndef TR_CURVE_H
#define TR_CURVE_H

#include <stddef.h>

#include "util/error.h"

typedef enum tr_cst_kind {
    TR_CST_FIXED = 1, /* vertex stays at point p */
    TR_CST_LINE = 2,  /* vertex stays on the line p + t u (u unit) */
    TR_CST_PLANE = 3  /* vertex stays on the plane n.x = d (n unit) */
} tr_cst_kind;

typedef struct tr_constraint {
    tr_cst_kind kind;
    int id;       /* the number the file gave it ("# Constraint 3 ...") */
    double p[3];  /* FIXED: the point; LINE: a point on the line */
    double u[3];  /* LINE: unit direction; PLANE: unit normal */
    double d;     /* PLANE: offset, n.x = d */
} tr_constraint;

typedef struct tr_curve {
    size_t nv;              /* total number of vertices */
    double *x;              /* 3*nv coordinates */
    int ncomp;
    size_t *start;          /* ncomp+1 offsets into the vertex array */
    unsigned char *closed;  /* ncomp flags */
    int *vcst;              /* nv entries (index into cst or -1); NULL if ncst == 0 */
    int ncst;
    tr_constraint *cst;
    /* NULL, or 3*nv low parts: vertex i is at x + lo exactly (|lo| at most
     * half a step of the doubles at x). Why: a vertex in doubles is known
     * to eps R, and a turning angle of size l0 to eps R / l0, so at
     * N = 200 640 the MinRad rows of a polygon stored in doubles carry
     * noise of 1e-8 a vertex and 1e-7 at the worst (the written trefoil
     * paid 5e-6 of ropelength for it); stored to 21 digits (long double)
     * the polygon's thickness is exact to 1e-11 there. Set by the readers
     * when a file carries more digits than a double holds, and by the
     * second-order solver's end game (newton.h); the oracles form edges
     * from x + lo, the writers print it. Anything that moves vertices
     * without knowing of lo drops it first (tr_curve_drop_lo). */
    double *lo;
} tr_curve;

/* Allocates a curve with the given component sizes and closure flags;
 * coordinates are zeroed, no constraints. */
int tr_curve_alloc(tr_curve *c, int ncomp, const size_t *nv, const unsigned char *closed,
                   tr_error *err);
void tr_curve_free(tr_curve *c);
int tr_curve_copy(tr_curve *dst, const tr_curve *src, tr_error *err);
/* one: component k of c alone (its vertices and low parts, its closure; no
 * constraints). */
int tr_curve_component(tr_curve *one, const tr_curve *c, int k, tr_error *err);

/* The low parts: tr_curve_want_lo gives c zeroed ones where it has none;
 * tr_curve_drop_lo forgets them (the vertices are then x, rounded). */
int tr_curve_want_lo(tr_curve *c, tr_error *err);
void tr_curve_drop_lo(tr_curve *c);

/* The edge vector from vertex a to vertex b, from x + lo: the difference
 * of the doubles is exact where the coordinates are within a factor 2 of
 * each other (Sterbenz), so the low parts' difference adds what they hold. */
static inline void tr_curve_edge(const tr_curve *c, size_t a, size_t b, double out[3])
{
    for (int d = 0; d < 3; d++) {
        out[d] = c->x[3 * b + (size_t)d] - c->x[3 * a + (size_t)d];
        if (c->lo)
            out[d] += c->lo[3 * b + (size_t)d] - c->lo[3 * a + (size_t)d];
    }
}

/* Multiplies every vertex (x + lo, in long double) by f; constraints are
 * left as they are. */
void tr_curve_scale_by(tr_curve *c, double f);

/* v = hi + lo split into the double nearest v and the rest (exact where
 * long double is wider than double; else lo = 0). */
void tr_split_long_double(long double v, double *hi, double *lo);

/* Adds a constraint table entry; returns its index or a negative status. */
int tr_curve_add_constraint(tr_curve *c, const tr_constraint *k, tr_error *err);

static inline size_t tr_comp_nv(const tr_curve *c, int k) { return c->start[k + 1] - c->start[k]; }

/* Number of edges of component k: nv for a closed one, nv-1 for an open one. */
static inline size_t tr_comp_ne(const tr_curve *c, int k)
{
    size_t n = tr_comp_nv(c, k);
    return c->closed[k] ? n : (n ? n - 1 : 0);
}

/* Component that vertex i belongs to (binary search over start). */
int tr_curve_comp_of(const tr_curve *c, size_t i);

/* Moves point x (3 doubles) to the nearest point satisfying constraint k. */
void tr_constraint_project(const tr_constraint *k, double *x);

/* Removes from a motion (or force) v the part constraint k forbids: the
 * normal part on a plane, all but the direction on a line, all if fixed. */
void tr_constraint_project_motion(const tr_constraint *k, double *v);

/* Distance from x to the set that constraint k allows. */
double tr_constraint_violation(const tr_constraint *k, const double *x);

/* Total polygon length, compensated (Neumaier) summation. */
double tr_curve_length(const tr_curve *c);
double tr_comp_length(const tr_curve *c, int k);

/* Ropelength is scale free, but squares of coordinates near 1e+-300 over- or
 * underflow. tr_curve_scale_exponent gives the e for which the coordinates
 * times 2^-e have their largest magnitude in [0.5, 1), or 0 when they are
 * already within [2^-TR_CURVE_SAFE_EXP, 2^TR_CURVE_SAFE_EXP] (where squares
 * and fourth powers of differences stay normal numbers) or all zero.
 * tr_curve_scale_pow2 multiplies coordinates and constraints by 2^e, which
 * is exact while nothing leaves the normal range: measuring in that frame
 * and multiplying lengths back by 2^-e gives the same numbers as exact
 * arithmetic in the original one. */
#define TR_CURVE_SAFE_EXP 128
int tr_curve_scale_exponent(const tr_curve *c);
void tr_curve_scale_pow2(tr_curve *c, int e);

/* Ropelength is translation free too, but a curve far from the origin for
 * its size (a circle of radius 5 at x = 1e15) keeps fewer of a double's
 * digits in its vertices' differences, and a tolerance relative to the
 * coordinates' magnitude (a crossing test's, say) no longer fits the curve.
 * The oracles measure in the frame x' = (x - centre) 2^-e: centre[a] is the
 * middle of the curve's extent along axis a, or 0 where that extent holds
 * the origin (the coordinates are then no larger than the extent, so there
 * is nothing to gain and the curve is measured as it stands); e is
 * tr_curve_scale_exponent's of the translated coordinates. The translation
 * rounds each coordinate by at most half a step of the doubles at the
 * curve's own extent, the scaling is exact. */
typedef struct tr_curve_frame {
    double centre[3];
    int e;
} tr_curve_frame;

/* The frame of c (finite coordinates); identity when no translation or
 * scaling is needed. */
void tr_curve_frame_of(const tr_curve *c, tr_curve_frame *f);
int tr_curve_frame_is_identity(const tr_curve_frame *f);
/* dst: a copy of c in frame f, constraints moved with it. */
int tr_curve_to_frame(tr_curve *dst, const tr_curve *c, const tr_curve_frame *f, tr_error *err);
/* What an oracle opens with: c refused if its numbers cannot hold its shape
 * (tr_curve_check_resolution, below), else *f its frame and *use the curve
 * to measure: c itself when the frame is the identity, else *moved, c in
 * frame *f. *moved is zeroed first; the caller frees it either way. */
int tr_curve_oracle_frame(const tr_curve *c, tr_curve_frame *f, tr_curve *moved, const tr_curve **use,
                          tr_error *err);

/* Whether the numbers that hold c can hold its shape at all. A vertex is
 * known to the step between doubles at its coordinates: 2.2e-16 of the
 * coordinate's magnitude, the smallest subnormal 4.9e-324 below 2.2e-308.
 * Far from the origin that step may be as long as the edges themselves (at
 * x = 1e15 it is 0.125; at 1e300 a circle of radius 5 rounds to one line),
 * and in subnormal numbers every coordinate has lost digits. Refused, with
 * TR_EGEOMETRY and a message naming the vertex (*vertex, when not NULL,
 * gets its index in c; SIZE_MAX when no single vertex is to blame):
 *  - a curve whose every coordinate is subnormal (|x| < 2.2e-308): fewer
 *    significant digits than a double has, and 1 / its thickness is beyond
 *    the largest double;
 *  - an edge shorter than TR_CURVE_MIN_STEPS steps of the doubles at its
 *    end points' largest coordinate (the comparison of max |x| with the
 *    extent times 1 / epsilon, made edge by edge with a margin of 2^10):
 *    its direction, and so the vertex's turning angle and MinRad, would be
 *    the rounding's more than the curve's, to a part in 2^10 or worse.
 * A curve that passes is measured right to the accuracy its numbers carry
 * (the oracles work in tr_curve_frame_of's frame): a translation changes the
 * result by at most its rounding of the vertices, a fraction of order
 * step / (edge x turning angle). Zero-length edges are left to the
 * readers, which refuse them as coinciding vertices. */
#define TR_CURVE_MIN_STEPS 1024.0
int tr_curve_check_resolution(const tr_curve *c, size_t *vertex, tr_error *err);

/* The step between doubles at |v| (the smallest subnormal at 0). */
double tr_double_step(double v);

#endif
