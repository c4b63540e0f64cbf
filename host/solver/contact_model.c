/* This file contains the solver's contact model: the distance a strut row
 * holds at 2, with its derivatives, and the thickness the solver's iterates
 * and result are judged by in that model.
 *
 * Rawdon's model (the default): the rows are edge pairs and the distance is
 * the exact segment distance (strut_hessian.h), the thickness the oracle's
 * (oracle/thickness.h). SP-FEM's model (tr_newton_params.vertex_contacts;
 * Przybyl & Pieranski's beams join vertices, oracle/vertex_thickness.h):
 * the rows are vertex pairs, the same pairs the list keeps for edges (a row
 * (a, b) is the first vertices of edges a and b, with the same exclusion
 * K = ceil(pi / l) along a component), and the distance is |x_a - x_b|.
 * Every vertex pair within the cutoff lies on an edge pair within it (an
 * edge's distance is at most its first vertex's), so the list's search
 * misses none; the local minima it keeps are those of the vertex distance.
 * The result is measured by the vertex oracle, not by the lists. */
#include "solver/newton_internal.h"

#include <math.h>

#include "oracle/vertex_thickness.h"
#include "solver/strut_hessian.h"
#include "util/vec3.h"

#include "segment_distance.h"

double tr_newton_i_pair_distance(const solver *s, const double *x, size_t a, size_t b)
{
    if (s->p->vertex_contacts)
        return sqrt(v3_dist2(x + 3 * a, x + 3 * b));
    double sp, tp;
    return tr_segment_distance(x + 3 * a, x + 3 * s->next[a], x + 3 * b, x + 3 * s->next[b], &sp, &tp);
}

int tr_newton_i_strut_index(const solver *s, size_t a, size_t b, size_t *idx)
{
    /* the segment rows' order is p0, p1, q0, q1 (strut_hessian.h) */
    size_t seg[4] = {a, s->next[a], b, s->next[b]}, vtx[2] = {a, b};
    const size_t *vx = s->p->vertex_contacts ? vtx : seg;
    int nvx = s->p->vertex_contacts ? 2 : 4;
    for (int j = 0; j < nvx; j++)
        for (int d = 0; d < 3; d++)
            idx[3 * j + d] = 3 * vx[j] + (size_t)d;
    return 3 * nvx;
}

/* d = |p - q|, u = (p - q) / d: grad d = (u, -u); the Hessian of |p - q| is
 * P = (I - u u^T) / d on the pp and qq blocks and -P on the pq blocks */
static double vertex_derivs(const double *p, const double *q, double *g, double *h)
{
    double c[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
    double d = sqrt(v3_dot(c, c));
    double u[3] = {c[0] / d, c[1] / d, c[2] / d};
    if (g)
        for (int k = 0; k < 3; k++) {
            g[k] = u[k];
            g[3 + k] = -u[k];
        }
    if (h)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double P = ((i == j) - u[i] * u[j]) / d;
                h[i * 6 + j] = P;
                h[(3 + i) * 6 + 3 + j] = P;
                h[i * 6 + 3 + j] = -P;
                h[(3 + i) * 6 + j] = -P;
            }
    return d;
}

int tr_newton_i_strut_derivs(const solver *s, const double *x, size_t a, size_t b, double *d, double *g,
                             double *h, size_t *idx)
{
    int m = tr_newton_i_strut_index(s, a, b, idx);
    if (s->p->vertex_contacts)
        *d = vertex_derivs(x + 3 * a, x + 3 * b, g, h);
    else
        *d = tr_strut_distance_derivs(x + 3 * a, x + 3 * s->next[a], x + 3 * b, x + 3 * s->next[b], g, h);
    return m;
}

int tr_newton_i_model_thickness(const tr_newton_params *p, const tr_curve *c, const tr_thickness_opts *opts,
                                tr_thickness *th, tr_error *err)
{
    int rc = tr_thickness_measure(c, opts, th, NULL, err);
    if (rc || !p->vertex_contacts)
        return rc;
    tr_vertex_thickness vt;
    if ((rc = tr_vertex_thickness_measure(c, NULL, th, &vt, err)))
        return rc;
    /* the vertex model's thickness and ropelength; its closest pair in
     * place of the segments' (the start's overshoot test compares MinRad
     * with it) */
    th->thickness = vt.thickness;
    th->ropelength = vt.ropelength;
    th->dcsd = vt.vertex_dmin;
    return TR_OK;
}
