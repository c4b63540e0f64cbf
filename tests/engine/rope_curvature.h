/* The clasp tests' curvature profile of one open rope (test_clasp.c,
 * test_clasp_newton.c). */
#ifndef TR_TEST_ROPE_CURVATURE_H
#define TR_TEST_ROPE_CURVATURE_H

#include <math.h>

#include "curve/curve.h"
#include "util/vec3.h"

/* kappa_i = 2 tan(theta_i / 2) / ebar at the interior vertices of rope k:
 * the curvature Rawdon's MinRad bounds (MinRad = 1/kappa on equal edges). */
static inline void rope_curvature(const tr_curve *c, int k, double *kap)
{
    size_t s = c->start[k], n = tr_comp_nv(c, k);
    double ebar = tr_comp_length(c, k) / (double)(n - 1);
    for (size_t i = 1; i + 1 < n; i++) {
        const double *a = c->x + 3 * (s + i - 1), *b = c->x + 3 * (s + i), *d = c->x + 3 * (s + i + 1);
        double p[3], q[3];
        v3_sub(p, b, a);
        v3_sub(q, d, b);
        double cs = v3_dot(p, q) / (v3_norm(p) * v3_norm(q));
        double th = acos(cs > 1.0 ? 1.0 : (cs < -1.0 ? -1.0 : cs));
        kap[i - 1] = 2.0 * tan(0.5 * th) / ebar;
    }
}

#endif
