/* The turning angle theta at a polygon vertex, as t = tan(theta/2), with its
 * gradients: the one quantity behind Rawdon's MinRad, min(|p|,|q|) / (2 t),
 * shared by the polish (polish.c) and the KKT certificate (kkt.c) so both
 * differentiate the same function. */
#ifndef TR_TURNING_ANGLE_H
#define TR_TURNING_ANGLE_H

#include <string.h>

#include "util/vec3.h"

/* p = x_i - x_prev, q = x_next - x_i, lp = |p|, lq = |q|. Returns t and
 * writes dt/dp, dt/dq; a straight vertex (|p x q| <= 1e-12 |p||q|, p.q > 0)
 * gets t = 0 and zero gradients: it is far from any curvature bound. */
static inline double tr_turning_tan(const double *p, const double *q, double lp, double lq,
                                    double *dtp, double *dtq)
{
    double cr[3];
    v3_cross(cr, p, q);
    double sn = v3_norm(cr), dt = v3_dot(p, q);
    if (sn <= 1e-12 * lp * lq && dt > 0) {
        memset(dtp, 0, 3 * sizeof *dtp);
        memset(dtq, 0, 3 * sizeof *dtq);
        return 0.0;
    }
    double t = sn / (lp * lq + dt);
    double cs = dt / (lp * lq), si = sn / (lp * lq), k = 0.5 * (1.0 + t * t);
    for (int a = 0; a < 3; a++) {
        double ph = p[a] / lp, qh = q[a] / lq;
        dtp[a] = k * (cs * ph - qh) / (lp * si);
        dtq[a] = k * (cs * qh - ph) / (lq * si);
    }
    return t;
}

/* The same at vertex i of coordinates x with neighbours ip and in: also
 * writes the edges p, q and their lengths, which every MinRad row needs. */
static inline double tr_vertex_turning(const double *x, size_t ip, size_t i, size_t in, double *p, double *q,
                                       double *lp, double *lq, double *dtp, double *dtq)
{
    v3_sub(p, x + 3 * i, x + 3 * ip);
    v3_sub(q, x + 3 * in, x + 3 * i);
    *lp = v3_norm(p);
    *lq = v3_norm(q);
    return tr_turning_tan(p, q, *lp, *lq, dtp, dtq);
}

#endif
