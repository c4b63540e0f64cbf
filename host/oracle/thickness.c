/* Rawdon's thickness of a polygon with octrope's conventions (docs/physics.md 2):
 * MinRad as octrope_minrad computes it, struts as octrope_struts accepts them
 * (Lumelsky closest points, the endpoint normal-wedge test, the pi_count index
 * rule), the paper's L_p, L_c, L_a, with a tree search in place of octrope's
 * octree so the cost stays linear in N. */
#include "oracle/thickness.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/neighbour_search.h"
#include "util/compensated_sum.h"
#include "util/vec3.h"

/* Edge lengths of a "near-equilateral" component differ by at most this
 * fraction of their mean; only then are L_c and L_a meaningful (the arcs of
 * K_c meet near the edge midpoints). */
#define NEAR_EQUILATERAL_REL 1e-3

/* A vertex whose edges are parallel to this relative accuracy is straight
 * (infinite radius). octrope uses an absolute 1e-12 on |a x b|, which at
 * N = 10^6 (edges ~3e-5) skips every vertex and loses MinRad; relative to
 * |a||b| the test means the same on the knots octrope was made for. */
#define STRAIGHT_SIN 1e-12

/* octrope's find_poca (Lumelsky's segment-segment closest points): s on
 * segment a, t on segment b. Ill-conditioned cases go to long double exactly
 * where octrope does (denominator < 1e-10); octrope's "parallel" test
 * (long-double denominator < 1e-25) is made relative (sin^2 of the angle
 * < 1e-20) so that tiny edges are not all called parallel, and parallel overlapping edges get an interior
 * closest pair (see below). */
double tr_segment_closest(const double *a0, const double *a1, const double *b0, const double *b1,
                          double *s_out, double *t_out)
{
    double d1[3], d2[3], d12[3];
    v3_sub(d1, a1, a0);
    v3_sub(d2, b1, b0);
    v3_sub(d12, b0, a0);
    double D1 = v3_dot(d1, d1), D2 = v3_dot(d2, d2), R = v3_dot(d1, d2);
    double S1 = v3_dot(d1, d12), S2 = v3_dot(d2, d12);
    double denom = D1 * D2 - R * R;
    if (denom < 1e-10) {
        long double LD1 = D1, LD2 = D2, LR = R, LS1 = S1, LS2 = S2;
        /* |d1 x d2|^2 rather than D1 D2 - R^2: no cancellation, so nearly
         * parallel edges are told from parallel ones. */
        long double cx = (long double)d1[1] * d2[2] - (long double)d1[2] * d2[1];
        long double cy = (long double)d1[2] * d2[0] - (long double)d1[0] * d2[2];
        long double cz = (long double)d1[0] * d2[1] - (long double)d1[1] * d2[0];
        long double Ldenom = cx * cx + cy * cy + cz * cz;
        long double LT, LU;
        if (Ldenom < 1e-20L * LD1 * LD2) {
            /* Parallel. octrope takes LT = 0, which lands on an end vertex
             * and misses the strut between parallel edges that overlap
             * (e.g. opposite edges of a rectangle); take the middle of the
             * overlap of the projections instead, when there is one. */
            long double u0 = LS1 / LD1, u1 = (LS1 + LR) / LD1;
            long double lo = u0 < u1 ? u0 : u1, hi = u0 < u1 ? u1 : u0;
            if (lo < 0)
                lo = 0;
            if (hi > 1)
                hi = 1;
            LT = lo <= hi ? 0.5L * (lo + hi) : 0;
        } else {
            LT = (LS1 * LD2 - LS2 * LR) / Ldenom;
            if (LT > 1)
                LT = 1;
            else if (LT < 0)
                LT = 0;
        }
        LU = (LT * LR - LS2) / LD2;
        if (LU > 1) {
            LU = 1;
            LT = (LU * LR + LS1) / LD1;
            if (LT > 1)
                LT = 1;
            else if (LT < 0)
                LT = 0;
        } else if (LU < 0) {
            LU = 0;
            LT = (LU * LR + LS1) / LD1;
            if (LT > 1)
                LT = 1;
            else if (LT < 0)
                LT = 0;
        }
        long double q = 0;
        for (int k = 0; k < 3; k++) {
            long double w = LT * d1[k] - LU * d2[k] - d12[k];
            q += w * w;
        }
        *s_out = (double)LT;
        *t_out = (double)LU;
        return sqrt((double)q);
    }
    double T = (S1 * D2 - S2 * R) / denom;
    if (T > 1)
        T = 1;
    else if (T < 0)
        T = 0;
    double U = (T * R - S2) / D2;
    if (U > 1) {
        U = 1;
        T = (U * R + S1) / D1;
        if (T > 1)
            T = 1;
        else if (T < 0)
            T = 0;
    } else if (U < 0) {
        U = 0;
        T = (U * R + S1) / D1;
        if (T > 1)
            T = 1;
        else if (T < 0)
            T = 0;
    }
    double q = 0;
    for (int k = 0; k < 3; k++) {
        double w = T * d1[k] - U * d2[k] - d12[k];
        q += w * w;
    }
    *s_out = T;
    *t_out = U;
    return sqrt(q);
}

/* octrope's wedge_check: is y in the normal wedge at the start vertex v of
 * an edge (v -> next), i.e. not in front of the edge's normal plane at v and
 * not behind the previous edge's normal plane at v? */
static int in_normal_wedge(const double *prev, const double *v, const double *next, const double *y)
{
    double slab[3], ramp[3], w[3];
    v3_sub(slab, next, v);
    v3_sub(ramp, prev, v);
    v3_sub(w, y, v);
    if (v3_dot(slab, w) > 0)
        return 0;
    if (v3_dot(ramp, w) > 0)
        return 0;
    return 1;
}

static void point_on(double *r, const double *a, const double *b, double s)
{
    for (int k = 0; k < 3; k++)
        r[k] = (1.0 - s) * a[k] + s * b[k];
}

typedef struct strut_search {
    const tr_nsearch *ns;
    double rel_tol;     /* collect struts within (1 + rel_tol) of the best */
    double best;        /* shortest doubly-critical distance so far */
    tr_strut best_strut;
    tr_strut_list *list; /* may be NULL */
    int oom;
} strut_search;

static int is_last_edge(const tr_nsearch *ns, size_t e)
{
    int k = ns->ecomp[e];
    return !ns->c->closed[k] && e + 1 == ns->estart[k + 1];
}

static int list_push(tr_strut_list *l, const tr_strut *s)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 64;
        tr_strut *g = realloc(l->s, cap * sizeof *g);
        if (!g)
            return -1;
        l->s = g;
        l->cap = cap;
    }
    l->s[l->n++] = *s;
    return 0;
}

/* The exact test of octrope's check_boxes for one pair, edge i the "main"
 * edge (the later one in our order). */
static int strut_candidate(void *ctx, size_t ei, size_t ej, double *cutoff)
{
    strut_search *S = ctx;
    const tr_nsearch *ns = S->ns;
    const double *x = ns->c->x;
    const double *a0 = x + 3 * ns->ea[ei], *a1 = x + 3 * ns->eb[ei], *ap = x + 3 * ns->eprev[ei];
    const double *b0 = x + 3 * ns->ea[ej], *b1 = x + 3 * ns->eb[ej], *bp = x + 3 * ns->eprev[ej];
    double s, t;
    double dist = tr_segment_closest(a0, a1, b0, b1, &s, &t);
    if (!(dist <= *cutoff))
        return 0;
    if (!(s < 1 || is_last_edge(ns, ei)) || !(t < 1 || is_last_edge(ns, ej)))
        return 0;
    if (!(s > 0)) {
        double y[3];
        point_on(y, b0, b1, t);
        if (!in_normal_wedge(ap, a0, a1, y))
            return 0;
    }
    if (!(t > 0)) {
        double y[3];
        point_on(y, a0, a1, s);
        if (!in_normal_wedge(bp, b0, b1, y))
            return 0;
    }
    tr_strut st = {.ei = ei, .ej = ej, .si = s, .sj = t, .dist = dist};
    if (dist < S->best) {
        S->best = dist;
        S->best_strut = st;
        *cutoff = S->rel_tol > 0 ? dist * (1.0 + S->rel_tol) : dist;
    }
    if (S->list && list_push(S->list, &st)) {
        S->oom = 1;
        return TR_ENOMEM;
    }
    return 0;
}

/* Seeding: the same exact test with the later edge as the main one, but
 * nothing collected; only the cutoff (and the best strut) move. */
static int strut_seed(void *ctx, size_t ei, size_t ej, double *cutoff)
{
    strut_search *S = ctx;
    tr_strut_list *keep = S->list;
    S->list = NULL;
    int rc = ei > ej ? strut_candidate(ctx, ei, ej, cutoff) : strut_candidate(ctx, ej, ei, cutoff);
    S->list = keep;
    return rc;
}

/* octrope's max_turning_angle: acos of the normalised dot product, NaN
 * (rounding past +-1) ignored as octrope's max() does. */
static double max_turning_angle(const tr_curve *c)
{
    double mx = 0.0;
    for (int k = 0; k < c->ncomp; k++) {
        size_t v0 = c->start[k], n = tr_comp_nv(c, k);
        if (n < 3)
            continue;
        size_t first = c->closed[k] ? 0 : 1, end = c->closed[k] ? n : n - 1;
        for (size_t j = first; j < end; j++) {
            const double *p = c->x + 3 * (v0 + (j + n - 1) % n);
            const double *v = c->x + 3 * (v0 + j);
            const double *q = c->x + 3 * (v0 + (j + 1) % n);
            double e1[3], e2[3];
            v3_sub(e1, v, p);
            v3_sub(e2, q, v);
            double ang = acos(v3_dot(e1, e2) / sqrt(v3_dot(e1, e1) * v3_dot(e2, e2)));
            if (ang > mx)
                mx = ang;
        }
    }
    return mx;
}

/* Octrope's pi_count: fewer edges than this cannot turn by pi, so no strut
 * joins edges closer in index (at least 2: neighbours never). */
static size_t pi_count(const tr_curve *c, size_t ne)
{
    double mt = max_turning_angle(c);
    double q = floor(acos(-1.0) / mt);
    size_t pc;
    if (!(q < (double)ne + 2.0))
        pc = ne + 2; /* straight or nearly: every same-component pair skipped */
    else
        pc = (size_t)q;
    return pc < 2 ? 2 : pc;
}

/* MinRad (octrope_minrad) and the inscribed-arc lengths of one component. */
typedef struct comp_lengths {
    double minrad;
    size_t minrad_vertex;
    double length;
    double L_c; /* NAN unless closed and near-equilateral */
} comp_lengths;

/* theta / tan(theta/2) without cancellation for small theta. */
static double arc_factor(double theta)
{
    double x = 0.5 * theta;
    if (x < 1e-4) {
        double x2 = x * x;
        return 2.0 * (1.0 - x2 / 3.0 - x2 * x2 / 45.0);
    }
    return 2.0 * x / tan(x);
}

/* octrope's MinRad at a vertex from its edges in and out (lengths, dot and
 * cross product's norm): INFINITY where it is straight, 0 at a hairpin (the
 * rope folds back on itself: not straight). */
static double vertex_minrad(double normin, double normout, double dot, double crn)
{
    double rad;
    if (crn <= STRAIGHT_SIN * normin * normout) {
        if (dot >= 0)
            return INFINITY; /* straight: no bend, infinite radius */
        rad = 0.0;
    } else {
        rad = (normin * normout + dot) / (2 * crn);
    }
    double mrminus = normin * rad, mrplus = normout * rad;
    return mrminus < mrplus ? mrminus : mrplus;
}

/* vertex_minrad at vertex j of the component of n vertices from v0 */
static double minrad_at(const tr_curve *c, size_t v0, size_t n, size_t j)
{
    double in[3], o[3], cr[3];
    tr_curve_edge(c, v0 + (j + n - 1) % n, v0 + j, in);
    tr_curve_edge(c, v0 + j, v0 + (j + 1) % n, o);
    v3_cross(cr, in, o);
    return vertex_minrad(v3_norm(in), v3_norm(o), v3_dot(in, o), v3_norm(cr));
}

static void component_lengths(const tr_curve *c, int k, comp_lengths *out)
{
    size_t v0 = c->start[k], n = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
    int closed = c->closed[k];
    out->minrad = INFINITY;
    out->minrad_vertex = v0;
    tr_csum len = {0, 0};
    double emin = INFINITY, emax = 0.0;
    /* edges from x + lo (curve.h): exact to eps l0, where the coordinates
     * themselves are known to eps R only when there are no low parts */
    for (size_t j = 0; j < ne; j++) {
        double e[3];
        tr_curve_edge(c, v0 + j, v0 + (j + 1) % n, e);
        double l = v3_norm(e);
        tr_csum_add(&len, l);
        emin = fmin(emin, l);
        emax = fmax(emax, l);
    }
    out->length = tr_csum_value(&len);
    /* Vertices with two edges: all on a closed component, interior ones on an
     * open one (octrope's convention). */
    size_t first = closed ? 0 : 1, end = closed ? n : (n >= 2 ? n - 1 : 0);
    tr_csum arcs = {0, 0};
    for (size_t j = first; j < end; j++) {
        double in[3], o[3], cr[3];
        tr_curve_edge(c, v0 + (j + n - 1) % n, v0 + j, in);
        tr_curve_edge(c, v0 + j, v0 + (j + 1) % n, o);
        double normin = v3_norm(in), normout = v3_norm(o);
        double dot = v3_dot(in, o);
        v3_cross(cr, in, o);
        double crn = v3_norm(cr);
        double tj = 0.5 * fmin(normin, normout);
        if (closed)
            tr_csum_add(&arcs, tj * arc_factor(atan2(crn, dot)));
        double mr = vertex_minrad(normin, normout, dot, crn);
        if (mr < out->minrad) {
            out->minrad = mr;
            out->minrad_vertex = v0 + j;
        }
    }
    out->L_c = NAN;
    if (closed && ne >= 3) {
        double e_av = out->length / (double)ne;
        if (emax - emin <= NEAR_EQUILATERAL_REL * e_av) {
            /* Straight pieces between consecutive arcs: |e_j| - t_j - t_{j+1};
             * zero for an equilateral polygon. */
            for (size_t j = 0; j < ne; j++) {
                double ep[3], e[3], en[3];
                tr_curve_edge(c, v0 + (j + n - 1) % n, v0 + j, ep);
                tr_curve_edge(c, v0 + j, v0 + (j + 1) % n, e);
                tr_curve_edge(c, v0 + (j + 1) % n, v0 + (j + 2) % n, en);
                double lp = v3_norm(ep), l = v3_norm(e), ln = v3_norm(en);
                double piece = l - 0.5 * fmin(lp, l) - 0.5 * fmin(l, ln);
                tr_csum_add(&arcs, piece);
            }
            double R_c = sqrt(1.0 - 0.25 * e_av * e_av);
            out->L_c = tr_csum_value(&arcs) / R_c;
        }
    }
}

/* Two non-neighbouring edges that meet, to rounding: the curve passes
 * through itself. The doubly-critical test of a strut misses such a pair
 * when the crossing is at or next to a vertex (the connector of a crossing
 * has no direction), and thickness = min(MinRad, dcsd/2) holds only for a
 * curve that does not meet itself, so this is looked for on its own. */
typedef struct crossing_search {
    const tr_nsearch *ns;
    double tol;
    size_t ei, ej;
} crossing_search;

static int crossing_candidate(void *ctx, size_t ei, size_t ej, double *cutoff)
{
    crossing_search *X = ctx;
    const double *x = X->ns->c->x;
    (void)cutoff;
    double s, t;
    double d = tr_segment_closest(x + 3 * X->ns->ea[ei], x + 3 * X->ns->eb[ei], x + 3 * X->ns->ea[ej],
                                  x + 3 * X->ns->eb[ej], &s, &t);
    if (!(d <= X->tol))
        return 0;
    X->ei = ei;
    X->ej = ej;
    return 1; /* found: stops the search */
}

/* The measure's bound has passed (tr_thickness_opts.bound). */
static int stopped_at(const tr_curve *c, const tr_deadline *bound, tr_error *err)
{
    return tr_fail(err, TR_EINTERRUPTED, "measuring %zu vertices: %s before the measure was done", c->nv,
                   tr_deadline_passed(bound) == 2 ? "stopped by a signal" : "the time limit came");
}

static int stopped(const tr_nsearch *ns, tr_error *err) { return stopped_at(ns->c, ns->bound, err); }

/* The measure's refusal of a curve through itself: edges ei and ej meet. */
static int crossing_error(const tr_nsearch *ns, size_t ei, size_t ej, tr_error *err)
{
    const tr_curve *c = ns->c;
    int ki = ns->ecomp[ei], kj = ns->ecomp[ej];
    size_t s0 = c->start[ki], t0 = c->start[kj];
    return tr_fail(err, TR_EGEOMETRY,
                   "the curve passes through itself: the edge from vertex %zu to %zu of component %d meets "
                   "the edge from vertex %zu to %zu of component %d, so no rope of any thickness follows it",
                   ns->ea[ej] - t0, ns->eb[ej] - t0, kj, ns->ea[ei] - s0, ns->eb[ei] - s0, ki);
}

/* The largest coordinate in absolute value: the crossing test's tolerance
 * is CROSSING_EPS of it (rounding relative to the coordinates). */
#define CROSSING_EPS (16 * DBL_EPSILON)
static double largest_coordinate(const tr_curve *c)
{
    double m = 0.0;
    for (size_t i = 0; i < 3 * c->nv; i++)
        m = fabs(c->x[i]) > m ? fabs(c->x[i]) : m;
    return m;
}

/* Components too small to have edges or vertices with two edges: refused. */
static int check_counts(const tr_curve *c, tr_error *err)
{
    for (int k = 0; k < c->ncomp; k++) {
        size_t n = tr_comp_nv(c, k);
        if (n < 2 || (c->closed[k] && n < 3))
            return tr_fail(err, TR_EGEOMETRY, "component %d has too few vertices (%zu)", k, n);
    }
    return TR_OK;
}

static int find_crossing(const tr_nsearch *ns, tr_error *err)
{
    crossing_search X = {.ns = ns, .tol = CROSSING_EPS * largest_coordinate(ns->c)};
    double cutoff = X.tol;
    int rc = tr_nsearch_pairs(ns, &cutoff, 2, 0, crossing_candidate, &X);
    if (rc == 0)
        return TR_OK;
    if (rc == TR_NSEARCH_STOPPED)
        return stopped(ns, err);
    if (rc != 1)
        return tr_fail(err, TR_ENOMEM, "out of memory looking for self-crossings");
    return crossing_error(ns, X.ei, X.ej, err);
}

/* tr_thickness_measure in the curve's own frame. */
static int measure_frame(const tr_curve *c, const tr_thickness_opts *opts, tr_thickness *out,
                         tr_strut_list *struts, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (!c || c->ncomp <= 0 || !c->x)
        return tr_fail(err, TR_EINVAL, "thickness of an empty curve");
    double rel_tol = opts ? opts->strut_rel_tol : 0.0;
    if (!(rel_tol >= 0) || !isfinite(rel_tol))
        return tr_fail(err, TR_EINVAL, "strut tolerance must be finite and >= 0, got %g", rel_tol);
    int rc = check_counts(c, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < 3 * c->nv; i++)
        if (!isfinite(c->x[i]))
            return tr_fail(err, TR_EGEOMETRY, "vertex %zu is not finite", i / 3);

    /* the linear passes before the pair search (lengths, the search's
     * boxes) take a few hundred ms at 10^6 vertices: the bound is looked at
     * between them as well */
    const tr_deadline *bound = opts ? opts->bound : NULL;
    if (tr_deadline_passed_for(bound, c->nv))
        return stopped_at(c, bound, err);
    out->vertices = c->nv;
    tr_csum len = {0, 0}, lc = {0, 0};
    int all_equilateral = 1;
    out->minrad = INFINITY;
    for (int k = 0; k < c->ncomp; k++) {
        comp_lengths cl;
        component_lengths(c, k, &cl);
        tr_csum_add(&len, cl.length);
        if (cl.minrad < out->minrad) {
            out->minrad = cl.minrad;
            out->minrad_vertex = cl.minrad_vertex;
        }
        if (isnan(cl.L_c))
            all_equilateral = 0;
        else
            tr_csum_add(&lc, cl.L_c);
    }
    out->length = tr_csum_value(&len);
    if (all_equilateral) {
        out->L_p = out->length;
        out->L_c = tr_csum_value(&lc);
        out->L_a = 0.8 * out->L_p + 0.2 * out->L_c;
    } else {
        out->L_p = out->L_c = out->L_a = NAN;
    }

    if (tr_deadline_passed_for(bound, c->nv))
        return stopped_at(c, bound, err);
    tr_nsearch ns;
    rc = tr_nsearch_build(&ns, c, err);
    if (rc)
        return rc;
    ns.bound = bound;
    if ((rc = find_crossing(&ns, err))) {
        tr_nsearch_free(&ns);
        return rc;
    }
    strut_search S = {.ns = &ns, .rel_tol = rel_tol, .best = INFINITY, .list = struts};
    if (struts)
        struts->n = 0;
    size_t pc = pi_count(c, ns.ne);
    double cutoff = INFINITY;
    if (opts && opts->brute_force) {
        rc = tr_nsearch_pairs_brute(&ns, &cutoff, pc, TR_NSEARCH_CRITICAL, strut_candidate, &S);
    } else {
        /* A first strut from a few sample edges bounds dcsd from above, so
         * the search below prunes by distance from its first edge on. Every
         * pair under that bound is still looked at, so the result is exact. */
        size_t step = ns.ne / 64 + 1;
        for (size_t i = 0; i < ns.ne && rc == 0; i += step)
            rc = tr_nsearch_edge(&ns, i, &cutoff, pc, TR_NSEARCH_CRITICAL, strut_seed, &S);
        if (rc == 0)
            rc = tr_nsearch_pairs(&ns, &cutoff, pc, TR_NSEARCH_CRITICAL, strut_candidate, &S);
    }
    if (rc == TR_NSEARCH_STOPPED)
        rc = stopped(&ns, err);
    else if (rc)
        rc = tr_fail(err, TR_ENOMEM, "out of memory collecting struts");
    tr_nsearch_free(&ns);
    if (rc)
        return rc;

    out->dcsd = S.best;
    if (isfinite(S.best))
        out->shortest = S.best_strut;
    if (struts) {
        /* Keep the struts within the tolerance of the final shortest. */
        double lim = S.best * (1.0 + rel_tol);
        size_t m = 0;
        for (size_t i = 0; i < struts->n; i++)
            if (struts->s[i].dist <= lim)
                struts->s[m++] = struts->s[i];
        struts->n = m;
    }
    out->thickness = fmin(out->minrad, 0.5 * out->dcsd);
    out->ropelength = out->length / out->thickness;
    return TR_OK;
}

/* The curve is measured in tr_curve_frame_of's frame: centred when it is
 * far from the origin for its size (so that the crossing test's tolerance,
 * relative to the coordinates, is relative to the curve), and scaled by a
 * power of two, exactly, when its coordinates are near 1e+-300 (where
 * squared distances over- or underflow); lengths are scaled back. A curve
 * whose numbers cannot hold its shape (curve.h, tr_curve_check_resolution:
 * a circle of radius 5 at x = 1e15, or in subnormal numbers) is refused:
 * any number measured from it would be the rounding's. */
int tr_thickness_measure(const tr_curve *c, const tr_thickness_opts *opts, tr_thickness *out,
                         tr_strut_list *struts, tr_error *err)
{
    if (!c || c->ncomp <= 0 || !c->x)
        return measure_frame(c, opts, out, struts, err);
    for (size_t i = 0; i < 3 * c->nv; i++)
        if (!isfinite(c->x[i]))
            return measure_frame(c, opts, out, struts, err); /* which names the vertex */
    memset(out, 0, sizeof *out);
    tr_curve_frame f;
    tr_curve s;
    const tr_curve *use;
    int rc = tr_curve_oracle_frame(c, &f, &s, &use, err);
    if (!rc && opts && tr_deadline_passed_for(opts->bound, c->nv))
        rc = stopped_at(c, opts->bound, err);
    if (!rc)
        rc = measure_frame(use, opts, out, struts, err);
    tr_curve_free(&s);
    if (rc || use == c)
        return rc;
    int e = f.e;
    double *len[] = {&out->length, &out->minrad, &out->dcsd, &out->thickness, &out->shortest.dist,
                     &out->L_p, &out->L_c, &out->L_a};
    for (size_t i = 0; e && i < sizeof len / sizeof *len; i++)
        *len[i] = ldexp(*len[i], e);
    for (size_t i = 0; e && struts && i < struts->n; i++)
        struts->s[i].dist = ldexp(struts->s[i].dist, e);
    return TR_OK; /* ropelength, a ratio, is the frame's */
}

int tr_thickness_measure_component(const tr_curve *c, int k, tr_thickness *out, tr_error *err)
{
    if (k < 0 || k >= c->ncomp)
        return tr_fail(err, TR_EINVAL, "no component %d (the curve has %d)", k, c->ncomp);
    tr_curve one;
    int rc = tr_curve_component(&one, c, k, err);
    if (rc)
        return rc;
    rc = tr_thickness_measure(&one, NULL, out, NULL, err);
    tr_curve_free(&one);
    if (rc == TR_OK) {
        /* Report indices in the whole curve's numbering. */
        out->minrad_vertex += c->start[k];
        size_t e0 = 0;
        for (int q = 0; q < k; q++)
            e0 += tr_comp_ne(c, q);
        if (isfinite(out->dcsd)) {
            out->shortest.ei += e0;
            out->shortest.ej += e0;
        }
    }
    return rc;
}

void tr_strut_list_free(tr_strut_list *l)
{
    if (!l)
        return;
    free(l->s);
    l->s = NULL;
    l->n = l->cap = 0;
}

/* ---- the thickness against a gate (thickness.h) ---- */

struct tr_thickness_gate {
    tr_curve view;      /* c's topology; its x is each evaluation's */
    tr_nsearch ns;      /* flat: the edge numbering and the index rules */
    double *mid, *half; /* per edge: midpoint (3), half its length */
    size_t hint_i, hint_j;
    int hint; /* the last evaluation's shortest strut, looked at first */
};

int tr_thickness_gate_new(const tr_curve *c, tr_thickness_gate **out, tr_error *err)
{
    *out = NULL;
    if (!c || c->ncomp <= 0 || !c->x)
        return tr_fail(err, TR_EINVAL, "thickness of an empty curve");
    int rc = check_counts(c, err);
    if (rc)
        return rc;
    tr_thickness_gate *g = calloc(1, sizeof *g);
    if (!g)
        return tr_fail(err, TR_ENOMEM, "out of memory (thickness gate)");
    g->view = *c;
    g->view.lo = NULL; /* the coordinates given are whole */
    rc = tr_nsearch_build_flat(&g->ns, &g->view, err);
    if (rc == TR_OK) {
        size_t ne = g->ns.ne ? g->ns.ne : 1;
        g->mid = malloc(3 * ne * sizeof *g->mid);
        g->half = malloc(ne * sizeof *g->half);
        if (!g->mid || !g->half)
            rc = tr_fail(err, TR_ENOMEM, "out of memory (thickness gate)");
    }
    if (rc) {
        tr_thickness_gate_free(g);
        return rc;
    }
    *out = g;
    return TR_OK;
}

void tr_thickness_gate_free(tr_thickness_gate *g)
{
    if (!g)
        return;
    tr_nsearch_free(&g->ns);
    free(g->mid);
    free(g->half);
    free(g);
}

int tr_thickness_gate_eval(tr_thickness_gate *g, const double *x, double gate, double *thickness, tr_error *err)
{
    tr_curve *c = &g->view;
    c->x = (double *)x; /* read only */
    tr_thickness t;
    int rc;
    /* what tr_thickness_measure refuses it refuses alike, and a curve it
     * would measure in another frame (far from the origin for its size,
     * or near 1e+-300) it measures so: the numbers are then its */
    for (size_t i = 0; i < 3 * c->nv; i++)
        if (!isfinite(x[i]))
            return measure_frame(c, NULL, &t, NULL, err);
    tr_curve_frame f;
    if ((rc = tr_curve_check_resolution(c, NULL, err)))
        return rc;
    tr_curve_frame_of(c, &f);
    if (!tr_curve_frame_is_identity(&f)) {
        if ((rc = tr_thickness_measure(c, NULL, &t, NULL, err)) == TR_OK)
            *thickness = t.thickness;
        return rc;
    }
    /* MinRad first: the cheaper proof of a thickness below the gate */
    double minrad = INFINITY;
    for (int k = 0; k < c->ncomp; k++) {
        size_t v0 = c->start[k], n = tr_comp_nv(c, k);
        size_t first = c->closed[k] ? 0 : 1, end = c->closed[k] ? n : (n >= 2 ? n - 1 : 0);
        for (size_t j = first; j < end; j++) {
            double mr = minrad_at(c, v0, n, j);
            if (mr < minrad)
                minrad = mr;
        }
        if (minrad < gate) {
            *thickness = minrad;
            return TR_OK;
        }
    }
    /* every pair of edges, pruned by their midpoints: two edges are at
     * least |m_i - m_j| - h_i - h_j apart (h half their lengths), and the
     * slack covers the rounding of m and h (relative to the coordinates) */
    const tr_nsearch *ns = &g->ns;
    double m = largest_coordinate(c);
    const double tol = CROSSING_EPS * m, slack = 64 * DBL_EPSILON * m; /* tol: find_crossing's */
    for (size_t e = 0; e < ns->ne; e++) {
        const double *a = x + 3 * ns->ea[e], *b = x + 3 * ns->eb[e];
        double d[3];
        v3_sub(d, b, a);
        for (int q = 0; q < 3; q++)
            g->mid[3 * e + (size_t)q] = 0.5 * (a[q] + b[q]);
        g->half[e] = 0.5 * v3_norm(d);
    }
    size_t pc = pi_count(c, ns->ne);
    strut_search S = {.ns = ns, .rel_tol = 0.0, .best = INFINITY, .list = NULL};
    double cutoff = INFINITY;
    if (g->hint && g->hint_i < ns->ne && !tr_nsearch_excluded(ns, g->hint_i, g->hint_j, pc))
        strut_candidate(&S, g->hint_i, g->hint_j, &cutoff);
    for (size_t i = 1; i < ns->ne && !(S.best < 2.0 * gate); i++) {
        const double *mi = g->mid + 3 * i;
        double hi = g->half[i];
        /* the distance a pair must be within: the cutoff (which the strut
         * test lowers), or the crossing test's tolerance */
        double near = cutoff * (1.0 + 1e-12) > tol ? cutoff * (1.0 + 1e-12) : tol;
        for (size_t j = 0; j < i; j++) {
            const double *mj = g->mid + 3 * j;
            double reach = near + hi + g->half[j] + slack;
            double d2 = (mi[0] - mj[0]) * (mi[0] - mj[0]) + (mi[1] - mj[1]) * (mi[1] - mj[1]) +
                        (mi[2] - mj[2]) * (mi[2] - mj[2]);
            if (d2 > reach * reach || tr_nsearch_excluded(ns, i, j, 2))
                continue;
            /* a curve through itself (find_crossing's test): thickness 0 */
            double lower = sqrt(d2) - hi - g->half[j];
            if (lower <= tol + slack) {
                double s, u;
                if (tr_segment_closest(x + 3 * ns->ea[i], x + 3 * ns->eb[i], x + 3 * ns->ea[j], x + 3 * ns->eb[j],
                                       &s, &u) <= tol) {
                    *thickness = 0.0;
                    return TR_OK;
                }
            }
            if (!tr_nsearch_excluded(ns, i, j, pc)) {
                strut_candidate(&S, i, j, &cutoff);
                near = cutoff * (1.0 + 1e-12) > tol ? cutoff * (1.0 + 1e-12) : tol;
            }
            if (S.best < 2.0 * gate)
                break;
        }
    }
    if (isfinite(S.best)) {
        g->hint = 1;
        g->hint_i = S.best_strut.ei;
        g->hint_j = S.best_strut.ej;
    }
    *thickness = fmin(minrad, 0.5 * S.best);
    return TR_OK;
}
