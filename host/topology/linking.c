/* Linking numbers (linking.h): crossings of a generic projection counted,
 * or the polygon Gauss integral where no projection is clearly generic. */
#include "topology/linking.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/vec3.h"

#define TR_PI 3.14159265358979323846

/* unit normal of a x b, or 0 when they are parallel */
static int unit_cross(const double *a, const double *b, double *o)
{
    v3_cross(o, a, b);
    double l = sqrt(v3_dot(o, o));
    if (!(l > 0))
        return 0;
    o[0] /= l;
    o[1] /= l;
    o[2] /= l;
    return 1;
}

static double clamp1(double x) { return x > 1 ? 1 : (x < -1 ? -1 : x); }

/* The solid angle (over 4 pi, signed) that edge r1 -> r2 and edge r3 -> r4
 * subtend: the Gauss integral's contribution of the pair. */
static double pair_term(const double *r1, const double *r2, const double *r3, const double *r4)
{
    double r13[3], r14[3], r23[3], r24[3], r12[3], r34[3], n[4][3], c[3];
    v3_sub(r13, r3, r1);
    v3_sub(r14, r4, r1);
    v3_sub(r23, r3, r2);
    v3_sub(r24, r4, r2);
    v3_sub(r12, r2, r1);
    v3_sub(r34, r4, r3);
    if (!unit_cross(r13, r14, n[0]) || !unit_cross(r14, r24, n[1]) || !unit_cross(r24, r23, n[2]) ||
        !unit_cross(r23, r13, n[3]))
        return 0; /* coplanar edges: no solid angle */
    double omega = asin(clamp1(v3_dot(n[0], n[1]))) + asin(clamp1(v3_dot(n[1], n[2]))) +
                   asin(clamp1(v3_dot(n[2], n[3]))) + asin(clamp1(v3_dot(n[3], n[0])));
    v3_cross(c, r34, r12);
    double s = v3_dot(c, r13);
    return s > 0 ? omega : (s < 0 ? -omega : 0);
}

/* ------------------------------------------------ by a projection */

typedef struct pedge {
    double x0, x1; /* extent along the projection's first axis */
    int comp;
    size_t v;      /* first vertex (global index); the edge runs to next */
    size_t w;      /* the other end */
} pedge;

static int pedge_order(const void *a, const void *b)
{
    double x = ((const pedge *)a)->x0, y = ((const pedge *)b)->x0;
    return (x > y) - (x < y);
}

/* Linking numbers from a projection along d: every crossing where
 * component i passes over component j adds its sign to lk(i, j) (and the
 * matrix is symmetrised: each pair's crossings with i over j alone sum to
 * the linking number). 1 when the projection is not clearly generic (a
 * crossing near an edge's end, strands nearly parallel in projection or
 * nearly touching in height), else 0. Edges are swept in order of their
 * extent along the first axis, so the cost is ~N log N for a curve whose
 * edges are short against its size. */
static int linking_by_projection(const tr_curve *c, const double *d, int *lk, tr_error *err)
{
    /* the projection's frame (u, v, d) */
    double u[3], v[3], a[3] = {0, 0, 0};
    int k = fabs(d[0]) < fabs(d[1]) ? (fabs(d[0]) < fabs(d[2]) ? 0 : 2) : (fabs(d[1]) < fabs(d[2]) ? 1 : 2);
    a[k] = 1;
    if (!unit_cross(d, a, u))
        return 1;
    v3_cross(v, d, u);
    size_t ne = c->nv;
    pedge *e = malloc(ne * sizeof *e);
    double *p = malloc(3 * c->nv * sizeof *p);
    int *sum = calloc((size_t)c->ncomp * (size_t)c->ncomp, sizeof *sum);
    if (!e || !p || !sum) {
        free(e);
        free(p);
        free(sum);
        return tr_fail(err, TR_ENOMEM, "out of memory for linking numbers");
    }
    double scale = 0;
    for (size_t i = 0; i < c->nv; i++) {
        const double *x = c->x + 3 * i;
        p[3 * i] = v3_dot(x, u);
        p[3 * i + 1] = v3_dot(x, v);
        p[3 * i + 2] = v3_dot(x, d);
        scale = fmax(scale, fmax(fabs(p[3 * i]), fmax(fabs(p[3 * i + 1]), fabs(p[3 * i + 2]))));
    }
    double tol = 1e-9 * (scale > 0 ? scale : 1);
    size_t m = 0;
    for (int q = 0; q < c->ncomp; q++) {
        size_t s0 = c->start[q], n = tr_comp_nv(c, q);
        for (size_t i = 0; i < n; i++) {
            size_t a0 = s0 + i, a1 = s0 + (i + 1) % n;
            e[m++] = (pedge){fmin(p[3 * a0], p[3 * a1]), fmax(p[3 * a0], p[3 * a1]), q, a0, a1};
        }
    }
    qsort(e, m, sizeof *e, pedge_order);
    int bad = 0;
    for (size_t i = 0; i < m && !bad; i++)
        for (size_t j = i + 1; j < m && e[j].x0 <= e[i].x1 + tol && !bad; j++) {
            if (e[i].comp == e[j].comp)
                continue;
            const double *A = p + 3 * e[i].v, *B = p + 3 * e[i].w, *C = p + 3 * e[j].v, *D = p + 3 * e[j].w;
            double r[2] = {B[0] - A[0], B[1] - A[1]}, t2[2] = {D[0] - C[0], D[1] - C[1]};
            double ca[2] = {C[0] - A[0], C[1] - A[1]};
            double den = r[0] * t2[1] - r[1] * t2[0];
            double lr = hypot(r[0], r[1]), lt = hypot(t2[0], t2[1]);
            if (fabs(den) <= 1e-9 * lr * lt) {
                /* parallel in projection: generic only when well apart */
                double dist = fabs(ca[0] * r[1] - ca[1] * r[0]) / (lr > 0 ? lr : 1);
                if (dist < tol * 1e3 && lr > 0)
                    bad = 1;
                continue;
            }
            double sa = (ca[0] * t2[1] - ca[1] * t2[0]) / den, sc = (ca[0] * r[1] - ca[1] * r[0]) / den;
            double ma = 1e-7, mc = 1e-7;
            if (sa < -ma || sa > 1 + ma || sc < -mc || sc > 1 + mc)
                continue; /* clear of each other */
            if (sa < ma || sa > 1 - ma || sc < mc || sc > 1 - mc) {
                bad = 1; /* at or near an end: the count would be the rounding's */
                break;
            }
            double ha = A[2] + sa * (B[2] - A[2]), hc = C[2] + sc * (D[2] - C[2]);
            if (fabs(ha - hc) < tol * 1e3) {
                bad = 1;
                break;
            }
            /* the sign of the crossing seen from +d: over direction x under
             * direction (knot_diagram.h's convention) */
            int a_over = ha > hc;
            double cr = a_over ? den : -den;
            int sign = cr > 0 ? 1 : -1;
            int over = a_over ? e[i].comp : e[j].comp, under = a_over ? e[j].comp : e[i].comp;
            sum[over * c->ncomp + under] += sign;
        }
    if (!bad)
        for (int i = 0; i < c->ncomp; i++)
            for (int j = 0; j < c->ncomp; j++)
                lk[i * c->ncomp + j] = i == j ? 0 : (i < j ? sum[i * c->ncomp + j] : sum[j * c->ncomp + i]);
    free(e);
    free(p);
    free(sum);
    return bad;
}

/* The Gauss sum over every pair of edges, O(N_i N_j): the fallback when no
 * projection is clearly generic. */
static int linking_by_gauss_sum(const tr_curve *c, int *lk, tr_error *err)
{
    int nc = c->ncomp;
    for (int i = 0; i < nc; i++)
        for (int j = i + 1; j < nc; j++) {
            size_t ni = tr_comp_nv(c, i), nj = tr_comp_nv(c, j);
            const double *xi = c->x + 3 * c->start[i], *xj = c->x + 3 * c->start[j];
            double sum = 0;
            for (size_t a = 0; a < ni; a++)
                for (size_t b = 0; b < nj; b++)
                    sum += pair_term(xi + 3 * a, xi + 3 * ((a + 1) % ni), xj + 3 * b, xj + 3 * ((b + 1) % nj));
            double v = sum / (4 * TR_PI);
            double r = nearbyint(v);
            if (!(fabs(v - r) < 0.05))
                return tr_fail(err, TR_EGEOMETRY, "the Gauss integral of components %d and %d is %.3g, not an integer: "
                               "they touch or pass through each other", i, j, v);
            lk[i * nc + j] = lk[j * nc + i] = (int)r;
        }
    return 0;
}

int tr_linking_numbers(const tr_curve *c, int *lk, tr_error *err)
{
    int nc = c->ncomp;
    memset(lk, 0, (size_t)nc * (size_t)nc * sizeof *lk);
    for (int k = 0; k < nc; k++)
        if (!c->closed[k])
            return tr_fail(err, TR_EINVAL, "linking numbers need closed components; component %d is open", k);
    for (size_t i = 0; i < 3 * c->nv; i++)
        if (!isfinite(c->x[i]))
            return tr_fail(err, TR_EINVAL, "vertex %zu has a coordinate that is not a finite number", i / 3);
    /* a few fixed, irrational-looking directions; the first clearly generic
     * one counts */
    static const double dirs[4][3] = {{0.2672612419124244, 0.5345224838248488, 0.8017837257372732},
                                      {-0.6123724356957945, 0.3535533905932738, 0.7071067811865476},
                                      {0.8728715609439696, -0.2182178902359924, 0.4364357804719848},
                                      {0.1348399724926484, 0.9438798074485388, -0.3015113445777636}};
    for (int k = 0; k < 4; k++) {
        int rc = linking_by_projection(c, dirs[k], lk, err);
        if (rc <= 0)
            return rc;
    }
    return linking_by_gauss_sum(c, lk, err);
}
