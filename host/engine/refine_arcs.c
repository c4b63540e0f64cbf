/* This file contains the open rope's resampling along inscribed arcs
 * (refine_arcs.h). */
#include "engine/refine_arcs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/vec3.h"

/* The circle through a, b, p: its curvature (0 when the three are
 * collinear to rounding) and centre. */
static double circumcircle(const double *a, const double *b, const double *p, double *centre)
{
    double u[3], v[3], uxv[3], t[3], w[3];
    v3_sub(u, a, p);
    v3_sub(v, b, p);
    v3_cross(uxv, u, v);
    double d = v3_dot(uxv, uxv);
    double uu = v3_dot(u, u), vv = v3_dot(v, v);
    if (d <= 1e-28 * uu * vv)
        return 0.0;
    /* centre = p + ((|u|^2 v - |v|^2 u) x (u x v)) / (2 |u x v|^2) */
    for (int q = 0; q < 3; q++)
        t[q] = uu * v[q] - vv * u[q];
    v3_cross(w, t, uxv);
    for (int q = 0; q < 3; q++)
        centre[q] = p[q] + w[q] / (2.0 * d);
    return 1.0 / sqrt(v3_dist2(centre, a));
}

/* One old edge a -> b as an arc: chord length l, unit chord u, unit bulge
 * direction v (in the circle's plane, away from its centre), radius r and
 * half-angle phi; r = 0 marks a straight edge. */
typedef struct arc {
    double a[3], mid[3], u[3], v[3];
    double l, r, phi, len;
} arc;

static void arc_make(arc *s, const double *a, const double *b, double kappa, const double *centre)
{
    memcpy(s->a, a, sizeof s->a);
    v3_sub(s->u, b, a);
    s->l = v3_norm(s->u);
    for (int q = 0; q < 3; q++) {
        s->mid[q] = 0.5 * (a[q] + b[q]);
        s->u[q] = s->l > 0 ? s->u[q] / s->l : 0.0;
    }
    s->r = 0.0;
    s->len = s->l;
    if (kappa <= 0.0 || s->l <= 0.0)
        return;
    double v[3];
    v3_sub(v, s->mid, centre);
    v3_axpy(v, -v3_dot(v, s->u), s->u);
    double nv = v3_norm(v);
    double half = 0.5 * s->l * kappa;
    if (nv <= 0.0 || half >= 1.0)
        return; /* a half circle or a degenerate one: kept straight */
    v3_scale(s->v, 1.0 / nv, v);
    s->r = 1.0 / kappa;
    s->phi = asin(half);
    s->len = 2.0 * s->phi * s->r;
}

/* The point at arclength fraction f (0..1) of the arc. */
static void arc_point(const arc *s, double f, double *p)
{
    if (s->r == 0.0) {
        for (int q = 0; q < 3; q++)
            p[q] = s->a[q] + f * s->l * s->u[q];
        return;
    }
    double psi = (2.0 * f - 1.0) * s->phi;
    double along = s->r * sin(psi);
    /* r (cos psi - cos phi), without the cancellation */
    double out = 2.0 * s->r * sin(0.5 * (s->phi + psi)) * sin(0.5 * (s->phi - psi));
    for (int q = 0; q < 3; q++)
        p[q] = s->mid[q] + along * s->u[q] + out * s->v[q];
}

int tr_refine_arcs_open(const tr_curve *c, int k, size_t m, double *y, tr_error *err)
{
    size_t s0 = c->start[k], n = tr_comp_nv(c, k);
    if (c->closed[k] || n < 2 || m < 2)
        return tr_fail(err, TR_EINVAL, "arc resampling needs an open rope of two vertices or more");
    const double *x = c->x + 3 * s0;
    size_t ne = n - 1;
    double *kappa = calloc(n, sizeof *kappa), *centre = calloc(3 * n, sizeof *centre);
    arc *arcs = malloc(ne * sizeof *arcs);
    double *cum = malloc((ne + 1) * sizeof *cum);
    if (!kappa || !centre || !arcs || !cum) {
        free(kappa);
        free(centre);
        free(arcs);
        free(cum);
        return tr_fail(err, TR_ENOMEM, "out of memory resampling");
    }
    for (size_t i = 1; i + 1 < n; i++)
        kappa[i] = circumcircle(x + 3 * (i - 1), x + 3 * (i + 1), x + 3 * i, centre + 3 * i);
    cum[0] = 0.0;
    for (size_t j = 0; j < ne; j++) {
        /* the circles at the edge's two ends both pass through it; the
         * ends of the rope have none */
        size_t pick = 0;
        double kp = 0.0;
        if (j >= 1 && kappa[j] > kp) {
            pick = j;
            kp = kappa[j];
        }
        if (j + 2 < n && kappa[j + 1] > kp) {
            pick = j + 1;
            kp = kappa[j + 1];
        }
        arc_make(&arcs[j], x + 3 * j, x + 3 * (j + 1), kp, centre + 3 * pick);
        cum[j + 1] = cum[j] + arcs[j].len;
    }
    double total = cum[ne];
    size_t seg = 0;
    for (size_t i = 0; i < m; i++) {
        double t = total * (double)i / (double)(m - 1);
        while (seg + 1 < ne && cum[seg + 1] <= t)
            seg++;
        double len = cum[seg + 1] - cum[seg];
        double f = len > 0 ? (t - cum[seg]) / len : 0.0;
        arc_point(&arcs[seg], f < 0 ? 0 : f > 1 ? 1 : f, y + 3 * i);
    }
    memcpy(y, x, 3 * sizeof *y);
    memcpy(y + 3 * (m - 1), x + 3 * (n - 1), 3 * sizeof *y);
    free(kappa);
    free(centre);
    free(arcs);
    free(cum);
    return TR_OK;
}
