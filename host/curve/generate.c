/* Start curves and resampling. Every generator describes a smooth curve by a
 * parameter and places the vertices with one routine, equal_chords(), that
 * moves the parameter values until all edges have the same length: the
 * engine's edge constraint wants an equilateral polygon from the start. */
#include "curve/generate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/clock.h"
#include "util/compensated_sum.h"
#include "util/vec3.h"

/* strict C17 math.h has no TR_PI */
#define TR_PI 3.14159265358979323846

/* Point of a parametrised curve at t; *hint is a segment index the callee may
 * keep between calls (t increases within one sweep). */
typedef void (*curve_eval)(const void *ctx, double t, size_t *hint, double *out);

/* Places n points at parameters t[0..n-1] on [t0, t0+T) (closed: the last
 * edge runs back to t[0]) or [t0, t0+T] (open: t[0] = t0, t[n-1] = t0+T
 * exactly, so end vertices stay where they are) with all chords equal.
 * t holds a first guess on entry. The update scales each parameter interval
 * by mean chord / its chord, which is Newton's step for a chord that grows
 * linearly with its interval; the coupling through the renormalisation is
 * weak, so it converges geometrically down to rounding. *spread receives
 * max |chord - mean| / mean of the returned polygon. bound (NULL: none) is
 * looked at once a sweep: a sweep over 10^6 vertices takes ~10 ms and a
 * resampling tens of sweeps, which a --time-limit of seconds must see. */
static int equal_chords(curve_eval f, const void *ctx, double t0, double T, int closed, size_t n, double *t,
                        double *x, double *spread, const tr_deadline *bound, tr_error *err)
{
    size_t m = closed ? n : n - 1;
    double *dt = malloc(m * sizeof *dt), *ch = malloc(m * sizeof *ch);
    if (!dt || !ch) {
        free(dt);
        free(ch);
        return tr_fail(err, TR_ENOMEM, "out of memory resampling %zu vertices", n);
    }
    for (size_t i = 0; i < m; i++)
        dt[i] = (i + 1 < n ? t[i + 1] : t0 + T) - t[i];
    double best = INFINITY, relax = 1.0;
    int stall = 0;
    for (int iter = 0; iter < 400; iter++) {
        int past = tr_deadline_passed_for(bound, n);
        if (past) {
            free(dt);
            free(ch);
            return tr_fail(err, TR_EINTERRUPTED, "resampling %zu vertices: %s", n,
                           past == 2 ? "stopped by a signal" : "the time limit came");
        }
        /* parameters from intervals, compensated so t[n-1] lands on the end */
        tr_csum acc = {t0, 0};
        size_t hint = 0;
        for (size_t i = 0; i < n; i++) {
            t[i] = tr_csum_value(&acc);
            if (!closed && i == n - 1)
                t[i] = t0 + T;
            f(ctx, t[i], &hint, x + 3 * i);
            if (i < m)
                tr_csum_add(&acc, dt[i]);
        }
        tr_csum cs = {0, 0};
        for (size_t i = 0; i < m; i++) {
            ch[i] = sqrt(v3_dist2(x + 3 * i, x + 3 * ((i + 1) % n)));
            tr_csum_add(&cs, ch[i]);
        }
        double mean = tr_csum_value(&cs) / (double)m, dev = 0;
        for (size_t i = 0; i < m; i++)
            dev = fmax(dev, fabs(ch[i] - mean));
        dev /= mean;
        if (!(mean > 0) || !isfinite(dev)) {
            free(dt);
            free(ch);
            return tr_fail(err, TR_EGEOMETRY, "resampling failed: a degenerate edge");
        }
        *spread = dev;
        /* rounding floor: each chord carries an error of a few ulp of the
         * coordinates, which is large relative to a short edge */
        double xmax = 0;
        for (size_t i = 0; i < n; i++)
            xmax = fmax(xmax, fmax(fabs(x[3 * i]), fmax(fabs(x[3 * i + 1]), fabs(x[3 * i + 2]))));
        double floor = 8 * 2.220446049250313e-16 * xmax / mean;
        if (dev < fmax(1e-14, floor))
            break;
        if (dev < best * 0.9) {
            best = dev;
            stall = 0;
        } else if (++stall >= 8) {
            if (dev < fmax(1e-10, 100 * floor) || relax < 0.01)
                break; /* at the rounding floor, or hopeless */
            /* overshooting on a very coarse polygon (chords across several
             * corners): take smaller steps */
            relax *= 0.5;
            stall = 0;
        }
        tr_csum ds = {0, 0};
        for (size_t i = 0; i < m; i++) {
            dt[i] *= relax == 1.0 ? mean / ch[i] : pow(mean / ch[i], relax);
            tr_csum_add(&ds, dt[i]);
        }
        double s = T / tr_csum_value(&ds);
        for (size_t i = 0; i < m; i++)
            dt[i] *= s;
    }
    free(dt);
    free(ch);
    /* the floor is rounding in the coordinates, ~1e-16 |x| / edge; far
     * above it the iteration did not converge (a pathological polygon) */
    if (*spread > 1e-8)
        return tr_fail(err, TR_EGEOMETRY, "could not make the %zu edges equal (spread %.2g)", m, *spread);
    return TR_OK;
}

/* ------------------------------------------------- polygon as a curve */

typedef struct poly_ctx {
    const double *x; /* vertices of one component */
    size_t n, m;     /* vertices, edges */
    double *cum;     /* m+1 cumulative edge lengths */
} poly_ctx;

static void poly_eval(const void *vctx, double t, size_t *hint, double *out)
{
    const poly_ctx *c = vctx;
    size_t k = *hint < c->m ? *hint : 0;
    while (k + 1 < c->m && c->cum[k + 1] <= t)
        k++;
    while (k > 0 && c->cum[k] > t)
        k--;
    *hint = k;
    double len = c->cum[k + 1] - c->cum[k];
    double u = len > 0 ? (t - c->cum[k]) / len : 0;
    u = fmin(fmax(u, 0), 1);
    const double *a = c->x + 3 * k, *b = c->x + 3 * ((k + 1) % c->n);
    /* (1-u) a + u b: exactly a at u = 0 and exactly b at u = 1 */
    for (int d = 0; d < 3; d++)
        out[d] = (1 - u) * a[d] + u * b[d];
}

static int poly_cum(poly_ctx *c, tr_error *err)
{
    c->cum = malloc((c->m + 1) * sizeof *c->cum);
    if (!c->cum)
        return tr_fail(err, TR_ENOMEM, "out of memory resampling");
    tr_csum acc = {0, 0};
    c->cum[0] = 0;
    for (size_t k = 0; k < c->m; k++) {
        tr_csum_add(&acc, sqrt(v3_dist2(c->x + 3 * k, c->x + 3 * ((k + 1) % c->n))));
        c->cum[k + 1] = tr_csum_value(&acc);
    }
    if (!(c->cum[c->m] > 0))
        return tr_fail(err, TR_EGEOMETRY, "cannot resample a component of zero length");
    return TR_OK;
}

/* ------------------------------------------------ cubic spline curve */

/* Interpolating cubic spline through the vertices, parametrised by
 * cumulative chord length: periodic for a closed component, natural (zero
 * second derivative at the ends) for an open one. m2 holds the second
 * derivatives at the knots, 3 per vertex. */
typedef struct spline_ctx {
    poly_ctx p;
    double *m2;
} spline_ctx;

static void spline_eval(const void *vctx, double t, size_t *hint, double *out)
{
    const spline_ctx *s = vctx;
    const poly_ctx *c = &s->p;
    size_t k = *hint < c->m ? *hint : 0;
    while (k + 1 < c->m && c->cum[k + 1] <= t)
        k++;
    while (k > 0 && c->cum[k] > t)
        k--;
    *hint = k;
    size_t k1 = (k + 1) % c->n;
    double h = c->cum[k + 1] - c->cum[k];
    double B = fmin(fmax((t - c->cum[k]) / h, 0), 1), A = 1 - B;
    double ca = (A * A * A - A) * h * h / 6, cb = (B * B * B - B) * h * h / 6;
    for (int d = 0; d < 3; d++)
        out[d] = A * c->x[3 * k + d] + B * c->x[3 * k1 + d] + ca * s->m2[3 * k + d] + cb * s->m2[3 * k1 + d];
}

/* Solves the tridiagonal system a[i] y[i-1] + b[i] y[i] + c[i] y[i+1] = r[i]
 * (a[0], c[n-1] unused) in place of r; w is scratch of n doubles. */
static void tridiag(const double *a, const double *b, const double *c, double *r, double *w, size_t n)
{
    double beta = b[0];
    r[0] /= beta;
    for (size_t i = 1; i < n; i++) {
        w[i] = c[i - 1] / beta;
        beta = b[i] - a[i] * w[i];
        r[i] = (r[i] - a[i] * r[i - 1]) / beta;
    }
    for (size_t i = n - 1; i > 0; i--)
        r[i - 1] -= w[i] * r[i];
}

static int spline_build(spline_ctx *s, int closed, tr_error *err)
{
    const poly_ctx *c = &s->p;
    size_t n = c->n;
    s->m2 = calloc(3 * n, sizeof *s->m2);
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *cc = malloc(n * sizeof *cc);
    double *r = malloc(n * sizeof *r), *z = malloc(n * sizeof *z), *w = malloc(n * sizeof *w);
    double *bb = malloc(n * sizeof *bb);
    int rc = TR_OK;
    if (!s->m2 || !a || !b || !cc || !r || !z || !w || !bb) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory building a spline");
        goto done;
    }
    if (!closed && n < 3)
        goto done; /* two points: the spline is the segment (m2 = 0) */
    const double *x = c->x;
    const double *cum = c->cum;
#define H(i) (cum[(i) + 1] - cum[(i)])
    if (closed) {
        /* row i: h[i-1] M[i-1] + 2 (h[i-1] + h[i]) M[i] + h[i] M[i+1] = rhs,
         * cyclic; Sherman-Morrison turns it into two tridiagonal solves */
        for (size_t i = 0; i < n; i++) {
            double hp = H((i + n - 1) % n), hi = H(i);
            a[i] = hp;
            b[i] = 2 * (hp + hi);
            cc[i] = hi;
        }
        double alpha = cc[n - 1], beta = a[0], gamma = -b[0];
        memcpy(bb, b, n * sizeof *bb);
        bb[0] = b[0] - gamma;
        bb[n - 1] = b[n - 1] - alpha * beta / gamma;
        for (size_t i = 0; i < n; i++)
            z[i] = 0;
        z[0] = gamma;
        z[n - 1] = alpha;
        tridiag(a, bb, cc, z, w, n);
        for (int d = 0; d < 3; d++) {
            for (size_t i = 0; i < n; i++) {
                size_t ip = (i + n - 1) % n, in = (i + 1) % n;
                double hp = H(ip), hi = H(i);
                r[i] = 6 * ((x[3 * in + d] - x[3 * i + d]) / hi - (x[3 * i + d] - x[3 * ip + d]) / hp);
            }
            tridiag(a, bb, cc, r, w, n);
            double fact = (r[0] + beta * r[n - 1] / gamma) / (1 + z[0] + beta * z[n - 1] / gamma);
            for (size_t i = 0; i < n; i++)
                s->m2[3 * i + d] = r[i] - fact * z[i];
        }
    } else {
        size_t ni = n - 2; /* interior knots 1..n-2 */
        for (size_t j = 0; j < ni; j++) {
            size_t i = j + 1;
            a[j] = H(i - 1);
            b[j] = 2 * (H(i - 1) + H(i));
            cc[j] = H(i);
        }
        for (int d = 0; d < 3; d++) {
            for (size_t j = 0; j < ni; j++) {
                size_t i = j + 1;
                r[j] = 6 * ((x[3 * (i + 1) + d] - x[3 * i + d]) / H(i) - (x[3 * i + d] - x[3 * (i - 1) + d]) / H(i - 1));
            }
            tridiag(a, b, cc, r, w, ni);
            for (size_t j = 0; j < ni; j++)
                s->m2[3 * (j + 1) + d] = r[j];
        }
    }
#undef H
done:
    free(a);
    free(b);
    free(cc);
    free(r);
    free(z);
    free(w);
    free(bb);
    return rc;
}

/* ----------------------------------------------------------- resampling */

int tr_resample_within(const tr_curve *in, const size_t *n_per_comp, int smooth, const tr_deadline *bound,
                       tr_curve *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (!in || in->ncomp <= 0)
        return tr_fail(err, TR_EINVAL, "nothing to resample");
    size_t *nv = malloc((size_t)in->ncomp * sizeof *nv);
    if (!nv)
        return tr_fail(err, TR_ENOMEM, "out of memory resampling");
    int rc = TR_OK;
    for (int k = 0; k < in->ncomp; k++) {
        nv[k] = n_per_comp ? n_per_comp[k] : tr_comp_nv(in, k);
        size_t need = in->closed[k] ? 3 : 2;
        if (nv[k] < need) {
            rc = tr_fail(err, TR_EINVAL, "component %d: %zu vertices requested, a%s component needs at least %zu",
                         k, nv[k], in->closed[k] ? " closed" : "n open", need);
            goto out;
        }
        if (tr_comp_nv(in, k) < need) {
            rc = tr_fail(err, TR_EINVAL, "component %d has only %zu vertices", k, tr_comp_nv(in, k));
            goto out;
        }
        /* a constraint pins a vertex; only the ends of an open rope stay
         * vertices after resampling, so only they may carry one */
        for (size_t i = in->start[k]; in->vcst && i < in->start[k + 1]; i++) {
            int end = !in->closed[k] && (i == in->start[k] || i + 1 == in->start[k + 1]);
            if (in->vcst[i] >= 0 && !end) {
                rc = tr_fail(err, TR_EINVAL,
                             "vertex %zu carries a constraint; resampling keeps constraints only on the end vertices of open components",
                             i);
                goto out;
            }
        }
    }
    if ((rc = tr_curve_alloc(out, in->ncomp, nv, in->closed, err)))
        goto out;
    if (in->ncst > 0) {
        for (int j = 0; j < in->ncst; j++) {
            int r = tr_curve_add_constraint(out, &in->cst[j], err);
            if (r < 0) {
                rc = r;
                goto out;
            }
        }
        for (int k = 0; k < in->ncomp; k++) {
            if (in->closed[k])
                continue;
            out->vcst[out->start[k]] = in->vcst[in->start[k]];
            out->vcst[out->start[k + 1] - 1] = in->vcst[in->start[k + 1] - 1];
        }
    }
    for (int k = 0; k < in->ncomp && !rc; k++) {
        spline_ctx sc = {{in->x + 3 * in->start[k], tr_comp_nv(in, k), tr_comp_ne(in, k), NULL}, NULL};
        size_t n = nv[k];
        double *t = malloc(n * sizeof *t);
        if (!t) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory resampling");
            break;
        }
        rc = poly_cum(&sc.p, err);
        if (!rc && smooth)
            rc = spline_build(&sc, in->closed[k], err);
        if (!rc) {
            double L = sc.p.cum[sc.p.m], spread;
            size_t m = in->closed[k] ? n : n - 1;
            for (size_t i = 0; i < n; i++)
                t[i] = L * (double)i / (double)m;
            rc = equal_chords(smooth ? spline_eval : poly_eval, smooth ? (const void *)&sc : (const void *)&sc.p, 0,
                              L, in->closed[k], n, t, out->x + 3 * out->start[k], &spread, bound, err);
        }
        free(t);
        free(sc.p.cum);
        free(sc.m2);
    }
out:
    free(nv);
    if (rc)
        tr_curve_free(out);
    return rc;
}

int tr_resample(const tr_curve *in, const size_t *n_per_comp, tr_curve *out, tr_error *err)
{
    return tr_resample_within(in, n_per_comp, 0, NULL, out, err);
}

int tr_resample_smooth(const tr_curve *in, const size_t *n_per_comp, tr_curve *out, tr_error *err)
{
    return tr_resample_within(in, n_per_comp, 1, NULL, out, err);
}

/* ----------------------------------------------------------- generators */

/* Edges longer than the rope's radius would make a polygon too coarse to
 * stand for the smooth start curve (its MinRad and struts would be the
 * polygon's, not the curve's). */
static int check_edge(double length, size_t n, size_t edges, const char *what, tr_error *err)
{
    double e = length / (double)edges;
    if (e > 1.0) {
        /* as many digits as it takes to show the edge above 1 (61
         * vertices of T(2,3) give 1.00475, which %.3g printed as "1") */
        char num[32];
        for (int p = 3; p <= 17; p++) {
            snprintf(num, sizeof num, "%.*g", p, e);
            if (strtod(num, NULL) > 1.0)
                break;
        }
        return tr_fail(err, TR_EINVAL,
                       "%s: %zu vertices give edges of %s (a length of %.6g over %zu edges), longer than "
                       "the rope radius 1; use at least %zu",
                       what, n, num, length, edges, (size_t)ceil(length) + (n - edges));
    }
    return TR_OK;
}

int tr_make_circle(tr_curve *out, double radius, size_t n, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (n < 3)
        return tr_fail(err, TR_EINVAL, "a circle needs at least 3 vertices, got %zu", n);
    /* above 1e12 the length (and every later sum) loses the rope's scale */
    if (!(radius > 0) || !(radius <= 1e12))
        return tr_fail(err, TR_EINVAL, "circle radius must be positive and at most 1e12, got %g", radius);
    int rc = tr_curve_alloc(out, 1, &n, NULL, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < n; i++) {
        double a = 2 * TR_PI * (double)i / (double)n;
        out->x[3 * i] = radius * cos(a);
        out->x[3 * i + 1] = radius * sin(a);
        out->x[3 * i + 2] = 0;
    }
    return TR_OK;
}

int tr_make_hopf(tr_curve *out, size_t n, tr_error *err)
{
    memset(out, 0, sizeof *out);
    /* Radius 3: each circle passes through the other's centre, so the two
     * come no closer than the radius, 3 > 2 rope diameters... of radius 1. */
    const double rho = 3.0;
    if (n < 3)
        return tr_fail(err, TR_EINVAL, "the hopf link needs at least 3 vertices per circle, got %zu", n);
    int rc = check_edge(2 * TR_PI * rho, n, n, "hopf link", err);
    if (rc)
        return rc;
    size_t nv[2] = {n, n};
    if ((rc = tr_curve_alloc(out, 2, nv, NULL, err)))
        return rc;
    for (size_t i = 0; i < n; i++) {
        double a = 2 * TR_PI * (double)i / (double)n;
        double *p = out->x + 3 * i, *q = out->x + 3 * (n + i);
        p[0] = rho * cos(a);
        p[1] = rho * sin(a);
        p[2] = 0;
        q[0] = rho + rho * cos(a);
        q[1] = 0;
        q[2] = rho * sin(a);
    }
    return TR_OK;
}

/* Torus knot on the torus of radii (R, r) = (1 + ratio, 1), scaled by s. */
typedef struct torus_ctx {
    double p, q, R, r, s;
} torus_ctx;

static void torus_eval(const void *vctx, double t, size_t *hint, double *out)
{
    (void)hint;
    const torus_ctx *c = vctx;
    double rad = c->R + c->r * cos(c->q * t);
    out[0] = c->s * rad * cos(c->p * t);
    out[1] = c->s * rad * sin(c->p * t);
    out[2] = -c->s * c->r * sin(c->q * t);
}

static int gcd(int a, int b)
{
    a = abs(a);
    b = abs(b);
    while (b) {
        int t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* Scale of the unit torus knot at which its radius of curvature is >= 2 and
 * points more than pi apart along the curve are >= 3 apart: a rope of radius
 * 1 around it is embedded with room to spare (2 would touch). Measured on a
 * fine sample of the smooth curve. */
static int torus_scale(torus_ctx *c, tr_error *err)
{
    const size_t M = 2048;
    double *x = malloc(3 * M * sizeof *x), *arc = malloc((M + 1) * sizeof *arc);
    if (!x || !arc) {
        free(x);
        free(arc);
        return tr_fail(err, TR_ENOMEM, "out of memory sizing a torus knot");
    }
    c->s = 1;
    for (size_t i = 0; i < M; i++)
        torus_eval(c, 2 * TR_PI * (double)i / (double)M, NULL, x + 3 * i);
    double kmax = 0;
    arc[0] = 0;
    for (size_t i = 0; i < M; i++) {
        const double *a = x + 3 * ((i + M - 1) % M), *b = x + 3 * i, *d = x + 3 * ((i + 1) % M);
        double ab = sqrt(v3_dist2(a, b)), bd = sqrt(v3_dist2(b, d)), ad = sqrt(v3_dist2(a, d));
        double e1[3], e2[3], cr[3];
        v3_sub(e1, b, a);
        v3_sub(e2, d, b);
        v3_cross(cr, e1, e2);
        kmax = fmax(kmax, 2 * v3_norm(cr) / (ab * bd * ad)); /* 1 / circumradius */
        arc[i + 1] = arc[i] + bd;
    }
    double L = arc[M];
    double s = 2 * kmax;
    for (int iter = 0; iter < 50; iter++) {
        double dmin = INFINITY;
        for (size_t i = 0; i < M; i++)
            for (size_t j = i + 1; j < M; j++) {
                double g = arc[j] - arc[i];
                if (s * fmin(g, L - g) < TR_PI)
                    continue;
                dmin = fmin(dmin, v3_dist2(x + 3 * i, x + 3 * j));
            }
        dmin = s * sqrt(dmin);
        if (dmin >= 3.0)
            break;
        s *= 3.0 / dmin * 1.001;
    }
    free(x);
    free(arc);
    c->s = s;
    return TR_OK;
}

int tr_make_torus(tr_curve *out, int p, int q, size_t n, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (abs(p) < 2 || abs(q) < 2 || abs(p) > 1000 || abs(q) > 1000)
        return tr_fail(err, TR_EINVAL, "torus knot T(%d,%d): need 2 <= |p|, |q| <= 1000", p, q);
    if (gcd(p, q) != 1)
        return tr_fail(err, TR_EINVAL, "torus knot T(%d,%d): p and q must be coprime (else it is a link)", p, q);
    if (n < 3)
        return tr_fail(err, TR_EINVAL, "a torus knot needs at least 3 vertices, got %zu", n);
    /* The |p| strands cross each meridian disk 2 r sin(pi/|p|) apart and the
     * |q| passes along the inner equator 2 (R - r) sin(pi/|q|) apart; R is
     * chosen to make the two equal, so neither direction is crowded. */
    torus_ctx c = {p, q, 0, 1, 1};
    c.R = 1 + fmax(0.5, sin(TR_PI / abs(p)) / sin(TR_PI / abs(q)));
    int rc = torus_scale(&c, err);
    if (rc)
        return rc;
    /* length of the scaled curve, for the coarseness check */
    double L = 0, prev[3], cur[3];
    const size_t M = 8192;
    torus_eval(&c, 0, NULL, prev);
    for (size_t i = 1; i <= M; i++) {
        torus_eval(&c, 2 * TR_PI * (double)i / (double)M, NULL, cur);
        L += sqrt(v3_dist2(prev, cur));
        memcpy(prev, cur, sizeof cur);
    }
    char what[64];
    snprintf(what, sizeof what, "torus knot T(%d,%d)", p, q);
    if ((rc = check_edge(L, n, n, what, err)))
        return rc;
    if ((rc = tr_curve_alloc(out, 1, &n, NULL, err)))
        return rc;
    double *t = malloc(n * sizeof *t), spread;
    if (!t) {
        tr_curve_free(out);
        return tr_fail(err, TR_ENOMEM, "out of memory making a torus knot");
    }
    for (size_t i = 0; i < n; i++)
        t[i] = 2 * TR_PI * (double)i / (double)n;
    rc = equal_chords(torus_eval, &c, 0, 2 * TR_PI, 1, n, t, out->x, &spread, NULL, err);
    free(t);
    if (rc)
        tr_curve_free(out);
    return rc;
}

/* One rope of the clasp, parametrised by arclength: a leg from the wall down
 * (or up) to the arch, a half circle of radius 3, and a leg back to the wall.
 * sign = +1: rope A in the xz plane, arch opening upwards, walls z = +h;
 * sign = -1: rope B in the yz plane, arch opening downwards, walls z = -h. */
typedef struct clasp_ctx {
    double h, leg, T;
    int sign;
} clasp_ctx;

#define CLASP_RADIUS 3.0
#define CLASP_CENTRE 1.5 /* arch centres at z = +-1.5: each arch's tip at the other's centre */

static void clasp_eval(const void *vctx, double s, size_t *hint, double *out)
{
    (void)hint;
    const clasp_ctx *c = vctx;
    double u, v, w; /* in-plane coordinate, z for rope A */
    if (s <= c->leg) {
        u = -CLASP_RADIUS;
        w = c->h - s;
    } else if (s >= c->T - c->leg) {
        u = CLASP_RADIUS;
        w = c->h - (c->T - s); /* exactly h at s = T: the end stays on its wall */
    } else {
        double phi = TR_PI + (s - c->leg) / CLASP_RADIUS;
        u = CLASP_RADIUS * cos(phi);
        w = CLASP_CENTRE + CLASP_RADIUS * sin(phi);
    }
    v = 0;
    if (c->sign > 0) {
        out[0] = u;
        out[1] = v;
        out[2] = w;
    } else {
        out[0] = v;
        out[1] = u;
        out[2] = -w;
    }
}

int tr_make_clasp(tr_curve *out, size_t n, double h, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (!isfinite(h) || h < CLASP_CENTRE)
        return tr_fail(err, TR_EINVAL, "clasp walls at z = +-%g: the height must be at least %g", h, CLASP_CENTRE);
    if (n < 3)
        return tr_fail(err, TR_EINVAL, "a clasp rope needs at least 3 vertices, got %zu", n);
    clasp_ctx ca = {h, h - CLASP_CENTRE, 0, +1};
    ca.T = 2 * ca.leg + TR_PI * CLASP_RADIUS;
    clasp_ctx cb = ca;
    cb.sign = -1;
    int rc = check_edge(ca.T, n, n - 1, "clasp", err);
    if (rc)
        return rc;
    size_t nv[2] = {n, n};
    unsigned char closed[2] = {0, 0};
    if ((rc = tr_curve_alloc(out, 2, nv, closed, err)))
        return rc;
    tr_constraint wa = {.kind = TR_CST_PLANE, .id = 1, .u = {0, 0, 1}, .d = h};
    tr_constraint wb = {.kind = TR_CST_PLANE, .id = 2, .u = {0, 0, 1}, .d = -h};
    double *t = malloc(n * sizeof *t), spread;
    if (!t || tr_curve_add_constraint(out, &wa, err) < 0 || tr_curve_add_constraint(out, &wb, err) < 0) {
        free(t);
        tr_curve_free(out);
        return tr_fail(err, TR_ENOMEM, "out of memory making a clasp");
    }
    for (int k = 0; k < 2 && !rc; k++) {
        for (size_t i = 0; i < n; i++)
            t[i] = ca.T * (double)i / (double)(n - 1);
        rc = equal_chords(clasp_eval, k ? &cb : &ca, 0, ca.T, 0, n, t, out->x + 3 * out->start[k], &spread, NULL, err);
        out->vcst[out->start[k]] = k;
        out->vcst[out->start[k + 1] - 1] = k;
    }
    free(t);
    if (rc)
        tr_curve_free(out);
    return rc;
}
