/* The relaxation of a loose start (relax.h). */
#include "geometry/relax.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "segment_distance.h"

/* the energy's power: the push between two vertices at r is r^-(P+1),
 * P = 4 (the push below is d / r^6, d the vector between them) */
#define RELAX_POWER 4.0
/* the springs' stiffness (force per length stretched) and the push between
 * two vertices one mean edge apart, in units of the mean edge */
#define RELAX_SPRING 2.0
#define RELAX_PUSH 5.0
/* the largest move in a step: a tenth of the closest non-adjacent edges'
 * distance (TR_RELAX_STEPS_BETWEEN steps between two looks move a vertex by
 * at most 0.4 of it, two strands by 0.8: they cannot meet), and a twentieth
 * of the mean edge */
#define RELAX_MOVE_OF_GAP 0.1
#define RELAX_MOVE_OF_EDGE 0.05
/* and at most this times the force (a length: the springs' stretch, the push
 * in units of the mean edge): a step of the bound alone would grow without
 * limit as the forces vanish, and the stiffest mode (neighbours moving
 * against each other along the springs, 4 RELAX_SPRING) would jitter at a
 * twentieth of an edge instead of settling; gradient descent is stable
 * below 2 / (4 RELAX_SPRING) = 0.25 */
#define RELAX_RATE 0.2

/* cyclic index distance of vertices (or edges) i and j of one component */
static size_t cyc_gap(size_t i, size_t j, size_t n)
{
    size_t g = i > j ? i - j : j - i;
    return g < n - g ? g : n - g;
}

/* The distance between the closest two edges that share no vertex. An edge
 * is within half its length of its midpoint, so two edges whose midpoints
 * are farther apart than the best so far plus their half lengths are not
 * measured (most pairs). mid holds 4 numbers an edge: midpoint, half length. */
static double closest_edges(const tr_curve *c, double *mid)
{
    for (int k = 0; k < c->ncomp; k++) {
        size_t s = c->start[k], n = tr_comp_nv(c, k);
        for (size_t i = 0; i < n; i++) {
            const double *a = c->x + 3 * (s + i), *b = c->x + 3 * (s + (i + 1) % n);
            double *m = mid + 4 * (s + i);
            for (int q = 0; q < 3; q++)
                m[q] = 0.5 * (a[q] + b[q]);
            m[3] = 0.5 * sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                              (b[2] - a[2]) * (b[2] - a[2]));
        }
    }
    double best = INFINITY;
    for (int ka = 0; ka < c->ncomp; ka++) {
        size_t sa = c->start[ka], na = tr_comp_nv(c, ka);
        for (size_t i = 0; i < na; i++) {
            const double *p0 = c->x + 3 * (sa + i), *p1 = c->x + 3 * (sa + (i + 1) % na);
            const double *mi = mid + 4 * (sa + i);
            for (int kb = ka; kb < c->ncomp; kb++) {
                size_t sb = c->start[kb], nb = tr_comp_nv(c, kb);
                for (size_t j = kb == ka ? i + 2 : 0; j < nb; j++) {
                    if (kb == ka && cyc_gap(i, j, na) < 2)
                        continue;
                    const double *mj = mid + 4 * (sb + j);
                    double reach = best + mi[3] + mj[3];
                    double dx = mi[0] - mj[0], dy = mi[1] - mj[1], dz = mi[2] - mj[2];
                    if (dx * dx + dy * dy + dz * dz > reach * reach)
                        continue;
                    double s, t;
                    const double *q0 = c->x + 3 * (sb + j), *q1 = c->x + 3 * (sb + (j + 1) % nb);
                    best = fmin(best, tr_segment_distance(p0, p1, q0, q1, &s, &t));
                }
            }
        }
    }
    return best;
}

int tr_curve_relax(tr_curve *c, int steps, tr_error *err)
{
    for (int k = 0; k < c->ncomp; k++)
        if (!c->closed[k] || tr_comp_nv(c, k) < 4)
            return tr_fail(err, TR_EINVAL, "the relaxation takes closed components of 4 vertices or more");
    size_t nv = c->nv;
    double *force = malloc(3 * nv * sizeof *force), *rest = malloc((size_t)c->ncomp * sizeof *rest),
           *mid = malloc(4 * nv * sizeof *mid);
    if (!force || !rest || !mid) {
        free(force);
        free(rest);
        free(mid);
        return tr_fail(err, TR_ENOMEM, "out of memory relaxing a start");
    }
    tr_curve_drop_lo(c);
    /* each component's springs rest at its mean edge; the push is scaled by
     * the mean edge of all */
    for (int k = 0; k < c->ncomp; k++)
        rest[k] = tr_comp_length(c, k) / (double)tr_comp_nv(c, k);
    double h = tr_curve_length(c) / (double)nv;
    double push = RELAX_PUSH * pow(h, RELAX_POWER + 2.0);
    double gap = 0;
    for (int it = 0; it < steps; it++) {
        if (it % TR_RELAX_STEPS_BETWEEN == 0)
            gap = closest_edges(c, mid);
        memset(force, 0, 3 * nv * sizeof *force);
        /* the push between every two vertices but neighbours */
        for (int ka = 0; ka < c->ncomp; ka++) {
            size_t sa = c->start[ka], na = tr_comp_nv(c, ka);
            for (size_t i = 0; i < na; i++) {
                const double *a = c->x + 3 * (sa + i);
                double fa[3] = {0, 0, 0};
                for (int kb = ka; kb < c->ncomp; kb++) {
                    size_t sb = c->start[kb], nb = tr_comp_nv(c, kb);
                    /* in a's own component from i + 2, and vertex 0's
                     * neighbour n - 1 left out */
                    size_t j0 = kb == ka ? i + 2 : 0, j1 = kb == ka && i == 0 ? nb - 1 : nb;
                    const double *xb = c->x + 3 * sb;
                    double *fb = force + 3 * sb;
                    for (size_t j = j0; j < j1; j++) {
                        double d0 = a[0] - xb[3 * j], d1 = a[1] - xb[3 * j + 1], d2 = a[2] - xb[3 * j + 2];
                        double r2 = d0 * d0 + d1 * d1 + d2 * d2;
                        double f = push / (r2 * r2 * r2);
                        fa[0] += f * d0;
                        fa[1] += f * d1;
                        fa[2] += f * d2;
                        fb[3 * j] -= f * d0;
                        fb[3 * j + 1] -= f * d1;
                        fb[3 * j + 2] -= f * d2;
                    }
                }
                for (int q = 0; q < 3; q++)
                    force[3 * (sa + i) + q] += fa[q];
            }
        }
        /* the springs along each component */
        for (int k = 0; k < c->ncomp; k++) {
            size_t s = c->start[k], n = tr_comp_nv(c, k);
            for (size_t i = 0; i < n; i++) {
                size_t j = (i + 1) % n;
                const double *a = c->x + 3 * (s + i), *b = c->x + 3 * (s + j);
                double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
                double f = RELAX_SPRING * (len - rest[k]) / len;
                for (int q = 0; q < 3; q++) {
                    force[3 * (s + i) + q] += f * e[q];
                    force[3 * (s + j) + q] -= f * e[q];
                }
            }
        }
        double fbig = 0;
        for (size_t v = 0; v < nv; v++)
            fbig = fmax(fbig, sqrt(force[3 * v] * force[3 * v] + force[3 * v + 1] * force[3 * v + 1] +
                                   force[3 * v + 2] * force[3 * v + 2]));
        if (!(fbig > 0) || !isfinite(fbig) || !(gap > 0))
            break;
        double move = fmin(fmin(RELAX_MOVE_OF_GAP * gap, RELAX_MOVE_OF_EDGE * h) / fbig, RELAX_RATE);
        for (size_t q = 0; q < 3 * nv; q++)
            c->x[q] += move * force[q];
    }
    free(force);
    free(rest);
    free(mid);
    return TR_OK;
}
