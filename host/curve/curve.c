/* This file contains the curve container: allocation, copies, constraints, component lengths
 * (curve.h). */
#include "curve/curve.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/compensated_sum.h"
#include "util/vec3.h"

int tr_curve_alloc(tr_curve *c, int ncomp, const size_t *nv, const unsigned char *closed,
                   tr_error *err)
{
    memset(c, 0, sizeof *c);
    if (ncomp <= 0)
        return tr_fail(err, TR_EINVAL, "a curve needs at least one component");
    size_t total = 0;
    for (int k = 0; k < ncomp; k++) {
        /* 3 doubles per vertex must fit in size_t: refuse before any wrap */
        if (nv[k] > SIZE_MAX / (3 * sizeof(double)) - total)
            return tr_fail(err, TR_EINVAL, "curve of more than %zu vertices is too large",
                           SIZE_MAX / (3 * sizeof(double)));
        total += nv[k];
    }
    c->ncomp = ncomp;
    c->nv = total;
    c->start = malloc((size_t)(ncomp + 1) * sizeof *c->start);
    c->closed = malloc((size_t)ncomp);
    c->x = calloc(total ? 3 * total : 3, sizeof *c->x);
    if (!c->start || !c->closed || !c->x) {
        tr_curve_free(c);
        return tr_fail(err, TR_ENOMEM, "out of memory allocating a curve of %zu vertices", total);
    }
    c->start[0] = 0;
    for (int k = 0; k < ncomp; k++) {
        c->start[k + 1] = c->start[k] + nv[k];
        c->closed[k] = closed ? (closed[k] != 0) : 1;
    }
    return TR_OK;
}

void tr_curve_free(tr_curve *c)
{
    if (!c)
        return;
    free(c->x);
    free(c->start);
    free(c->closed);
    free(c->vcst);
    free(c->cst);
    free(c->lo);
    memset(c, 0, sizeof *c);
}

int tr_curve_want_lo(tr_curve *c, tr_error *err)
{
    if (c->lo)
        return TR_OK;
    c->lo = calloc(c->nv ? 3 * c->nv : 3, sizeof *c->lo);
    return c->lo ? TR_OK : tr_fail(err, TR_ENOMEM, "out of memory (a curve's low parts)");
}

void tr_curve_drop_lo(tr_curve *c)
{
    free(c->lo);
    c->lo = NULL;
}

void tr_split_long_double(long double v, double *hi, double *lo)
{
    *hi = (double)v;
    *lo = (double)(v - (long double)*hi);
}

void tr_curve_scale_by(tr_curve *c, double f)
{
    if (!c->lo) {
        for (size_t i = 0; i < 3 * c->nv; i++)
            c->x[i] *= f;
        return;
    }
    for (size_t i = 0; i < 3 * c->nv; i++)
        tr_split_long_double(((long double)c->x[i] + c->lo[i]) * f, &c->x[i], &c->lo[i]);
}

int tr_curve_component(tr_curve *one, const tr_curve *c, int k, tr_error *err)
{
    size_t nv = tr_comp_nv(c, k);
    unsigned char closed = c->closed[k] ? 1 : 0;
    int rc = tr_curve_alloc(one, 1, &nv, &closed, err);
    if (rc)
        return rc;
    memcpy(one->x, c->x + 3 * c->start[k], 3 * nv * sizeof *one->x);
    if (c->lo) {
        if ((rc = tr_curve_want_lo(one, err))) {
            tr_curve_free(one);
            return rc;
        }
        memcpy(one->lo, c->lo + 3 * c->start[k], 3 * nv * sizeof *one->lo);
    }
    return TR_OK;
}

int tr_curve_copy(tr_curve *dst, const tr_curve *src, tr_error *err)
{
    memset(dst, 0, sizeof *dst); /* a failed copy leaves a curve that tr_curve_free accepts */
    size_t *nv = malloc((size_t)src->ncomp * sizeof *nv);
    if (!nv)
        return tr_fail(err, TR_ENOMEM, "out of memory copying a curve");
    for (int k = 0; k < src->ncomp; k++)
        nv[k] = tr_comp_nv(src, k);
    int rc = tr_curve_alloc(dst, src->ncomp, nv, src->closed, err);
    free(nv);
    if (rc)
        return rc;
    memcpy(dst->x, src->x, 3 * src->nv * sizeof *src->x);
    if (src->ncst > 0) {
        dst->cst = malloc((size_t)src->ncst * sizeof *dst->cst);
        dst->vcst = malloc(src->nv * sizeof *dst->vcst);
        if (!dst->cst || !dst->vcst) {
            tr_curve_free(dst);
            return tr_fail(err, TR_ENOMEM, "out of memory copying constraints");
        }
        memcpy(dst->cst, src->cst, (size_t)src->ncst * sizeof *dst->cst);
        memcpy(dst->vcst, src->vcst, src->nv * sizeof *dst->vcst);
        dst->ncst = src->ncst;
    }
    if (src->lo) {
        if ((rc = tr_curve_want_lo(dst, err))) {
            tr_curve_free(dst);
            return rc;
        }
        memcpy(dst->lo, src->lo, 3 * src->nv * sizeof *src->lo);
    }
    return TR_OK;
}

int tr_curve_add_constraint(tr_curve *c, const tr_constraint *k, tr_error *err)
{
    if (!c->vcst) {
        c->vcst = malloc((c->nv ? c->nv : 1) * sizeof *c->vcst);
        if (!c->vcst)
            return tr_fail(err, TR_ENOMEM, "out of memory adding a constraint");
        for (size_t i = 0; i < c->nv; i++)
            c->vcst[i] = -1;
    }
    tr_constraint *grown = realloc(c->cst, (size_t)(c->ncst + 1) * sizeof *grown);
    if (!grown)
        return tr_fail(err, TR_ENOMEM, "out of memory adding a constraint");
    c->cst = grown;
    c->cst[c->ncst] = *k;
    return c->ncst++;
}

int tr_curve_comp_of(const tr_curve *c, size_t i)
{
    int lo = 0, hi = c->ncomp - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (c->start[mid] <= i)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

void tr_constraint_project(const tr_constraint *k, double *x)
{
    switch (k->kind) {
    case TR_CST_FIXED:
        x[0] = k->p[0];
        x[1] = k->p[1];
        x[2] = k->p[2];
        break;
    case TR_CST_LINE: {
        double t = (x[0] - k->p[0]) * k->u[0] + (x[1] - k->p[1]) * k->u[1] + (x[2] - k->p[2]) * k->u[2];
        for (int a = 0; a < 3; a++)
            x[a] = k->p[a] + t * k->u[a];
        break;
    }
    case TR_CST_PLANE: {
        double s = x[0] * k->u[0] + x[1] * k->u[1] + x[2] * k->u[2] - k->d;
        for (int a = 0; a < 3; a++)
            x[a] -= s * k->u[a];
        break;
    }
    }
}

void tr_constraint_project_motion(const tr_constraint *k, double *v)
{
    double d = v[0] * k->u[0] + v[1] * k->u[1] + v[2] * k->u[2];
    switch (k->kind) {
    case TR_CST_PLANE:
        for (int a = 0; a < 3; a++)
            v[a] -= d * k->u[a];
        break;
    case TR_CST_LINE:
        for (int a = 0; a < 3; a++)
            v[a] = d * k->u[a];
        break;
    default:
        v[0] = v[1] = v[2] = 0.0;
    }
}

double tr_constraint_violation(const tr_constraint *k, const double *x)
{
    double y[3] = {x[0], x[1], x[2]};
    tr_constraint_project(k, y);
    return sqrt(v3_dist2(x, y));
}

double tr_comp_length(const tr_curve *c, int k)
{
    size_t s = c->start[k], n = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
    tr_csum sum = {0.0, 0.0};
    for (size_t j = 0; j < ne; j++) {
        double e[3];
        tr_curve_edge(c, s + j, s + (j + 1) % n, e);
        tr_csum_add(&sum, v3_norm(e));
    }
    return tr_csum_value(&sum);
}

double tr_curve_length(const tr_curve *c)
{
    double sum = 0.0;
    for (int k = 0; k < c->ncomp; k++)
        sum += tr_comp_length(c, k);
    return sum;
}

/* tr_curve_scale_exponent's e for a largest magnitude m. */
static int exponent_for(double m)
{
    if (!(m > 0.0) || !isfinite(m))
        return 0;
    int e;
    (void)frexp(m, &e); /* m = f 2^e, f in [0.5, 1) */
    if (e > -TR_CURVE_SAFE_EXP && e <= TR_CURVE_SAFE_EXP)
        return 0;
    return e;
}

/* The constraints' largest magnitude, in the frame translated by centre. */
static double constraint_max(const tr_curve *c, const double *centre)
{
    double m = 0.0;
    for (int q = 0; q < c->ncst; q++) {
        const tr_constraint *k = &c->cst[q];
        double nc = k->kind == TR_CST_PLANE ? k->u[0] * centre[0] + k->u[1] * centre[1] + k->u[2] * centre[2] : 0.0;
        m = fmax(m, fabs(k->d - nc));
        for (int a = 0; k->kind != TR_CST_PLANE && a < 3; a++)
            m = fmax(m, fabs(k->p[a] - centre[a]));
    }
    return m;
}

int tr_curve_scale_exponent(const tr_curve *c)
{
    static const double zero[3] = {0.0, 0.0, 0.0};
    double m = constraint_max(c, zero);
    for (size_t i = 0; i < 3 * c->nv; i++)
        m = fmax(m, fabs(c->x[i]));
    return exponent_for(m);
}

void tr_curve_frame_of(const tr_curve *c, tr_curve_frame *f)
{
    memset(f, 0, sizeof *f);
    if (!c || !c->x || c->nv == 0)
        return;
    for (int a = 0; a < 3; a++) {
        double lo = c->x[a], hi = c->x[a];
        for (size_t i = 1; i < c->nv; i++) {
            lo = fmin(lo, c->x[3 * i + a]);
            hi = fmax(hi, c->x[3 * i + a]);
        }
        /* lo and hi of one sign: hi - lo cannot overflow */
        if (lo > 0.0 || hi < 0.0)
            f->centre[a] = lo + 0.5 * (hi - lo);
    }
    double m = constraint_max(c, f->centre);
    for (size_t i = 0; i < c->nv; i++)
        for (int a = 0; a < 3; a++)
            m = fmax(m, fabs(c->x[3 * i + a] - f->centre[a]));
    f->e = exponent_for(m);
}

int tr_curve_frame_is_identity(const tr_curve_frame *f)
{
    return f->e == 0 && f->centre[0] == 0.0 && f->centre[1] == 0.0 && f->centre[2] == 0.0;
}

int tr_curve_to_frame(tr_curve *dst, const tr_curve *c, const tr_curve_frame *f, tr_error *err)
{
    int rc = tr_curve_copy(dst, c, err);
    if (rc)
        return rc;
    /* with low parts, the translation's rounding goes into them */
    for (size_t i = 0; i < dst->nv; i++)
        for (int a = 0; a < 3; a++) {
            size_t q = 3 * i + (size_t)a;
            if (dst->lo)
                tr_split_long_double((long double)dst->x[q] - f->centre[a] + dst->lo[q], &dst->x[q], &dst->lo[q]);
            else
                dst->x[q] -= f->centre[a];
        }
    for (int q = 0; q < dst->ncst; q++) {
        tr_constraint *k = &dst->cst[q];
        if (k->kind == TR_CST_PLANE)
            k->d -= k->u[0] * f->centre[0] + k->u[1] * f->centre[1] + k->u[2] * f->centre[2];
        else
            for (int a = 0; a < 3; a++)
                k->p[a] -= f->centre[a];
    }
    if (f->e)
        tr_curve_scale_pow2(dst, -f->e);
    return TR_OK;
}

int tr_curve_oracle_frame(const tr_curve *c, tr_curve_frame *f, tr_curve *moved, const tr_curve **use,
                          tr_error *err)
{
    memset(moved, 0, sizeof *moved);
    *use = c;
    int rc = tr_curve_check_resolution(c, NULL, err);
    if (rc)
        return rc;
    tr_curve_frame_of(c, f);
    if (tr_curve_frame_is_identity(f))
        return TR_OK;
    if ((rc = tr_curve_to_frame(moved, c, f, err)))
        return rc;
    *use = moved;
    return TR_OK;
}

double tr_double_step(double v)
{
    v = fabs(v);
    if (!isfinite(v))
        return INFINITY;
    return nextafter(v, INFINITY) - v;
}

int tr_curve_check_resolution(const tr_curve *c, size_t *vertex, tr_error *err)
{
    if (vertex)
        *vertex = SIZE_MAX;
    double m = 0.0;
    size_t im = 0;
    for (size_t i = 0; i < 3 * c->nv; i++)
        if (fabs(c->x[i]) > m) {
            m = fabs(c->x[i]);
            im = i / 3;
        }
    if (!isfinite(m))
        return TR_OK; /* not finite: the oracles' own check says which vertex */
    if (m > 0.0 && m < DBL_MIN) {
        if (vertex)
            *vertex = im;
        int k = tr_curve_comp_of(c, im);
        return tr_fail(err, TR_EGEOMETRY,
                       "every coordinate is subnormal (the largest, %.3g at vertex %zu of component %d, is below "
                       "%.3g): such numbers keep fewer digits than a double has, and 1 / the curve's thickness "
                       "would be beyond the largest double; scale the curve up",
                       m, im - c->start[k], k, DBL_MIN);
    }
    for (int k = 0; k < c->ncomp; k++) {
        size_t s = c->start[k], n = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
        for (size_t j = 0; j < ne; j++) {
            const double *a = c->x + 3 * (s + j), *b = c->x + 3 * (s + (j + 1) % n);
            double q = 0.0, hmax = 0.0;
            for (int d = 0; d < 3; d++) {
                q = fmax(q, fmax(fabs(a[d]), fabs(b[d])));
                hmax = fmax(hmax, fabs(b[d] - a[d]));
            }
            /* the common case at a glance: the step at q is at most
             * q 2^-52, and the edge at least its largest component */
            if (q >= 0x1p-960 && hmax >= q * 0x1p-42)
                continue;
            /* hypot: the length of a subnormal edge does not underflow */
            double h = hypot(hypot(b[0] - a[0], b[1] - a[1]), b[2] - a[2]);
            double step = tr_double_step(q);
            if (h == 0.0 || !(h < TR_CURVE_MIN_STEPS * step))
                continue;
            size_t jv = (j + 1) % n;
            if (vertex)
                *vertex = s + jv;
            char from[48] = "the previous vertex";
            if (jv == 0)
                snprintf(from, sizeof from, "the last, vertex %zu", n - 1);
            int sub = q < DBL_MIN;
            return tr_fail(err, TR_EGEOMETRY,
                           "vertex %zu of component %d is %.3g from %s, less than %.0f steps of the doubles at "
                           "its coordinates (%.3g apart near %.3g): %s, the numbers cannot hold the curve's "
                           "shape; %s",
                           jv, k, h, from, TR_CURVE_MIN_STEPS, step, q,
                           sub ? "in the subnormal range" : "this far from the origin for its size",
                           sub ? "scale the curve up" : "move the curve nearer the origin (ropelength does not change)");
        }
    }
    return TR_OK;
}

void tr_curve_scale_pow2(tr_curve *c, int e)
{
    for (size_t i = 0; i < 3 * c->nv; i++) {
        c->x[i] = ldexp(c->x[i], e);
        if (c->lo)
            c->lo[i] = ldexp(c->lo[i], e);
    }
    for (int q = 0; q < c->ncst; q++) {
        for (int a = 0; a < 3; a++)
            c->cst[q].p[a] = ldexp(c->cst[q].p[a], e);
        c->cst[q].d = ldexp(c->cst[q].d, e);
    }
}
