/* This file contains curvature and torsion of the inscribed-arc knot on a closed polygon
 * (curvature_torsion.h). */
#include "analysis/curvature_torsion.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curve/arclength.h"
#include "util/vec3.h"

void tr_arc_profile_free(tr_arc_profile *p)
{
    if (!p)
        return;
    free(p->pos), free(p->kappa), free(p->dl), free(p->jpos), free(p->phi), free(p->tau),
        free(p->alpha);
    memset(p, 0, sizeof *p);
}

/* Below this |f_{k-1} x f_k| / (|f_{k-1}||f_k|) an arc is straight and its
 * osculating plane undefined; its binormal is carried over from the last arc
 * that had one, so torsion accumulates across straight runs. */
#define TR_STRAIGHT_SIN 1e-13

int tr_arc_profile_compute(const double *w, size_t n, const double *pos, double L,
                           tr_arc_profile *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (n < 4)
        return tr_fail(err, TR_EINVAL, "curvature needs a closed polygon of at least 4 vertices");
    double *f = malloc(3 * n * sizeof *f), *fl = malloc(n * sizeof *fl);
    double *b = malloc(3 * n * sizeof *b), *t = malloc(n * sizeof *t);
    unsigned char *has_b = malloc(n);
    out->pos = malloc(n * sizeof *out->pos);
    out->kappa = malloc(n * sizeof *out->kappa);
    out->dl = malloc(n * sizeof *out->dl);
    out->jpos = malloc(n * sizeof *out->jpos);
    out->phi = malloc(n * sizeof *out->phi);
    out->tau = malloc(n * sizeof *out->tau);
    out->alpha = malloc(n * sizeof *out->alpha);
    if (!f || !fl || !b || !t || !has_b || !out->pos || !out->kappa || !out->dl || !out->jpos ||
        !out->phi || !out->tau || !out->alpha) {
        free(f), free(fl), free(b), free(t), free(has_b);
        tr_arc_profile_free(out);
        return tr_fail(err, TR_ENOMEM, "out of memory for the curvature of %zu vertices", n);
    }
    out->n = n;
    for (size_t k = 0; k < n; k++) {
        v3_sub(f + 3 * k, w + 3 * ((k + 1) % n), w + 3 * k);
        fl[k] = v3_norm(f + 3 * k);
        if (!(fl[k] > 0)) {
            free(f), free(fl), free(b), free(t), free(has_b);
            tr_arc_profile_free(out);
            return tr_fail(err, TR_EGEOMETRY, "edge %zu has zero length", k);
        }
    }
    /* Positions: the polygon's own arclength unless the caller gives them. */
    if (pos) {
        memcpy(out->pos, pos, n * sizeof *pos);
        out->L = L;
    } else {
        double acc = 0.0;
        for (size_t k = 0; k < n; k++) {
            out->pos[k] = acc;
            acc += fl[k];
        }
        out->L = acc;
    }
    /* Arcs: curvature, length, tangent gap. */
    double Lc = 0.0;
    for (size_t k = 0; k < n; k++) {
        const double *a = f + 3 * ((k + n - 1) % n), *c = f + 3 * k;
        double la = fl[(k + n - 1) % n], lc = fl[k];
        double x[3];
        v3_cross(x, a, c);
        double sn = v3_norm(x), cs = v3_dot(a, c);
        double theta = atan2(sn, cs);
        t[k] = 0.5 * fmin(la, lc);
        if (sn / (la * lc) > TR_STRAIGHT_SIN) {
            out->kappa[k] = 2.0 * tan(0.5 * theta) / (2.0 * t[k]);
            out->dl[k] = theta / out->kappa[k];
            v3_scale(b + 3 * k, 1.0 / sn, x);
            has_b[k] = 1;
        } else {
            out->kappa[k] = 0.0;
            out->dl[k] = 2.0 * t[k];
            has_b[k] = 0;
        }
        Lc += out->dl[k];
    }
    /* Straight gaps: the part of edge f_k not covered by the tangent lengths. */
    for (size_t k = 0; k < n; k++)
        Lc += fl[k] - t[k] - t[(k + 1) % n];
    out->L_c = Lc;
    /* Carry binormals over straight arcs (from the last defined one, cyclically). */
    size_t k0 = n;
    for (size_t k = 0; k < n; k++)
        if (has_b[k]) {
            k0 = k;
            break;
        }
    if (k0 == n) {
        for (size_t k = 0; k < n; k++)
            b[3 * k] = 0, b[3 * k + 1] = 0, b[3 * k + 2] = 1;
    } else {
        for (size_t j = 1; j < n; j++) {
            size_t k = (k0 + j) % n;
            if (!has_b[k])
                memcpy(b + 3 * k, b + 3 * ((k + n - 1) % n), 3 * sizeof *b);
        }
    }
    double alpha = 0.0;
    for (size_t k = 0; k < n; k++) {
        size_t k1 = (k + 1) % n;
        const double *b0 = b + 3 * k, *b1 = b + 3 * k1;
        double x[3], tk[3];
        v3_cross(x, b0, b1);
        v3_scale(tk, 1.0 / fl[k], f + 3 * k);
        double phi = atan2(v3_dot(x, tk), v3_dot(b0, b1));
        double h = 0.5 * out->dl[k] + (fl[k] - t[k] - t[k1]) + 0.5 * out->dl[k1];
        out->phi[k] = phi;
        out->tau[k] = phi / h;
        alpha += phi;
        out->alpha[k] = alpha;
        double d = tr_wrap_signed(out->pos[k1] - out->pos[k], out->L);
        out->jpos[k] = tr_wrap(out->pos[k] + 0.5 * d, out->L);
    }
    free(f), free(fl), free(b), free(t), free(has_b);
    return TR_OK;
}
