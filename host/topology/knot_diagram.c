/* The diagram of a closed polygon: project, find the crossings of the
 * projected polygon with a uniform grid, keep over and under from the
 * heights, remove the kinks, write the Gauss and PD codes.
 *
 * Genericity. Coordinates are first moved to the curve's centroid and
 * divided by its radius (largest distance from the centroid), so the
 * tolerances below are fractions of the curve's size, and rounding in the
 * projected coordinates is ~1e-16 of them. A projection is accepted only if
 * every decision that makes the diagram is far from its tie:
 *  - no edge is seen end-on (projected length >= GEN_TOL_D): its crossings'
 *    positions along it would be noise;
 *  - no two consecutive edges fold back onto each other in projection
 *    (turning angle within GEN_TOL_SIN of pi): they would overlap;
 *  - every two non-consecutive projected edges either cross robustly -- at
 *    an angle whose sine is >= GEN_TOL_SIN, at least GEN_TOL_D from each
 *    edge's end vertices, and with heights at the crossing >= GEN_TOL_D
 *    apart -- or stay >= GEN_TOL_D apart. Anything in between (a vertex
 *    that projects onto or next to another edge, a crossing at a vertex,
 *    strands nearly tangent in projection, or a strand passing through the
 *    other in 3D) rejects the direction;
 *  - two crossings on the same edge are >= GEN_TOL_D apart along it, so
 *    their order along the curve is not the rounding's.
 * Then every crossing the arithmetic finds is one of the exact polygon's
 * and none is missed: the rounding errors (~1e-16, or ~1e-16 / GEN_TOL_SIN
 * = 1e-8 of an edge in a crossing's parameter) are far below the margins.
 * A random direction fails these only with probability ~ N x tolerance,
 * so the first of TR_DIAGRAM_DIRECTIONS almost always passes; a curve that
 * fails them all passes through (or within 1e-10 of its size of) itself. */
#include "topology/knot_diagram.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/splitmix64.h"

/* strict C17 math.h has no M_PI */
#define TR_PI 3.14159265358979323846

/* Distances (in the projection plane and in height), in units of the
 * curve's radius: a million times the rounding of unit coordinates, and
 * well below any physical gap (a tight knot's strands are ~0.3 apart). */
#define GEN_TOL_D 1e-10
/* Sine of the smallest accepted crossing angle (and of the fold-back
 * angle): keeps a crossing's parameter error ~1e-8 of an edge. */
#define GEN_TOL_SIN 1e-8
/* The seed of the direction list: "tightrop". */
#define DIAGRAM_SEED 0x7469676874726f70ULL

/* A crossing of the projection: edges e < f (edge i runs from vertex i to
 * vertex i+1 mod n), at parameter s along e and t along f. */
typedef struct crossing {
    size_t e, f;
    double s, t;
    int e_over; /* 1: e passes over f */
    int sign;   /* +1 right-handed, -1 left-handed */
} crossing;

typedef struct crossing_list {
    crossing *c;
    size_t n, cap;
} crossing_list;

/* One passage of the curve through a crossing. */
typedef struct passage {
    size_t edge;
    double param;
    int cross; /* index into the crossing list */
    int over;
} passage;

/* The curve prepared for projection: centred, divided by its radius. */
typedef struct unit_curve {
    size_t n;
    double *y; /* 3n */
    double *p; /* 2n projected */
    double *h; /* n heights along the direction */
} unit_curve;

static double cross2(const double *a, const double *b) { return a[0] * b[1] - a[1] * b[0]; }

static int push_crossing(crossing_list *l, const crossing *x)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 64;
        crossing *c = realloc(l->c, cap * sizeof *c);
        if (!c)
            return TR_ENOMEM;
        l->c = c;
        l->cap = cap;
    }
    l->c[l->n++] = *x;
    return 0;
}

static double point_segment_dist2(const double *q, const double *a, const double *b)
{
    double r[2] = {b[0] - a[0], b[1] - a[1]}, w[2] = {q[0] - a[0], q[1] - a[1]};
    double rr = r[0] * r[0] + r[1] * r[1];
    double s = rr > 0 ? (w[0] * r[0] + w[1] * r[1]) / rr : 0;
    s = s < 0 ? 0 : (s > 1 ? 1 : s);
    double dx = w[0] - s * r[0], dy = w[1] - s * r[1];
    return dx * dx + dy * dy;
}

/* The test of two non-consecutive projected edges e and f (the genericity
 * rule above): 1 and *x when they cross robustly, 0 when they stay clear,
 * -1 and a reason when the pair makes the direction non-generic. */
static int edge_pair(const unit_curve *u, size_t e, size_t f, crossing *x, char *why, size_t whyn)
{
    size_t n = u->n, e1 = (e + 1) % n, f1 = (f + 1) % n;
    const double *a = u->p + 2 * e, *b = u->p + 2 * e1, *c = u->p + 2 * f, *d = u->p + 2 * f1;
    double r[2] = {b[0] - a[0], b[1] - a[1]}, q[2] = {d[0] - c[0], d[1] - c[1]}, ca[2] = {c[0] - a[0], c[1] - a[1]};
    double lr = sqrt(r[0] * r[0] + r[1] * r[1]), lq = sqrt(q[0] * q[0] + q[1] * q[1]);
    double den = cross2(r, q);
    if (den != 0) {
        /* a + s r = c + t q */
        double s = cross2(ca, q) / den, t = cross2(ca, r) / den;
        double ms = GEN_TOL_D / lr, mt = GEN_TOL_D / lq;
        if (fabs(den) >= GEN_TOL_SIN * lr * lq && s >= ms && s <= 1 - ms && t >= mt && t <= 1 - mt) {
            double he = u->h[e] + s * (u->h[e1] - u->h[e]), hf = u->h[f] + t * (u->h[f1] - u->h[f]);
            if (fabs(he - hf) < GEN_TOL_D) {
                snprintf(why, whyn, "edges %zu and %zu pass within %g of the curve's radius of each other", e, f,
                         GEN_TOL_D);
                return -1;
            }
            x->e = e;
            x->f = f;
            x->s = s;
            x->t = t;
            x->e_over = he > hf;
            /* over direction x under direction > 0: right-handed (the
             * viewer at +w sees the plane's (u, v) counterclockwise) */
            double cr = cross2(r, q);
            x->sign = (x->e_over ? cr : -cr) > 0 ? 1 : -1;
            return 1;
        }
        if (s >= -ms && s <= 1 + ms && t >= -mt && t <= 1 + mt) {
            snprintf(why, whyn, "edges %zu and %zu meet at or near a vertex, or nearly tangent", e, f);
            return -1;
        }
    }
    double t2 = GEN_TOL_D * GEN_TOL_D;
    if (point_segment_dist2(a, c, d) < t2 || point_segment_dist2(b, c, d) < t2 || point_segment_dist2(c, a, b) < t2 ||
        point_segment_dist2(d, a, b) < t2) {
        snprintf(why, whyn, "a vertex projects onto another edge (edges %zu and %zu)", e, f);
        return -1;
    }
    return 0;
}

/* Orthonormal u, v with u x v = w (w unit): the viewer at +w sees u, v
 * counterclockwise. */
static void plane_basis(const double *w, double *u, double *v)
{
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(w[i]) < fabs(w[k]))
            k = i;
    double ax[3] = {0, 0, 0};
    ax[k] = 1;
    /* u = w x ax, normalised; v = w x u */
    u[0] = w[1] * ax[2] - w[2] * ax[1];
    u[1] = w[2] * ax[0] - w[0] * ax[2];
    u[2] = w[0] * ax[1] - w[1] * ax[0];
    double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int i = 0; i < 3; i++)
        u[i] /= lu;
    v[0] = w[1] * u[2] - w[2] * u[1];
    v[1] = w[2] * u[0] - w[0] * u[2];
    v[2] = w[0] * u[1] - w[1] * u[0];
}

static size_t cell_of(double x, double x0, double h, size_t nx)
{
    double f = floor((x - x0) / h);
    if (!(f > 0))
        return 0;
    return f >= (double)(nx - 1) ? nx - 1 : (size_t)f;
}

/* Projects u along w and finds the crossings (appended to *out, which is
 * emptied first). Returns 0 (generic), 1 (not generic: why says where) or
 * a negative status. A uniform grid of about 4N cells, each edge entered
 * into every cell its padded bounding box meets, so the work is O(N) for
 * a curve of evenly spread edges; a pair of edges is tested in every cell
 * they share, and a crossing kept only by the cell that holds its point,
 * so each is found once. */
static int project_crossings(unit_curve *u, const double *w, crossing_list *out, char *why, size_t whyn,
                             tr_error *err)
{
    size_t n = u->n;
    double bu[3], bv[3];
    plane_basis(w, bu, bv);
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY, total = 0;
    for (size_t i = 0; i < n; i++) {
        const double *y = u->y + 3 * i;
        double px = y[0] * bu[0] + y[1] * bu[1] + y[2] * bu[2], py = y[0] * bv[0] + y[1] * bv[1] + y[2] * bv[2];
        u->p[2 * i] = px;
        u->p[2 * i + 1] = py;
        u->h[i] = y[0] * w[0] + y[1] * w[1] + y[2] * w[2];
        x0 = fmin(x0, px);
        x1 = fmax(x1, px);
        y0 = fmin(y0, py);
        y1 = fmax(y1, py);
    }
    out->n = 0;
    for (size_t e = 0; e < n; e++) {
        const double *a = u->p + 2 * e, *b = u->p + 2 * ((e + 1) % n), *c = u->p + 2 * ((e + 2) % n);
        double r[2] = {b[0] - a[0], b[1] - a[1]}, q[2] = {c[0] - b[0], c[1] - b[1]};
        double lr = sqrt(r[0] * r[0] + r[1] * r[1]), lq = sqrt(q[0] * q[0] + q[1] * q[1]);
        total += lr;
        if (lr < GEN_TOL_D) {
            snprintf(why, whyn, "edge %zu is seen end-on", e);
            return 1;
        }
        if (n > 3 && fabs(cross2(r, q)) < GEN_TOL_SIN * lr * lq && r[0] * q[0] + r[1] * q[1] < 0) {
            snprintf(why, whyn, "edges %zu and %zu fold back onto each other", e, (e + 1) % n);
            return 1;
        }
    }
    if (n <= 3)
        return 0; /* every two edges of a triangle are consecutive */

    double W = x1 - x0, H = y1 - y0;
    double h = fmax(total / (double)n, sqrt(W * H / (4.0 * (double)n)));
    size_t nx, ny, maxcells = 4 * n + 64;
    for (;;) {
        nx = (size_t)(W / h) + 1;
        ny = (size_t)(H / h) + 1;
        if ((double)nx * (double)ny <= (double)maxcells)
            break;
        h *= 1.25;
    }
    size_t ncell = nx * ny;
    size_t *start = calloc(ncell + 1, sizeof *start);
    size_t *box = malloc(4 * n * sizeof *box);
    if (!start || !box) {
        free(start);
        free(box);
        return tr_fail(err, TR_ENOMEM, "out of memory for the crossing grid of %zu edges", n);
    }
    const double pad = GEN_TOL_D;
    for (size_t e = 0; e < n; e++) {
        const double *a = u->p + 2 * e, *b = u->p + 2 * ((e + 1) % n);
        size_t *bx = box + 4 * e;
        bx[0] = cell_of(fmin(a[0], b[0]) - pad, x0, h, nx);
        bx[1] = cell_of(fmax(a[0], b[0]) + pad, x0, h, nx);
        bx[2] = cell_of(fmin(a[1], b[1]) - pad, y0, h, ny);
        bx[3] = cell_of(fmax(a[1], b[1]) + pad, y0, h, ny);
        for (size_t iy = bx[2]; iy <= bx[3]; iy++)
            for (size_t ix = bx[0]; ix <= bx[1]; ix++)
                start[iy * nx + ix + 1]++;
    }
    for (size_t k = 0; k < ncell; k++)
        start[k + 1] += start[k];
    size_t *fill = malloc(ncell * sizeof *fill), *item = malloc((start[ncell] ? start[ncell] : 1) * sizeof *item);
    if (!fill || !item) {
        free(start);
        free(box);
        free(fill);
        free(item);
        return tr_fail(err, TR_ENOMEM, "out of memory for the crossing grid of %zu edges", n);
    }
    memcpy(fill, start, ncell * sizeof *fill);
    for (size_t e = 0; e < n; e++) {
        const size_t *bx = box + 4 * e;
        for (size_t iy = bx[2]; iy <= bx[3]; iy++)
            for (size_t ix = bx[0]; ix <= bx[1]; ix++)
                item[fill[iy * nx + ix]++] = e;
    }
    int rc = 0;
    for (size_t cell = 0; cell < ncell && rc == 0; cell++) {
        for (size_t i = start[cell]; i < start[cell + 1] && rc == 0; i++) {
            for (size_t j = i + 1; j < start[cell + 1]; j++) {
                size_t e = item[i], f = item[j];
                if (e > f) {
                    size_t tmp = e;
                    e = f;
                    f = tmp;
                }
                if (f == e + 1 || (e == 0 && f == n - 1))
                    continue; /* consecutive edges meet at their shared vertex only (fold-back tested above) */
                crossing x;
                int k = edge_pair(u, e, f, &x, why, whyn);
                if (k < 0) {
                    rc = 1;
                    break;
                }
                if (k == 0)
                    continue;
                /* the cell that holds the crossing's point reports it */
                const double *a = u->p + 2 * e, *b = u->p + 2 * ((e + 1) % n);
                double px = a[0] + x.s * (b[0] - a[0]), py = a[1] + x.s * (b[1] - a[1]);
                if (cell_of(py, y0, h, ny) * nx + cell_of(px, x0, h, nx) != cell)
                    continue;
                if (push_crossing(out, &x)) {
                    rc = tr_fail(err, TR_ENOMEM, "out of memory for the crossings");
                    break;
                }
            }
        }
    }
    free(start);
    free(box);
    free(fill);
    free(item);
    return rc;
}

static int passage_order(const void *pa, const void *pb)
{
    const passage *a = pa, *b = pb;
    if (a->edge != b->edge)
        return a->edge < b->edge ? -1 : 1;
    return (a->param > b->param) - (a->param < b->param);
}

/* The passages of the crossings in curve order, checked for crossings too
 * close along one edge. Returns 0, 1 (not generic) or a negative status. */
static int order_passages(const unit_curve *u, const crossing_list *l, passage **out, char *why, size_t whyn,
                          tr_error *err)
{
    size_t m = 2 * l->n;
    passage *ps = malloc((m ? m : 1) * sizeof *ps);
    if (!ps)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu crossings", l->n);
    for (size_t k = 0; k < l->n; k++) {
        const crossing *x = &l->c[k];
        ps[2 * k] = (passage){x->e, x->s, (int)k, x->e_over};
        ps[2 * k + 1] = (passage){x->f, x->t, (int)k, !x->e_over};
    }
    qsort(ps, m, sizeof *ps, passage_order);
    for (size_t i = 0; i + 1 < m; i++) {
        if (ps[i].edge != ps[i + 1].edge)
            continue;
        const double *a = u->p + 2 * ps[i].edge, *b = u->p + 2 * ((ps[i].edge + 1) % u->n);
        if ((ps[i + 1].param - ps[i].param) * hypot(b[0] - a[0], b[1] - a[1]) < GEN_TOL_D) {
            snprintf(why, whyn, "two crossings within %g of each other on edge %zu", GEN_TOL_D, ps[i].edge);
            free(ps);
            return 1;
        }
    }
    *out = ps;
    return 0;
}

/* Removes the kinks (a crossing whose two passages are consecutive along
 * the curve bounds a loop no other strand crosses: a Reidemeister I move
 * undoes it on the sphere, whichever side the rest of the knot lies) and
 * writes the Gauss and PD codes. Matching passages on a stack removes every
 * kink, the ones that appear when another is removed included, in one pass;
 * the pairs that meet across the start of the cycle are removed after. */
static int build_codes(const crossing_list *l, passage *ps, tr_knot_diagram *d, tr_error *err)
{
    size_t m = 2 * l->n, top = 0;
    for (size_t i = 0; i < m; i++) {
        if (top > 0 && ps[top - 1].cross == ps[i].cross)
            top--;
        else
            ps[top++] = ps[i];
    }
    size_t lo = 0;
    while (top - lo >= 2 && ps[lo].cross == ps[top - 1].cross) {
        lo++;
        top--;
    }
    size_t k = top - lo;
    int nc = (int)(k / 2);
    int *newid = malloc((l->n ? l->n : 1) * sizeof *newid);
    d->gauss = malloc((k ? k : 1) * sizeof *d->gauss);
    d->sign = malloc((nc ? nc : 1) * sizeof *d->sign);
    d->pd = malloc((nc ? nc : 1) * sizeof *d->pd);
    int *under_at = malloc((nc ? nc : 1) * sizeof *under_at), *over_at = malloc((nc ? nc : 1) * sizeof *over_at);
    if (!newid || !d->gauss || !d->sign || !d->pd || !under_at || !over_at) {
        free(newid);
        free(under_at);
        free(over_at);
        return tr_fail(err, TR_ENOMEM, "out of memory for a diagram of %d crossings", nc);
    }
    for (size_t i = 0; i < l->n; i++)
        newid[i] = -1;
    int next = 0;
    for (size_t i = 0; i < k; i++) {
        const passage *p = &ps[lo + i];
        if (newid[p->cross] < 0) {
            newid[p->cross] = next;
            d->sign[next] = (signed char)l->c[p->cross].sign;
            next++;
        }
        int c = newid[p->cross];
        d->gauss[i] = p->over ? c + 1 : -(c + 1);
        if (p->over)
            over_at[c] = (int)i;
        else
            under_at[c] = (int)i;
    }
    d->ncross = nc;
    /* passage i (0-based) is entered by edge i (edge 2nc for i = 0) and
     * left by edge i+1 */
    for (int c = 0; c < nc; c++) {
        int ui = under_at[c], oi = over_at[c];
        int a = ui == 0 ? 2 * nc : ui, cc = ui + 1, j = oi == 0 ? 2 * nc : oi, j1 = oi + 1;
        if (d->sign[c] > 0) {
            d->pd[c][0] = a;
            d->pd[c][1] = j1;
            d->pd[c][2] = cc;
            d->pd[c][3] = j;
        } else {
            d->pd[c][0] = a;
            d->pd[c][1] = j;
            d->pd[c][2] = cc;
            d->pd[c][3] = j1;
        }
    }
    free(newid);
    free(under_at);
    free(over_at);
    return 0;
}

/* Checks c and fills u with its vertices, centred and divided by the
 * radius. */
static int unit_curve_of(const tr_curve *c, unit_curve *u, tr_error *err)
{
    memset(u, 0, sizeof *u);
    if (c->ncomp != 1)
        return tr_fail(err, TR_EUNSUPPORTED,
                       "knot invariants need one closed component; this curve has %d (links are not handled yet)",
                       c->ncomp);
    if (!c->closed[0])
        return tr_fail(err, TR_EINVAL, "knot invariants need a closed curve; this one is an open rope");
    size_t n = c->nv;
    if (n < 3)
        return tr_fail(err, TR_EGEOMETRY, "a closed curve needs at least 3 vertices for a knot type, got %zu", n);
    double m[3] = {0, 0, 0};
    for (size_t i = 0; i < 3 * n; i++) {
        if (!isfinite(c->x[i]))
            return tr_fail(err, TR_EINVAL, "vertex %zu has a coordinate that is not a finite number", i / 3);
        m[i % 3] += c->x[i];
    }
    for (int a = 0; a < 3; a++)
        m[a] /= (double)n;
    double r2 = 0;
    for (size_t i = 0; i < n; i++) {
        double dx = c->x[3 * i] - m[0], dy = c->x[3 * i + 1] - m[1], dz = c->x[3 * i + 2] - m[2];
        r2 = fmax(r2, dx * dx + dy * dy + dz * dz);
    }
    double r = sqrt(r2);
    if (!(r > 0) || !isfinite(r))
        return tr_fail(err, TR_EGEOMETRY, "the curve's vertices all coincide (or its size overflows)");
    for (size_t i = 0; i < n; i++) {
        const double *a = c->x + 3 * i, *b = c->x + 3 * ((i + 1) % n);
        double dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
        if (sqrt(dx * dx + dy * dy + dz * dz) < GEN_TOL_D * r)
            return tr_fail(err, TR_EGEOMETRY, "edge %zu (vertices %zu, %zu) has no length to speak of: no direction "
                           "sees it as a line", i, i, (i + 1) % n);
    }
    u->n = n;
    u->y = malloc(3 * n * sizeof *u->y);
    u->p = malloc(2 * n * sizeof *u->p);
    u->h = malloc(n * sizeof *u->h);
    if (!u->y || !u->p || !u->h)
        return tr_fail(err, TR_ENOMEM, "out of memory projecting %zu vertices", n);
    for (size_t i = 0; i < 3 * n; i++)
        u->y[i] = (c->x[i] - m[i % 3]) / r;
    return 0;
}

static void unit_curve_free(unit_curve *u)
{
    free(u->y);
    free(u->p);
    free(u->h);
}

/* The diagram from direction w (unit), or 1 and a reason. */
static int diagram_from(unit_curve *u, const double *w, crossing_list *l, tr_knot_diagram *d, char *why, size_t whyn,
                        tr_error *err)
{
    int rc = project_crossings(u, w, l, why, whyn, err);
    if (rc)
        return rc;
    passage *ps = NULL;
    rc = order_passages(u, l, &ps, why, whyn, err);
    if (rc)
        return rc;
    if (l->n > (size_t)(INT32_MAX / 4)) {
        free(ps);
        return tr_fail(err, TR_EUNSUPPORTED, "a projection with %zu crossings", l->n);
    }
    rc = build_codes(l, ps, d, err);
    free(ps);
    d->projected_crossings = (int)l->n;
    for (int a = 0; a < 3; a++)
        d->direction[a] = w[a];
    return rc;
}

void tr_knot_diagram_free(tr_knot_diagram *d)
{
    if (!d)
        return;
    free(d->gauss);
    free(d->sign);
    free(d->pd);
    memset(d, 0, sizeof *d);
}

int tr_knot_diagram_along(const tr_curve *c, const double direction[3], tr_knot_diagram *d, tr_error *err)
{
    memset(d, 0, sizeof *d);
    double len = sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    if (!(len > 0) || !isfinite(len))
        return tr_fail(err, TR_EINVAL, "a projection direction must be a nonzero finite vector");
    double w[3] = {direction[0] / len, direction[1] / len, direction[2] / len};
    unit_curve u;
    crossing_list l = {0};
    char why[200] = "";
    int rc = unit_curve_of(c, &u, err);
    if (rc == 0) {
        rc = diagram_from(&u, w, &l, d, why, sizeof why, err);
        if (rc == 1)
            rc = tr_fail(err, TR_EGEOMETRY, "the projection along (%g, %g, %g) is not generic: %s", w[0], w[1], w[2],
                         why);
    }
    d->direction_index = -1;
    unit_curve_free(&u);
    free(l.c);
    return rc;
}

int tr_knot_diagram_of(const tr_curve *c, tr_knot_diagram *d, tr_error *err)
{
    memset(d, 0, sizeof *d);
    unit_curve u;
    int rc = unit_curve_of(c, &u, err);
    if (rc) {
        unit_curve_free(&u);
        return rc;
    }
    /* Every candidate is projected (O(N) each) and the generic one with the
     * fewest crossings kept: fewer crossings, smaller algebra. */
    uint64_t state = DIAGRAM_SEED;
    crossing_list l = {0};
    char why[200] = "", first_why[200] = "";
    int best = -1;
    size_t best_n = SIZE_MAX;
    double dirs[TR_DIAGRAM_DIRECTIONS][3];
    for (int k = 0; k < TR_DIAGRAM_DIRECTIONS; k++) {
        /* uniform on the sphere: z uniform in [-1, 1], azimuth uniform */
        double z = 2.0 * ((double)(tr_splitmix64(&state) >> 11) * 0x1p-53) - 1.0;
        double phi = 2.0 * TR_PI * ((double)(tr_splitmix64(&state) >> 11) * 0x1p-53);
        double s = sqrt(fmax(0.0, 1.0 - z * z));
        dirs[k][0] = s * cos(phi);
        dirs[k][1] = s * sin(phi);
        dirs[k][2] = z;
        int g = project_crossings(&u, dirs[k], &l, why, sizeof why, err);
        if (g == 0) {
            passage *ps = NULL;
            g = order_passages(&u, &l, &ps, why, sizeof why, err);
            free(ps);
        }
        if (g < 0) {
            unit_curve_free(&u);
            free(l.c);
            return g;
        }
        if (g == 1) {
            if (!first_why[0])
                memcpy(first_why, why, sizeof why);
            continue;
        }
        if (l.n < best_n) {
            best_n = l.n;
            best = k;
        }
        if (l.n == 0)
            break;
    }
    if (best < 0) {
        rc = tr_fail(err, TR_EGEOMETRY, "no generic projection among %d directions (first: %s)", TR_DIAGRAM_DIRECTIONS,
                     first_why);
    } else {
        /* the winner again, now with its codes (cheaper than keeping every
         * candidate's crossings) */
        rc = diagram_from(&u, dirs[best], &l, d, why, sizeof why, err);
        if (rc == 1) /* cannot happen: the same arithmetic passed before */
            rc = tr_fail(err, TR_EGEOMETRY, "internal: direction %d changed its verdict: %s", best, why);
        d->direction_index = best;
    }
    unit_curve_free(&u);
    free(l.c);
    return rc;
}
