/* This file contains curvature and torsion of the inscribed-arc knot on a closed polygon
 * (arc_profile.h). */
#include "analysis/arc_profile.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curve/polyline.h"
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

/* The closed polygon (closed = 1: n arcs, n junctions, positions taken from
 * pos when given) or the open polyline (closed = 0: arcs at the n - 2 interior
 * vertices only, since an end vertex has no turning angle; n - 3 junctions;
 * positions are arclength from vertex 0, never wrapped). */
static int arc_profile(const double *w, size_t n, int closed, const double *pos, double L,
                       tr_arc_profile *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (n < 4)
        return tr_fail(err, TR_EINVAL, "curvature needs a%s polygon of at least 4 vertices",
                       closed ? " closed" : "n open");
    size_t ne = closed ? n : n - 1, na = closed ? n : n - 2, nj = closed ? n : n - 3;
    size_t v0 = closed ? 0 : 1; /* vertex of arc 0 */
    double *f = malloc(3 * n * sizeof *f), *fl = malloc(n * sizeof *fl), *vpos = malloc(n * sizeof *vpos);
    double *b = malloc(3 * n * sizeof *b), *t = calloc(n, sizeof *t);
    unsigned char *has_b = malloc(n);
    out->pos = malloc(n * sizeof *out->pos);
    out->kappa = malloc(n * sizeof *out->kappa);
    out->dl = malloc(n * sizeof *out->dl);
    out->jpos = malloc(n * sizeof *out->jpos);
    out->phi = malloc(n * sizeof *out->phi);
    out->tau = malloc(n * sizeof *out->tau);
    out->alpha = malloc(n * sizeof *out->alpha);
    if (!f || !fl || !vpos || !b || !t || !has_b || !out->pos || !out->kappa || !out->dl ||
        !out->jpos || !out->phi || !out->tau || !out->alpha) {
        free(f), free(fl), free(vpos), free(b), free(t), free(has_b);
        tr_arc_profile_free(out);
        return tr_fail(err, TR_ENOMEM, "out of memory for the curvature of %zu vertices", n);
    }
    out->n = na;
    out->nj = nj;
    out->closed = closed;
    double acc = 0.0;
    for (size_t k = 0; k < ne; k++) {
        v3_sub(f + 3 * k, w + 3 * ((k + 1) % n), w + 3 * k);
        fl[k] = v3_norm(f + 3 * k);
        if (!(fl[k] > 0)) {
            free(f), free(fl), free(vpos), free(b), free(t), free(has_b);
            tr_arc_profile_free(out);
            return tr_fail(err, TR_EGEOMETRY, "edge %zu has zero length", k);
        }
        vpos[k] = acc;
        acc += fl[k];
    }
    if (!closed)
        vpos[n - 1] = acc;
    /* Positions: the polygon's own arclength unless the caller gives them. */
    if (pos && closed) {
        memcpy(out->pos, pos, n * sizeof *pos);
        out->L = L;
    } else {
        for (size_t k = 0; k < na; k++)
            out->pos[k] = vpos[k + v0];
        out->L = acc;
    }
    /* Arcs: curvature, length, tangent gap (t per vertex, 0 at an open end). */
    double Lc = 0.0;
    for (size_t k = 0; k < na; k++) {
        size_t v = k + v0, ea = (v + n - 1) % n, ec = v % n;
        const double *a = f + 3 * ea, *c = f + 3 * ec;
        double la = fl[ea], lc = fl[ec];
        double x[3];
        v3_cross(x, a, c);
        double sn = v3_norm(x), cs = v3_dot(a, c);
        double theta = atan2(sn, cs);
        t[v] = 0.5 * fmin(la, lc);
        if (sn / (la * lc) > TR_STRAIGHT_SIN) {
            out->kappa[k] = 2.0 * tan(0.5 * theta) / (2.0 * t[v]);
            out->dl[k] = theta / out->kappa[k];
            v3_scale(b + 3 * k, 1.0 / sn, x);
            has_b[k] = 1;
        } else {
            out->kappa[k] = 0.0;
            out->dl[k] = 2.0 * t[v];
            has_b[k] = 0;
        }
        Lc += out->dl[k];
    }
    /* Straight gaps: the part of edge f_k not covered by the tangent lengths. */
    for (size_t k = 0; k < ne; k++)
        Lc += fl[k] - t[k] - t[(k + 1) % n];
    out->L_c = Lc;
    /* Carry binormals over straight arcs (from the last defined one,
     * cyclically when closed; arcs before the first defined one of an open
     * rope take it). */
    size_t k0 = na;
    for (size_t k = 0; k < na; k++)
        if (has_b[k]) {
            k0 = k;
            break;
        }
    if (k0 == na) {
        for (size_t k = 0; k < na; k++)
            b[3 * k] = 0, b[3 * k + 1] = 0, b[3 * k + 2] = 1;
    } else {
        for (size_t j = 1; j < na; j++) {
            size_t k = (k0 + j) % na;
            if (!closed && k <= k0)
                memcpy(b + 3 * k, b + 3 * k0, 3 * sizeof *b);
            else if (!has_b[k])
                memcpy(b + 3 * k, b + 3 * ((k + na - 1) % na), 3 * sizeof *b);
        }
    }
    /* Junction k: between arc k and arc k + 1, on the edge that leaves arc k's vertex. */
    double alpha = 0.0;
    for (size_t k = 0; k < nj; k++) {
        size_t k1 = (k + 1) % na, e = k + v0, v1 = (e + 1) % n;
        const double *b0 = b + 3 * k, *b1 = b + 3 * k1;
        double x[3], tk[3];
        v3_cross(x, b0, b1);
        v3_scale(tk, 1.0 / fl[e], f + 3 * e);
        double phi = atan2(v3_dot(x, tk), v3_dot(b0, b1));
        double h = 0.5 * out->dl[k] + (fl[e] - t[e] - t[v1]) + 0.5 * out->dl[k1];
        out->phi[k] = phi;
        out->tau[k] = phi / h;
        alpha += phi;
        out->alpha[k] = alpha;
        if (closed) {
            double d = tr_wrap_signed(out->pos[k1] - out->pos[k], out->L);
            out->jpos[k] = tr_wrap(out->pos[k] + 0.5 * d, out->L);
        } else {
            out->jpos[k] = 0.5 * (out->pos[k] + out->pos[k1]);
        }
    }
    free(f), free(fl), free(vpos), free(b), free(t), free(has_b);
    return TR_OK;
}

int tr_arc_profile_compute(const double *w, size_t n, const double *pos, double L,
                           tr_arc_profile *out, tr_error *err)
{
    return arc_profile(w, n, 1, pos, L, out, err);
}

int tr_arc_profile_compute_open(const double *w, size_t n, tr_arc_profile *out, tr_error *err)
{
    return arc_profile(w, n, 0, NULL, 0.0, out, err);
}
