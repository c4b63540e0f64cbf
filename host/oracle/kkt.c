/* This file contains the KKT certificate: the residual of a curve's tension against struts and
 * MinRad rows (kkt.h). */
#include "oracle/kkt.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/neighbour_search.h"
#include "oracle/rowchol.h"
#include "geometry/struts.h"
#include "segment_distance.h"
#include "oracle/thickness.h"
#include "geometry/turning_angle.h"
#include "util/vec3.h"

#define NONE SIZE_MAX

/* Regularisation of the factor, relative to unit rows: far below any
 * curvature of the least squares that matters, far above rounding. */
#define KKT_BETA 1e-10

/* Rows dropped from the free set are pinned at 0 in its factor (one solve
 * each) up to this many, then the factor is rebuilt. */
#define KKT_MAX_PINS 256

enum { ROW_EDGE, ROW_MINRAD, ROW_STRUT };

/* One constraint row: its gradient touches at most four vertices. */
typedef struct row {
    int kind, comp, nvx;
    size_t v[4];
    double d[4][3]; /* dC/dx_v, already projected onto the allowed motion of v */
    double debar;   /* dC/debar_comp */
} row;

typedef struct sys {
    const tr_curve *c;
    size_t nv, nr, cap;
    int ncomp;
    size_t *next, *prev;
    int *comp;
    double *ne; /* edges per component (the ebar metric weight) */
    int *gap;
    row *r;
    double radius, band;
    int oom;
} sys;

void tr_kkt_params_default(tr_kkt_params *p)
{
    memset(p, 0, sizeof *p);
    p->radius = 0.0;
    p->band = TR_KKT_DEFAULT_BAND;
    p->max_outer = 100;
    p->opt_tol = 1e-9;
}

static void project(const tr_curve *c, size_t i, double *v)
{
    if (c->vcst && c->vcst[i] >= 0)
        tr_constraint_project_motion(&c->cst[c->vcst[i]], v);
}

static row *push(sys *s)
{
    if (s->nr == s->cap) {
        size_t nc = s->cap ? 2 * s->cap : 1024;
        row *g = realloc(s->r, nc * sizeof *g);
        if (!g) {
            s->oom = 1;
            return NULL;
        }
        s->r = g;
        s->cap = nc;
    }
    row *q = &s->r[s->nr++];
    memset(q, 0, sizeof *q);
    return q;
}

static void add_vertex(const sys *s, row *q, size_t v, const double *d)
{
    memcpy(q->d[q->nvx], d, 3 * sizeof *d);
    project(s->c, v, q->d[q->nvx]);
    q->v[q->nvx++] = v;
}

typedef struct strut_ctx {
    sys *s;
    const tr_nsearch *ns;
} strut_ctx;

static int strut_pair(void *vc, size_t ei, size_t ej, double *cutoff)
{
    (void)cutoff;
    strut_ctx *sc = vc;
    sys *s = sc->s;
    const tr_nsearch *ns = sc->ns;
    int k = ns->ecomp[ei];
    if (tr_nsearch_excluded(ns, ei, ej, (size_t)s->gap[k]))
        return 0;
    size_t a = ns->ea[ei], an = ns->eb[ei], b = ns->ea[ej], bn = ns->eb[ej];
    const double *x = s->c->x;
    double sp, tp;
    double d = tr_segment_distance(x + 3 * a, x + 3 * an, x + 3 * b, x + 3 * bn, &sp, &tp);
    if (!(d - 2.0 * s->radius < s->band * 2.0 * s->radius) || !(d > 0))
        return 0;
    row *q = push(s);
    if (!q)
        return 1;
    q->kind = ROW_STRUT;
    q->comp = k;
    double cn[3], g[4][3];
    for (int m = 0; m < 3; m++)
        cn[m] = x[3 * a + m] + sp * (x[3 * an + m] - x[3 * a + m]) - x[3 * b + m] -
                tp * (x[3 * bn + m] - x[3 * b + m]);
    tr_strut_gradient(cn, sp, tp, d, 1.0, g);
    add_vertex(s, q, a, g[0]);
    add_vertex(s, q, an, g[1]);
    add_vertex(s, q, b, g[2]);
    add_vertex(s, q, bn, g[3]);
    return 0;
}

/* Every row: the edges, the MinRad rows and the struts within the band. */
static int build_rows(sys *s, tr_error *err)
{
    const tr_curve *c = s->c;
    const double *x = c->x;
    double *ebar = calloc((size_t)s->ncomp, sizeof *ebar);
    if (!ebar)
        return tr_fail(err, TR_ENOMEM, "out of memory (KKT rows)");
    for (size_t a = 0; a < s->nv; a++)
        if (s->next[a] != NONE)
            ebar[s->comp[a]] += sqrt(v3_dist2(x + 3 * s->next[a], x + 3 * a));
    for (int k = 0; k < s->ncomp; k++) {
        ebar[k] /= s->ne[k] > 0 ? s->ne[k] : 1.0;
        s->gap[k] = tr_exclusion_gap(s->radius, ebar[k]);
    }
    for (size_t a = 0; a < s->nv && !s->oom; a++) {
        if (s->next[a] == NONE)
            continue;
        row *q = push(s);
        if (!q)
            break;
        double u[3], mu[3];
        v3_sub(u, x + 3 * s->next[a], x + 3 * a);
        v3_scale(u, 1.0 / v3_norm(u), u);
        v3_scale(mu, -1.0, u);
        q->kind = ROW_EDGE;
        q->comp = s->comp[a];
        add_vertex(s, q, a, mu);
        add_vertex(s, q, s->next[a], u);
        q->debar = -1.0;
    }
    for (size_t i = 0; i < s->nv && !s->oom; i++) {
        size_t ip = s->prev[i], in = s->next[i];
        if (ip == NONE || in == NONE)
            continue;
        double p[3], q[3], dtp[3], dtq[3], lp, lq;
        double t = tr_vertex_turning(x, ip, i, in, p, q, &lp, &lq, dtp, dtq), r2 = 2.0 * s->radius;
        for (int side = 0; side < 2; side++) {
            double l = side ? lq : lp;
            if (t == 0.0 || !((l - r2 * t) / l < s->band))
                continue;
            /* C = |p| - 2 r t (side 0) or |q| - 2 r t (side 1), in p and q */
            double gp[3], gq[3], gi[3], m[3];
            for (int d = 0; d < 3; d++) {
                gp[d] = (side ? 0.0 : p[d] / lp) - r2 * dtp[d];
                gq[d] = (side ? q[d] / lq : 0.0) - r2 * dtq[d];
                gi[d] = gp[d] - gq[d];
            }
            row *w = push(s);
            if (!w)
                break;
            w->kind = ROW_MINRAD;
            w->comp = s->comp[i];
            v3_scale(m, -1.0, gp);
            add_vertex(s, w, ip, m);
            add_vertex(s, w, i, gi);
            add_vertex(s, w, in, gq);
        }
    }
    free(ebar);
    if (s->oom)
        return tr_fail(err, TR_ENOMEM, "out of memory (KKT rows)");
    tr_nsearch ns;
    int rc = tr_nsearch_build(&ns, c, err);
    if (rc)
        return rc;
    int gmin = s->gap[0];
    for (int k = 1; k < s->ncomp; k++)
        gmin = s->gap[k] < gmin ? s->gap[k] : gmin;
    double cut = 2.0 * s->radius * (1.0 + s->band);
    strut_ctx sc = {.s = s, .ns = &ns};
    tr_nsearch_pairs(&ns, &cut, (size_t)gmin, 0, strut_pair, &sc);
    tr_nsearch_free(&ns);
    if (s->oom)
        return tr_fail(err, TR_ENOMEM, "out of memory (KKT rows)");
    return TR_OK;
}

/* v = W^-1 J^T y over the rows with use[r] (NULL: all): the x part (rows are
 * projected already), the ebar part divided by its weight ne_k. */
static void apply_JT(const sys *s, const double *y, const unsigned char *use, double *vx, double *vb)
{
    memset(vx, 0, 3 * s->nv * sizeof *vx);
    memset(vb, 0, (size_t)s->ncomp * sizeof *vb);
    for (size_t r = 0; r < s->nr; r++) {
        if ((use && !use[r]) || y[r] == 0.0)
            continue;
        const row *q = &s->r[r];
        for (int m = 0; m < q->nvx; m++)
            v3_axpy(vx + 3 * q->v[m], y[r], q->d[m]);
        vb[q->comp] += y[r] * q->debar;
    }
    for (int k = 0; k < s->ncomp; k++)
        vb[k] /= s->ne[k];
}

/* out_r = J_r . (vx, vb) for the rows with use[r], 0 elsewhere. */
static void apply_J(const sys *s, const double *vx, const double *vb, const unsigned char *use, double *out)
{
    for (size_t r = 0; r < s->nr; r++) {
        out[r] = 0.0;
        if (use && !use[r])
            continue;
        const row *q = &s->r[r];
        double a = q->debar * vb[q->comp];
        for (int m = 0; m < q->nvx; m++)
            a += v3_dot(q->d[m], vx + 3 * q->v[m]);
        out[r] = a;
    }
}

typedef struct work {
    double *g;        /* 3 nv: projected tension (the length gradient, negated) */
    double *vx, *vb;  /* W^-1 J^T of something */
    double *rx, *rb;  /* resolved force, ebar part already weighted */
    double *w, *p, *q, *z, *yn;
    double *scale;    /* 1 / |row| before the rows were normalised */
    unsigned char *in; /* row in the free set */
    size_t *fidx, *fpos, nf, *rowptr, *col; /* the factored free rows as a sparse matrix */
    double *val, *uval;
    int *ucol;
} work;

/* Resolved force of y: rx = g - J^T y, rb = -(J^T y)_ebar / ne; returns |.|^2
 * in the W^-1 metric, and (if w != NULL) the dual w = J (rx, rb). */
static double resolve(const sys *s, work *k, const double *y, double *w)
{
    apply_JT(s, y, NULL, k->vx, k->vb);
    double n2 = 0.0;
    for (size_t i = 0; i < 3 * s->nv; i++) {
        k->rx[i] = k->g[i] - k->vx[i];
        n2 += k->rx[i] * k->rx[i];
    }
    for (int c = 0; c < s->ncomp; c++) {
        k->rb[c] = -k->vb[c];
        n2 += k->rb[c] * k->rb[c] * s->ne[c];
    }
    if (w)
        apply_J(s, k->rx, k->rb, NULL, w);
    return n2;
}

/* |r|^2 at y + alpha (yn - y) on the free rows, the Lawson-Hanson walk's end. */
static double resolve_walk(const sys *s, work *k, const double *y, double alpha)
{
    for (size_t r = 0; r < s->nr; r++)
        k->p[r] = k->in[r] ? y[r] + alpha * (k->yn[r] - y[r]) : y[r];
    return resolve(s, k, k->p, NULL);
}

/* The sparse factor of the free set F (the rows with in[r]) as it stands:
 * fidx lists them, fpos maps a row to its place in the factor. */
static int factor_free(const sys *s, work *k, tr_rowchol **f, tr_error *err)
{
    size_t nr = s->nr, nf = 0, nz = 0;
    for (size_t r = 0; r < nr; r++) {
        k->fpos[r] = NONE;
        if (k->in[r]) {
            k->fpos[r] = nf;
            k->fidx[nf++] = r;
        }
    }
    k->nf = nf;
    k->rowptr[0] = 0;
    for (size_t i = 0; i < nf; i++) {
        const row *q = &s->r[k->fidx[i]];
        for (int m = 0; m < q->nvx; m++)
            for (int d = 0; d < 3; d++)
                if (q->d[m][d] != 0.0) {
                    k->col[nz] = 3 * q->v[m] + (size_t)d;
                    k->val[nz++] = q->d[m][d];
                }
        k->rowptr[i + 1] = nz;
        k->ucol[i] = q->comp;
        k->uval[i] = q->debar / sqrt(s->ne[q->comp]);
    }
    tr_rowsys a = {.nr = nf, .ncols = 3 * s->nv, .rowptr = k->rowptr, .col = k->col, .val = k->val,
                   .nu = s->ncomp, .ucol = k->ucol, .uval = k->uval};
    tr_rowchol_free(*f);
    *f = NULL;
    return tr_rowchol_factor(f, &a, KKT_BETA, err);
}

/* Least squares on the free set, from y (warm start): proximal-point
 * iterations z += (J_F W^-1 J_F^T + beta I)^-1 J_F r(z) with the factor of
 * factor_free; rows dropped from F since then are pinned at 0 in it
 * (rowchol.h). beta makes the factor exist although the struts of a tight
 * knot are dependent; the iteration removes its bias on every direction
 * the rows can resolve. */
static int ls_free(const sys *s, work *k, tr_rowchol *f, const double *y, double *z, int *solves, tr_error *err)
{
    size_t nr = s->nr, nf = k->nf;
    int rc = TR_OK;
    memcpy(z, y, nr * sizeof *z);
    double n2 = resolve(s, k, z, k->w);
    for (int it = 0; it < 100; it++) {
        for (size_t i = 0; i < nf; i++)
            k->q[i] = k->in[k->fidx[i]] ? k->w[k->fidx[i]] : 0.0;
        if ((rc = tr_rowchol_solve(f, k->q, k->q, err)))
            break;
        ++*solves;
        memcpy(k->p, z, nr * sizeof *z);
        double dz2 = 0.0, z2 = 0.0;
        for (size_t i = 0; i < nf; i++) {
            if (!k->in[k->fidx[i]])
                continue;
            k->p[k->fidx[i]] += k->q[i];
            dz2 += k->q[i] * k->q[i];
            z2 += z[k->fidx[i]] * z[k->fidx[i]];
        }
        double n2new = resolve(s, k, k->p, k->w);
        if (!(n2new < n2))
            break;
        memcpy(z, k->p, nr * sizeof *z);
        int small = n2 - n2new <= 1e-15 * n2 || dz2 <= 1e-28 * (1.0 + z2);
        n2 = n2new;
        if (small)
            break;
    }
    return rc;
}

static int topology(sys *s, tr_error *err)
{
    const tr_curve *c = s->c;
    s->next = malloc(s->nv * sizeof *s->next);
    s->prev = malloc(s->nv * sizeof *s->prev);
    s->comp = malloc(s->nv * sizeof *s->comp);
    s->ne = malloc((size_t)s->ncomp * sizeof *s->ne);
    s->gap = malloc((size_t)s->ncomp * sizeof *s->gap);
    if (!s->next || !s->prev || !s->comp || !s->ne || !s->gap)
        return tr_fail(err, TR_ENOMEM, "out of memory (KKT topology)");
    for (int k = 0; k < s->ncomp; k++) {
        size_t b = c->start[k], e = c->start[k + 1];
        s->ne[k] = (double)tr_comp_ne(c, k);
        if (s->ne[k] < 1.0)
            return tr_fail(err, TR_EGEOMETRY, "component %d has no edge", k + 1);
        for (size_t i = b; i < e; i++) {
            s->comp[i] = k;
            s->next[i] = i + 1 < e ? i + 1 : (c->closed[k] ? b : NONE);
            s->prev[i] = i > b ? i - 1 : (c->closed[k] ? e - 1 : NONE);
        }
    }
    return TR_OK;
}

static void sys_free(sys *s, work *k)
{
    free(s->next);
    free(s->prev);
    free(s->comp);
    free(s->ne);
    free(s->gap);
    free(s->r);
    free(k->g);
    free(k->vx);
    free(k->vb);
    free(k->rx);
    free(k->rb);
    free(k->w);
    free(k->p);
    free(k->q);
    free(k->z);
    free(k->scale);
    free(k->yn);
    free(k->in);
    free(k->fidx);
    free(k->fpos);
    free(k->rowptr);
    free(k->col);
    free(k->val);
    free(k->uval);
    free(k->ucol);
}


/* tr_kkt_certify_forces in the curve's own frame. */
static int certify_frame(const tr_curve *c, const tr_kkt_params *prm, tr_kkt *out, double *tension,
                         double *unresolved, tr_error *err)
{
    tr_kkt_params dp;
    if (!prm) {
        tr_kkt_params_default(&dp);
        prm = &dp;
    }
    memset(out, 0, sizeof *out);
    if (!(prm->band >= 0.0) || prm->max_outer < 1 || !(prm->opt_tol > 0.0))
        return tr_fail(err, TR_EINVAL, "KKT certificate: bad parameters");
    sys s = {.c = c, .nv = c->nv, .ncomp = c->ncomp, .band = prm->band};
    work k = {0};
    double *y = NULL;
    tr_rowchol *fac = NULL;
    int rc = TR_OK;
    s.radius = prm->radius;
    if (!(s.radius > 0.0)) {
        tr_thickness th;
        if ((rc = tr_thickness_measure(c, NULL, &th, NULL, err)))
            return rc;
        s.radius = th.thickness;
        if (!(s.radius > 0.0) || !isfinite(s.radius))
            return tr_fail(err, TR_EGEOMETRY, "KKT certificate: the curve has no finite thickness");
    }
    out->radius = s.radius;
    if ((rc = topology(&s, err)) || (rc = build_rows(&s, err)))
        goto done;
    size_t nx = 3 * s.nv, nr = s.nr;
    k.g = calloc(nx, sizeof *k.g);
    k.vx = malloc(nx * sizeof *k.vx);
    k.rx = malloc(nx * sizeof *k.rx);
    k.vb = malloc((size_t)s.ncomp * sizeof *k.vb);
    k.rb = malloc((size_t)s.ncomp * sizeof *k.rb);
    k.w = malloc((nr + 1) * sizeof *k.w);
    k.p = malloc((nr + 1) * sizeof *k.p);
    k.q = malloc((nr + 1) * sizeof *k.q);
    k.z = malloc((nr + 1) * sizeof *k.z);
    k.scale = malloc((nr + 1) * sizeof *k.scale);
    k.yn = malloc((nr + 1) * sizeof *k.yn);
    k.in = malloc(nr + 1);
    k.fidx = malloc((nr + 1) * sizeof *k.fidx);
    k.fpos = malloc((nr + 1) * sizeof *k.fpos);
    k.rowptr = malloc((nr + 1) * sizeof *k.rowptr);
    k.col = malloc((12 * nr + 1) * sizeof *k.col);
    k.val = malloc((12 * nr + 1) * sizeof *k.val);
    k.uval = malloc((nr + 1) * sizeof *k.uval);
    k.ucol = malloc((nr + 1) * sizeof *k.ucol);
    y = calloc(nr + 1, sizeof *y);
    if (!k.g || !k.vx || !k.rx || !k.vb || !k.rb || !k.w || !k.p || !k.q || !k.z || !k.scale || !k.yn ||
        !k.in || !k.fidx || !k.fpos || !k.rowptr || !k.col || !k.val || !k.uval || !k.ucol || !y) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (KKT solve)");
        goto done;
    }
    /* g = -grad L (the tension pulls each vertex along its two edges), projected */
    const double *x = c->x;
    for (size_t a = 0; a < s.nv; a++) {
        size_t b = s.next[a];
        if (b == NONE)
            continue;
        double u[3];
        v3_sub(u, x + 3 * b, x + 3 * a);
        v3_scale(u, 1.0 / v3_norm(u), u);
        v3_axpy(k.g + 3 * a, 1.0, u);
        v3_axpy(k.g + 3 * b, -1.0, u);
    }
    for (size_t i = 0; i < s.nv; i++)
        project(c, i, k.g + 3 * i);
    double g2 = 0.0;
    for (size_t i = 0; i < nx; i++)
        g2 += k.g[i] * k.g[i];
    if (tension)
        memcpy(tension, k.g, nx * sizeof *tension);
    if (unresolved) /* nothing holds anything until the multipliers say so */
        memcpy(unresolved, k.g, nx * sizeof *unresolved);
    out->force = sqrt(g2);
    /* KKT: grad L = sum lambda_r grad C_r with lambda_r >= 0 on the
     * inequality rows, i.e. g = sum lambda_r (-grad C_r): the tension pulls
     * against every row that holds it. The rows are negated here so that
     * the multipliers solved for below are the lambdas themselves.
     * Every row is also normalised (in the W^-1 metric): positive scaling
     * leaves the cone y >= 0 and so the residual unchanged, and makes the
     * normal matrix's diagonal 1 (MinRad rows are ~ 2r/ebar long, edges
     * sqrt 2). The multipliers are scaled back for the report. */
    for (size_t r = 0; r < nr; r++) {
        row *q = &s.r[r];
        double d2 = q->debar * q->debar / s.ne[q->comp];
        for (int m = 0; m < q->nvx; m++)
            d2 += v3_dot(q->d[m], q->d[m]);
        k.scale[r] = d2 > 0.0 ? 1.0 / sqrt(d2) : 1.0;
        for (int m = 0; m < q->nvx; m++)
            v3_scale(q->d[m], -k.scale[r], q->d[m]);
        q->debar *= -k.scale[r];
        k.in[r] = 1;
        if (q->kind == ROW_STRUT)
            out->strut_rows++;
        else if (q->kind == ROW_MINRAD)
            out->minrad_rows++;
    }
    if (g2 == 0.0) {
        out->converged = 1;
        goto done;
    }
    /* An active-set method for the nonnegative least squares, Lawson and
     * Hanson's ("Solving Least Squares Problems", 1974, ch. 23) with rows
     * added in blocks: each round frees every row whose multiplier is
     * positive or whose dual asks for one; the inner loop solves the least
     * squares on the free set (sparse factor), walks towards it until a
     * multiplier would turn negative, drops the rows that reach 0, and
     * solves again. Every iterate is feasible and the residual never rises.
     * Converged: no row outside the free set wants in. */
    double n2 = resolve(&s, &k, y, k.w);
    double tol = 1e-9 * sqrt(g2); /* a dual below this is solver noise */
    for (int round = 0; round < prm->max_outer; round++) {
        out->rounds = round + 1;
        for (size_t r = 0; r < nr; r++)
            k.in[r] = s.r[r].kind == ROW_EDGE || y[r] > 0.0 || k.w[r] > tol;
        double n2old = n2;
        if ((rc = factor_free(&s, &k, &fac, err)))
            goto done;
        for (int inner = 0; inner < 1000; inner++) {
            if ((rc = ls_free(&s, &k, fac, y, k.yn, &out->solves, err)))
                goto done;
            /* Two candidates: Lawson and Hanson's walk from y towards the
             * free set's minimiser until the first multiplier reaches 0 (the
             * objective falls all the way: it is convex and the segment lies
             * in the free set's subspace), which drops one row per solve, and
             * the minimiser clipped at 0, which drops every negative row at
             * once but may not descend. The clipped one is taken whenever it
             * is at least as good: with the many dependent struts of a fine
             * knot the walk alone needs hundreds of factorisations. */
            double alpha = 1.0;
            for (size_t r = 0; r < nr; r++)
                if (k.in[r] && s.r[r].kind != ROW_EDGE && k.yn[r] < 0.0)
                    alpha = fmin(alpha, y[r] / (y[r] - k.yn[r]));
            for (size_t r = 0; r < nr; r++)
                k.z[r] = k.in[r] && !(s.r[r].kind != ROW_EDGE && k.yn[r] < 0.0) ? k.yn[r] : 0.0;
            int clipped = alpha < 1.0 && resolve(&s, &k, k.z, NULL) <= resolve_walk(&s, &k, y, alpha);
            int dropped = 0;
            for (size_t r = 0; r < nr; r++) {
                if (!k.in[r])
                    continue;
                y[r] = clipped ? k.z[r] : y[r] + alpha * (k.yn[r] - y[r]);
                if (s.r[r].kind != ROW_EDGE && k.yn[r] < 0.0 && (clipped || y[r] <= 1e-14 * fabs(k.yn[r]))) {
                    y[r] = 0.0;
                    k.in[r] = 0;
                    dropped++;
                }
            }
            if (!dropped)
                break;
            /* a few dropped rows are pinned in the factor; many, refactored */
            if (tr_rowchol_pinned(fac) + (size_t)dropped > KKT_MAX_PINS) {
                if ((rc = factor_free(&s, &k, &fac, err)))
                    goto done;
            } else {
                for (size_t r = 0; r < nr; r++)
                    if (!k.in[r] && k.fpos[r] != NONE && (rc = tr_rowchol_pin(fac, k.fpos[r], err)))
                        goto done;
            }
        }
        n2 = resolve(&s, &k, y, NULL);
        int progress = n2 < n2old * (1.0 - 1e-12);
        n2 = resolve(&s, &k, y, k.w);
        /* optimality of y for the least squares: the projected gradient */
        double pg2 = 0.0;
        for (size_t r = 0; r < nr; r++) {
            double w = k.w[r];
            if (s.r[r].kind != ROW_EDGE && y[r] <= 0.0 && w < 0.0)
                w = 0.0;
            pg2 += w * w;
        }
        out->optimality = sqrt(pg2 / g2);
        if (!progress || out->optimality <= prm->opt_tol) {
            out->converged = out->optimality <= prm->opt_tol;
            break;
        }
    }
    n2 = resolve(&s, &k, y, NULL);
    out->residual = sqrt(n2 / g2);
    if (unresolved)
        memcpy(unresolved, k.rx, nx * sizeof *unresolved);
    for (size_t r = 0; r < nr; r++) {
        if (!(y[r] > 0.0))
            continue;
        if (s.r[r].kind == ROW_STRUT) {
            out->strut_active++;
            out->strut_force_max = fmax(out->strut_force_max, y[r] * k.scale[r]);
        } else if (s.r[r].kind == ROW_MINRAD)
            out->minrad_active++;
    }
done:
    tr_rowchol_free(fac);
    free(y);
    sys_free(&s, &k);
    return rc;
}

/* A curve far from the origin for its size, or far from unit scale, is
 * certified in the oracle's frame (curve.h, tr_curve_frame_of: centred,
 * scaled by a power of two): the residual, the tension (a gradient of
 * length) and the multipliers change with neither; the radius is scaled
 * back. A curve whose numbers cannot hold its shape is refused as the
 * thickness oracle refuses it. */
int tr_kkt_certify_forces(const tr_curve *c, const tr_kkt_params *prm, tr_kkt *out, double *tension,
                          double *unresolved, tr_error *err)
{
    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < 3 * c->nv; i++)
        if (!isfinite(c->x[i]))
            return tr_fail(err, TR_EGEOMETRY, "KKT certificate: vertex %zu is not finite", i / 3);
    tr_curve_frame f;
    tr_curve s;
    const tr_curve *use;
    int rc = tr_curve_oracle_frame(c, &f, &s, &use, err);
    if (rc || use == c) {
        tr_curve_free(&s);
        return rc ? rc : certify_frame(c, prm, out, tension, unresolved, err);
    }
    tr_kkt_params sp;
    if (prm)
        sp = *prm;
    else
        tr_kkt_params_default(&sp);
    if (sp.radius > 0.0)
        sp.radius = ldexp(sp.radius, -f.e);
    rc = certify_frame(&s, &sp, out, tension, unresolved, err);
    tr_curve_free(&s);
    out->radius = ldexp(out->radius, f.e);
    return rc;
}

int tr_kkt_certify(const tr_curve *c, const tr_kkt_params *prm, tr_kkt *out, tr_error *err)
{
    return tr_kkt_certify_forces(c, prm, out, NULL, NULL, err);
}
