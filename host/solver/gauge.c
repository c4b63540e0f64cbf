/* This file contains the gauge: the coordinates held so that no rigid motion is left in the Hessian's null space. */
#include "solver/newton_internal.h"

#include <math.h>
#include <string.h>

#include "util/vec3.h"

/* Gram-Schmidt of v (len entries) against the n orthonormal rows of B
 * (stride len); returns the norm of what is left (v is left normalised
 * when that is above 0). */
static double orthogonalise(double *v, const double *B, int n, int len)
{
    for (int pass = 0; pass < 2; pass++) /* twice is enough (Kahan) */
        for (int r = 0; r < n; r++) {
            double d = 0.0;
            for (int c = 0; c < len; c++)
                d += v[c] * B[r * len + c];
            for (int c = 0; c < len; c++)
                v[c] -= d * B[r * len + c];
        }
    double nn = 0.0;
    for (int c = 0; c < len; c++)
        nn += v[c] * v[c];
    nn = sqrt(nn);
    for (int c = 0; c < len && nn > 0.0; c++)
        v[c] /= nn;
    return nn;
}

/* Below this (relative to unit rows) a direction counts as dependent. */
#define GAUGE_TOL 1e-6
/* vertices tried for the held coordinates, spread along the curve */
#define GAUGE_CANDIDATES 24

/* The gauge of a curve with vertex constraints. A rigid motion
 * v_i = a + w x x_i is a gauge (L_A unchanged) only if every constrained
 * vertex may make it: (I - P_i) v_i = 0. The forbidden motions are spanned
 * by the rows q.(a + w x x_i) = q.a + w.(x_i x q) over q = (I - P_i) e_c;
 * the free ones are what Gram-Schmidt leaves of the six unit motions
 * against them (in units of the curve's size R about its centroid, so
 * translations and rotations weigh alike). For the simple clasp (ends on
 * z = +H and z = -H) that is the translations in x and y and the rotation
 * about z; a coordinate the constraints already fix (z of an end) must not
 * be held, and neither must a coordinate a forbidden motion alone moves
 * (it would pin the rope where nothing pins it). So as many coordinates as
 * there are free motions are held, at unconstrained vertices, each chosen
 * greedily as the one whose velocity under the free motions is the most
 * independent of those already held: every free motion then moves a held
 * coordinate, and the Hessian has no null space left. */
static void set_gauge_constrained(solver *s)
{
    size_t nv = s->nv;
    const double *x = s->w.x;
    double o[3] = {0, 0, 0}, R = 0.0;
    for (size_t i = 0; i < nv; i++)
        v3_axpy(o, 1.0 / (double)nv, x + 3 * i);
    for (size_t i = 0; i < nv; i++)
        R = fmax(R, sqrt(v3_dist2(x + 3 * i, o)));
    s->nfixed = 0;
    if (!(R > 0.0))
        return;
    /* the forbidden motions' span (at most 6 independent rows) */
    double B[36], F[36];
    int nb = 0, nf = 0;
    for (size_t q = 0; q < s->ncv && nb < 6; q++) {
        size_t i = s->cv[q];
        double xr[3];
        v3_sub(xr, x + 3 * i, o);
        v3_scale(xr, 1.0 / R, xr);
        for (int c = 0; c < 3 && nb < 6; c++) {
            double e[3] = {c == 0, c == 1, c == 2}, f[3] = {c == 0, c == 1, c == 2};
            tr_constraint_project_motion(tr_newton_i_vertex_cst(s, i), f);
            double qv[3], row[6];
            v3_sub(qv, e, f);
            if (!(v3_norm(qv) > GAUGE_TOL))
                continue;
            memcpy(row, qv, sizeof qv);
            v3_cross(row + 3, xr, qv);
            if (orthogonalise(row, B, nb, 6) > GAUGE_TOL)
                memcpy(B + 6 * nb++, row, sizeof row);
        }
    }
    /* the free motions */
    for (int c = 0; c < 6; c++) {
        double row[6] = {0};
        row[c] = 1.0;
        double both[72];
        memcpy(both, B, (size_t)nb * 6 * sizeof *B);
        memcpy(both + 6 * nb, F, (size_t)nf * 6 * sizeof *F);
        if (orthogonalise(row, both, nb + nf, 6) > GAUGE_TOL)
            memcpy(F + 6 * nf++, row, sizeof row);
    }
    /* held coordinates: velocities (one entry per free motion) made
     * independent greedily */
    double held[36];
    for (int pick = 0; pick < nf; pick++) {
        double best = GAUGE_TOL, bv[6];
        size_t bi = NONE;
        for (int q = 0; q < GAUGE_CANDIDATES; q++) {
            size_t i = (size_t)((double)nv * (double)q / GAUGE_CANDIDATES);
            if (i >= nv || tr_newton_i_vertex_cst(s, i))
                continue;
            double xr[3];
            v3_sub(xr, x + 3 * i, o);
            v3_scale(xr, 1.0 / R, xr);
            for (int c = 0; c < 3; c++) {
                /* e_c.(a + w x xr) = e_c.a + w.(xr x e_c) for each free motion (a, w) */
                double e[3] = {c == 0, c == 1, c == 2}, xe[3], v[6];
                v3_cross(xe, xr, e);
                for (int t = 0; t < nf; t++)
                    v[t] = v3_dot(e, F + 6 * t) + v3_dot(xe, F + 6 * t + 3);
                double nn = orthogonalise(v, held, pick, nf);
                if (nn > best && !tr_newton_i_is_fixed(s, 3 * i + (size_t)c)) {
                    best = nn;
                    bi = 3 * i + (size_t)c;
                    memcpy(bv, v, sizeof bv);
                }
            }
        }
        if (bi == NONE)
            return; /* what is left goes to the Levenberg shift */
        memcpy(held + nf * pick, bv, (size_t)nf * sizeof *bv);
        s->fixed[s->nfixed++] = bi;
    }
}

/* Holds x_0, the two coordinates of x_{N/3} across u = x_{N/3} - x_0 and
 * the coordinate of x_{2N/3} along which the rotation about u moves it
 * most: translations and rotations are then fixed. With vertex constraints
 * only the free rigid motions are held (set_gauge_constrained). */
void tr_newton_i_set_gauge(solver *s)
{
    if (s->ncv > 0) {
        set_gauge_constrained(s);
        return;
    }
    size_t nv = s->nv, k = nv / 3, m = 2 * nv / 3;
    const double *x = s->w.x;
    double u[3], r[3], v[3];
    v3_sub(u, x + 3 * k, x);
    v3_sub(r, x + 3 * m, x);
    v3_cross(v, u, r);
    int cu = 0, cv = 0;
    for (int c = 1; c < 3; c++) {
        if (fabs(u[c]) > fabs(u[cu]))
            cu = c;
        if (fabs(v[c]) > fabs(v[cv]))
            cv = c;
    }
    s->nfixed = 0;
    if (nv < 3 || !(v3_norm(v) > 1e-6 * v3_dot(u, u)))
        return; /* degenerate (straight): leave it to the Levenberg shift */
    for (int c = 0; c < 3; c++)
        s->fixed[s->nfixed++] = (size_t)c;
    for (int c = 0; c < 3; c++)
        if (c != cu)
            s->fixed[s->nfixed++] = 3 * k + (size_t)c;
    s->fixed[s->nfixed++] = 3 * m + (size_t)cv;
}
