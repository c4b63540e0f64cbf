/* This file contains the polish stage: augmented-Lagrangian / L-BFGS minimisation of a nearly
 * tight rope on the host (polish.h). */
#include "engine/polish.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "util/lbfgs.h"
#include "geometry/neighbour_search.h"
#include "geometry/struts.h"
#include "segment_distance.h"
#include "oracle/thickness.h"
#include "geometry/turning_angle.h"
#include "util/clock.h"
#include "util/vec3.h"

#define NONE SIZE_MAX

/* A constrained curve is taken at thickness 1 within CONSTRAINED_IN_TOL
 * (the engine's state mid-run; polish repairs that much) and given back
 * within CONSTRAINED_OUT_TOL (a run that ends at its round limit leaves
 * violations of ~1e-7; the ropelength compared is length / thickness, so
 * that costs it honestly); the engine's settle then restores its exact
 * constraint set. */
#define CONSTRAINED_IN_TOL 1e-3
#define CONSTRAINED_OUT_TOL 1e-6

void tr_polish_params_default(tr_polish_params *p)
{
    memset(p, 0, sizeof *p);
    p->time_limit = 0.0;
    p->max_outer = 40;
    p->max_inner = 400;
    p->skin = 0.2;
    p->max_move = 0.02;
    p->viol_tol = 1e-9;
    p->mu0 = 100.0;
    p->mu_max = 1e8;
    p->lbfgs_m = 12;
    p->max_restarts = 100;
    p->restart_tol = 1e-9;
}

typedef tr_strut_pair strut_pair;

typedef struct ctx {
    tr_curve w; /* working copy: topology; x = positions at the last pair-list build */
    const tr_polish_params *p;
    size_t nv;
    size_t *next, *prev;
    int *comp;
    size_t *ne;       /* edges per component */
    int *gap;         /* exclusion gap per component */
    double e0;        /* start edge length (scales the curvature rows) */
    double mu;
    double *lam_e, *lam_c1, *lam_c2; /* per edge / vertex multipliers */
    double *dphi_e;   /* scratch: penalty derivative per edge */
    double *good;     /* the last iterate that passed the guards */
    double *len_k, *mean_k;
    strut_pair *sp;
    size_t nsp, capsp;
    tr_nsearch ns;
    /* results of the last evaluation (the accepted iterate, see lbfgs.c) */
    double last_dmin, last_minrad;
    double viol_strut, viol_curv, viol_edge; /* relative */
    /* run control */
    double deadline;
    int need_rebuild, broken, out_of_time;
} ctx;

/* Rebuilds the candidate pair list at x, carrying the multipliers of pairs
 * that stay listed. */
static int rebuild(ctx *c, const double *x, tr_error *err)
{
    memcpy(c->w.x, x, 3 * c->nv * sizeof *x);
    tr_nsearch_refit(&c->ns);
    return tr_strut_candidates(&c->ns, c->w.x, c->next, c->gap, c->w.ncomp, 2.0 + c->p->skin, &c->sp, &c->nsp,
                               err);

}

/* Penalty of an inequality row C >= 0 (PHR): value, derivative in C. */
static double ineq_pen(double C, double lam, double mu, double *dphi)
{
    if (C < lam / mu) {
        *dphi = -lam + mu * C;
        return -lam * C + 0.5 * mu * C * C;
    }
    *dphi = 0.0;
    return -lam * lam / (2.0 * mu);
}

static double eval(void *vc, const double *x, double *g)
{
    ctx *c = vc;
    size_t nv = c->nv;
    double mu = c->mu, f = 0.0;
    memset(g, 0, 3 * nv * sizeof *g);
    double vs = 0.0, vc_ = 0.0, ve = 0.0, dmin = INFINITY, mrad = INFINITY;
    /* edges: length + equal-edge rows (h_a = |e_a| - L_k / n_k) */
    for (int k = 0; k < c->w.ncomp; k++)
        c->len_k[k] = c->mean_k[k] = 0.0;
    for (size_t a = 0; a < nv; a++)
        if (c->next[a] != NONE)
            c->len_k[c->comp[a]] += sqrt(v3_dist2(x + 3 * c->next[a], x + 3 * a));
    for (int k = 0; k < c->w.ncomp; k++)
        c->len_k[k] /= (double)(c->ne[k] ? c->ne[k] : 1);
    for (size_t a = 0; a < nv; a++) {
        if (c->next[a] == NONE)
            continue;
        int k = c->comp[a];
        double l = sqrt(v3_dist2(x + 3 * c->next[a], x + 3 * a));
        double h = l - c->len_k[k];
        f += l - c->lam_e[a] * h + 0.5 * mu * h * h;
        c->dphi_e[a] = -c->lam_e[a] + mu * h;
        c->mean_k[k] += c->dphi_e[a];
        ve = fmax(ve, fabs(h) / c->len_k[k]);
    }
    for (size_t a = 0; a < nv; a++) {
        if (c->next[a] == NONE)
            continue;
        int k = c->comp[a];
        double w = 1.0 + c->dphi_e[a] - c->mean_k[k] / (double)c->ne[k], u[3];
        v3_sub(u, x + 3 * c->next[a], x + 3 * a);
        double l = v3_norm(u);
        for (int d = 0; d < 3; d++) {
            g[3 * c->next[a] + d] += w * u[d] / l;
            g[3 * a + d] -= w * u[d] / l;
        }
    }
    /* MinRad rows: e0 (|p| - 2t) >= 0 and e0 (|q| - 2t) >= 0 */
    double e0 = c->e0;
    for (size_t i = 0; i < nv; i++) {
        size_t ip = c->prev[i], in = c->next[i];
        if (ip == NONE || in == NONE)
            continue;
        double p[3], q[3], dtp[3], dtq[3], lp, lq;
        double t = tr_vertex_turning(x, ip, i, in, p, q, &lp, &lq, dtp, dtq);
        if (t > 0)
            mrad = fmin(mrad, fmin(lp, lq) / (2.0 * t));
        double C1 = e0 * (lp - 2.0 * t), C2 = e0 * (lq - 2.0 * t), d1, d2;
        f += ineq_pen(C1, c->lam_c1[i], mu, &d1) + ineq_pen(C2, c->lam_c2[i], mu, &d2);
        vc_ = fmax(vc_, fmax(-C1 / (e0 * lp), -C2 / (e0 * lq)));
        if (d1 == 0.0 && d2 == 0.0)
            continue;
        for (int d = 0; d < 3; d++) {
            /* dC1/dp = e0 (p^ - 2 dt/dp), dC1/dq = -2 e0 dt/dq; C2 likewise */
            double gp = e0 * (d1 * (p[d] / lp - 2.0 * dtp[d]) - 2.0 * d2 * dtp[d]);
            double gq = e0 * (d2 * (q[d] / lq - 2.0 * dtq[d]) - 2.0 * d1 * dtq[d]);
            g[3 * ip + d] -= gp;
            g[3 * i + d] += gp - gq;
            g[3 * in + d] += gq;
        }
    }
    /* struts: d(a, b) - 2 >= 0 */
    for (size_t r = 0; r < c->nsp; r++) {
        strut_pair *sp = &c->sp[r];
        size_t a = sp->a, b = sp->b, na = c->next[a], nb = c->next[b];
        double s, t;
        double d = tr_segment_distance(x + 3 * a, x + 3 * na, x + 3 * b, x + 3 * nb, &s, &t);
        dmin = fmin(dmin, d);
        double dphi;
        f += ineq_pen(d - 2.0, sp->lam, mu, &dphi);
        vs = fmax(vs, (2.0 - d) / 2.0);
        if (dphi == 0.0)
            continue;
        double cn[3], gs[4][3];
        for (int k = 0; k < 3; k++)
            cn[k] = (x[3 * a + k] + s * (x[3 * na + k] - x[3 * a + k])) -
                    (x[3 * b + k] + t * (x[3 * nb + k] - x[3 * b + k]));
        tr_strut_gradient(cn, s, t, d, dphi, gs);
        for (int k = 0; k < 3; k++) {
            g[3 * a + k] += gs[0][k];
            g[3 * na + k] += gs[1][k];
            g[3 * b + k] += gs[2][k];
            g[3 * nb + k] += gs[3][k];
        }
    }
    /* constrained vertices (clasp ends) move only as their constraint
     * allows: L-BFGS steps are combinations of these gradients, so the
     * iterates stay on the planes (up to rounding, snapped at the end) */
    if (c->w.vcst)
        for (size_t i = 0; i < nv; i++)
            if (c->w.vcst[i] >= 0)
                tr_constraint_project_motion(&c->w.cst[c->w.vcst[i]], g + 3 * i);
    c->last_dmin = dmin;
    c->last_minrad = mrad;
    c->viol_strut = vs;
    c->viol_curv = vc_;
    c->viol_edge = ve;
    return f;
}

static void update_multipliers(ctx *c, const double *x)
{
    size_t nv = c->nv;
    double mu = c->mu, e0 = c->e0;
    for (int k = 0; k < c->w.ncomp; k++)
        c->len_k[k] = 0.0;
    for (size_t a = 0; a < nv; a++)
        if (c->next[a] != NONE)
            c->len_k[c->comp[a]] += sqrt(v3_dist2(x + 3 * c->next[a], x + 3 * a));
    for (size_t a = 0; a < nv; a++)
        if (c->next[a] != NONE) {
            int k = c->comp[a];
            double h = sqrt(v3_dist2(x + 3 * c->next[a], x + 3 * a)) - c->len_k[k] / (double)c->ne[k];
            c->lam_e[a] -= mu * h;
        }
    for (size_t i = 0; i < nv; i++) {
        size_t ip = c->prev[i], in = c->next[i];
        if (ip == NONE || in == NONE)
            continue;
        double p[3], q[3], dtp[3], dtq[3], lp, lq;
        double t = tr_vertex_turning(x, ip, i, in, p, q, &lp, &lq, dtp, dtq);
        c->lam_c1[i] = fmax(0.0, c->lam_c1[i] - mu * e0 * (lp - 2.0 * t));
        c->lam_c2[i] = fmax(0.0, c->lam_c2[i] - mu * e0 * (lq - 2.0 * t));
    }
    for (size_t r = 0; r < c->nsp; r++) {
        strut_pair *sp = &c->sp[r];
        double s, t;
        double d = tr_segment_distance(x + 3 * sp->a, x + 3 * c->next[sp->a], x + 3 * sp->b,
                                       x + 3 * c->next[sp->b], &s, &t);
        sp->lam = fmax(0.0, sp->lam - mu * (d - 2.0));
    }
}

static int on_iter(void *vc, const double *x, double f, const double *g, int it)
{
    (void)f;
    (void)g;
    (void)it;
    ctx *c = vc;
    /* the guards of the header comment */
    if (!(c->last_dmin > 4.0 * c->p->max_move) || !(c->last_minrad >= 0.9)) {
        c->broken = 1;
        return 1;
    }
    memcpy(c->good, x, 3 * c->nv * sizeof *x);
    if (c->p->observe)
        c->p->observe(c->p->user, x, c->nv);
    double m = 0.0;
    for (size_t i = 0; i < c->nv; i++)
        m = fmax(m, v3_dist2(x + 3 * i, c->w.x + 3 * i));
    if (sqrt(m) > 0.25 * c->p->skin - c->p->max_move) {
        c->need_rebuild = 1;
        return 1;
    }
    if ((c->deadline > 0 && tr_clock_seconds() > c->deadline) || (c->p->stop && *c->p->stop)) {
        c->out_of_time = 1;
        return 1;
    }
    return 0;
}

static void ctx_free(ctx *c)
{
    tr_nsearch_free(&c->ns);
    tr_curve_free(&c->w);
    free(c->next);
    free(c->prev);
    free(c->comp);
    free(c->ne);
    free(c->gap);
    free(c->lam_e);
    free(c->lam_c1);
    free(c->lam_c2);
    free(c->dphi_e);
    free(c->good);
    free(c->len_k);
    free(c->mean_k);
    free(c->sp);
}

/* Shortest segment distance over non-excluded pairs (below 2 + skin; else
 * 2 + skin), Rawdon MinRad, relative edge deviation: at c->w.x. */
static int final_geometry(ctx *c, double *dmin, double *minrad, double *edge_dev, tr_error *err)
{
    int rc = rebuild(c, c->w.x, err);
    if (rc)
        return rc;
    double *gtmp = malloc(3 * c->nv * sizeof *gtmp);
    if (!gtmp)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    double save_mu = c->mu;
    eval(c, c->w.x, gtmp);
    c->mu = save_mu;
    free(gtmp);
    *dmin = fmin(c->last_dmin, 2.0 + c->p->skin);
    *minrad = c->last_minrad;
    *edge_dev = c->viol_edge;
    return TR_OK;
}

/* One augmented-Lagrangian run from mu0 and zero multipliers. */
static int polish_once(tr_curve *cv, const tr_polish_params *prm, tr_polish_stats *st, tr_error *err)
{
    memset(st, 0, sizeof *st);
    double t0 = tr_clock_seconds();
    tr_thickness th0;
    int rc = tr_thickness_measure(cv, NULL, &th0, NULL, err);
    if (rc)
        return rc;
    if (!(th0.thickness > 0) || !isfinite(th0.thickness))
        return tr_fail(err, TR_EGEOMETRY, "polish: the curve has no finite positive thickness");
    /* a constrained curve cannot be rescaled (its ends would leave their
     * planes): it is polished as it is, at thickness 1, if it has that */
    int constrained = cv->ncst > 0;
    if (constrained && th0.thickness < 1.0 - CONSTRAINED_IN_TOL) {
        st->skipped = 1;
        return TR_OK;
    }
    st->ropelength_before = st->ropelength_after = th0.ropelength;
    ctx c;
    memset(&c, 0, sizeof c);
    c.p = prm;
    if ((rc = tr_curve_copy(&c.w, cv, err)))
        return rc;
    tr_curve_drop_lo(&c.w); /* the polish moves vertices in doubles */
    if (!constrained)
        tr_curve_scale_by(&c.w, 1.0 / th0.thickness);
    size_t nv = c.nv = c.w.nv;
    int nc = c.w.ncomp;
    c.next = malloc(nv * sizeof *c.next);
    c.prev = malloc(nv * sizeof *c.prev);
    c.comp = malloc(nv * sizeof *c.comp);
    c.ne = calloc((size_t)nc, sizeof *c.ne);
    c.gap = calloc((size_t)nc, sizeof *c.gap);
    c.lam_e = calloc(nv, sizeof *c.lam_e);
    c.lam_c1 = calloc(nv, sizeof *c.lam_c1);
    c.lam_c2 = calloc(nv, sizeof *c.lam_c2);
    c.dphi_e = calloc(nv, sizeof *c.dphi_e);
    c.good = malloc(3 * nv * sizeof *c.good);
    c.len_k = calloc((size_t)nc, sizeof *c.len_k);
    c.mean_k = calloc((size_t)nc, sizeof *c.mean_k);
    double *x = malloc(3 * nv * sizeof *x), *best = malloc(3 * nv * sizeof *best);
    if (!c.next || !c.prev || !c.comp || !c.ne || !c.gap || !c.lam_e || !c.lam_c1 || !c.lam_c2 ||
        !c.dphi_e || !c.good || !c.len_k || !c.mean_k || !x || !best) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (polish, %zu vertices)", nv);
        goto done;
    }
    double ltot = 0.0;
    size_t etot = 0;
    for (int k = 0; k < nc; k++) {
        size_t s = c.w.start[k], n = tr_comp_nv(&c.w, k);
        for (size_t l = 0; l < n; l++) {
            size_t i = s + l;
            c.comp[i] = k;
            c.next[i] = l + 1 < n ? i + 1 : (c.w.closed[k] ? s : NONE);
            c.prev[i] = l > 0 ? i - 1 : (c.w.closed[k] ? s + n - 1 : NONE);
        }
        c.ne[k] = tr_comp_ne(&c.w, k);
        double lk = tr_comp_length(&c.w, k);
        c.gap[k] = tr_exclusion_gap(1.0, lk / (double)c.ne[k]);
        ltot += lk;
        etot += c.ne[k];
    }
    c.e0 = ltot / (double)etot;
    c.mu = prm->mu0;
    if ((rc = tr_nsearch_build(&c.ns, &c.w, err)))
        goto done;
    memcpy(x, c.w.x, 3 * nv * sizeof *x);
    memcpy(c.good, x, 3 * nv * sizeof *x);
    if ((rc = rebuild(&c, x, err)))
        goto done;
    c.deadline = prm->time_limit > 0 ? t0 + prm->time_limit : 0.0;
    if (!(prm->max_move > 0 && prm->max_move <= prm->skin / 8) || prm->max_inner < 1 || prm->max_outer < 1) {
        rc = tr_fail(err, TR_EINVAL, "polish: need 0 < max_move <= skin / 8 and at least one iteration");
        goto done;
    }
    tr_lbfgs_params lp;
    tr_lbfgs_params_default(&lp);
    lp.m = prm->lbfgs_m;
    lp.max_move = prm->max_move;
    lp.group = 3;
    lp.max_iter = prm->max_inner;
    lp.gtol = 1e-3;
    double prev_viol = INFINITY, viol = INFINITY, prev_len = INFINITY;
    int breaks = 0;
    double *gtmp = best; /* scratch for evaluations */
    for (int outer = 0; outer < prm->max_outer && !c.out_of_time; outer++) {
        tr_lbfgs_result res;
        int used = 0; /* iterations of this round, over list rebuilds */
        for (;;) {
            c.need_rebuild = 0;
            lp.max_iter = prm->max_inner - used;
            if ((rc = tr_lbfgs_minimize(3 * nv, x, &lp, eval, on_iter, &c, &res, err)))
                goto done;
            st->inner_iters += res.iters;
            used += res.iters;
            st->evals += res.evals;
            if (c.broken) {
                /* the penalty was too weak for this iterate: drop it, go
                 * back to the last guarded iterate and stiffen */
                if (++breaks > 40) {
                    st->why_rejected = "a motion guard broke (strands too close or MinRad < 0.9)";
                    goto done;
                }
                c.broken = 0;
                memcpy(x, c.good, 3 * nv * sizeof *x);
                c.mu = fmin(4.0 * c.mu, prm->mu_max);
                lp.max_move = fmax(0.5 * lp.max_move, 1e-6);
                continue;
            }
            if (!c.need_rebuild || used >= prm->max_inner)
                break;
            if ((rc = rebuild(&c, x, err)))
                goto done;
            st->rebuilds++;
            if (c.out_of_time)
                break;
        }
        st->outer = outer + 1;
        lp.max_move = fmin(2.0 * lp.max_move, prm->max_move);
        eval(&c, x, gtmp);
        viol = fmax(c.viol_strut, fmax(c.viol_curv, c.viol_edge));
        double len = 0.0;
        for (int k = 0; k < nc; k++)
            len += c.len_k[k] * (double)c.ne[k];
        /* converged: feasible and either stationary or no longer shortening */
        if (viol <= prm->viol_tol &&
            ((res.reason == TR_LBFGS_GTOL && lp.gtol <= 1e-8) || fabs(prev_len - len) <= 1e-13 * len))
            break;
        prev_len = len;
        update_multipliers(&c, x);
        if (viol > 0.25 * prev_viol)
            c.mu = fmin(10.0 * c.mu, prm->mu_max);
        prev_viol = viol;
        lp.gtol = fmax(0.1 * lp.gtol, 1e-9);
    }
    st->max_viol = viol;
    /* validate and rescale */
    memcpy(c.w.x, x, 3 * nv * sizeof *x);
    for (size_t i = 0; constrained && i < nv; i++)
        if (c.w.vcst[i] >= 0)
            tr_constraint_project(&c.w.cst[c.w.vcst[i]], c.w.x + 3 * i);
    double dmin = 0, minrad = 0, edev = INFINITY;
    if ((rc = final_geometry(&c, &dmin, &minrad, &edev, err)))
        goto done;
    st->edge_dev = edev;
    if (!(dmin >= 2.0 * (1.0 - 1e-3)) || !(minrad >= 1.0 - 1e-3) || !(edev <= 1e-3)) {
        st->why_rejected = "the polished curve violates the constraints by more than 1e-3";
        goto done;
    }
    tr_thickness th;
    if ((rc = tr_thickness_measure(&c.w, NULL, &th, NULL, err)))
        goto done;
    double thick = fmin(th.thickness, fmin(minrad, 0.5 * dmin));
    if (!(thick > 0) || !isfinite(thick)) {
        st->why_rejected = "the polished curve has no finite positive thickness";
        goto done;
    }
    if (!constrained) {
        tr_curve_scale_by(&c.w, 1.0 / thick);
        if ((rc = tr_thickness_measure(&c.w, NULL, &th, NULL, err)))
            goto done;
    }
    if (!(th.ropelength < th0.ropelength) || !(th.thickness >= 1.0 - (constrained ? CONSTRAINED_OUT_TOL : 1e-12))) {
        st->why_rejected = "the polished curve is not shorter";
        goto done;
    }
    tr_curve_drop_lo(cv);
    memcpy(cv->x, c.w.x, 3 * nv * sizeof *x);
    st->accepted = 1;
    st->ropelength_after = th.ropelength;
done:
    st->seconds = tr_clock_seconds() - t0;
    free(x);
    free(best);
    ctx_free(&c);
    return rc;
}

/* The penalty only grows within one run, and once it is large the inner
 * problem is so stiff that L-BFGS creeps: the length stops changing and the
 * run ends "converged" while the rope could still shorten by a lot (a 4_1
 * from KnotPlot's start at N = 100: one run 45.74 -> 45.05, repeated runs
 * 44.93, 44.47, 43.35, 42.47, 42.26 and then no change). So the run is
 * restarted from its own result with a fresh penalty and multipliers until
 * two restarts in a row no longer shorten the rope by more than
 * restart_tol. After one such restart the next can still move the curve
 * onto its contacts: the demo's N = 400 trefoil, stopped after one, ended
 * with a KKT residual of 5.5e-3 to 7.5e-3 in 2 of 26 runs (c858d02) and 4 of
 * 10 (986c245), 3-7e-4 in the rest; stopped after two, 2.9e-4 to 6.4e-4 in
 * 30 of 30. */
int tr_polish(tr_curve *cv, const tr_polish_params *prm, tr_polish_stats *st, tr_error *err)
{
    tr_polish_params defp;
    if (!prm) {
        tr_polish_params_default(&defp);
        prm = &defp;
    }
    memset(st, 0, sizeof *st);
    tr_polish_params run = *prm;
    double spent = 0.0;
    int idle = 0;
    for (int r = 0; r < (prm->max_restarts > 0 ? prm->max_restarts : 1); r++) {
        if (prm->time_limit > 0) {
            run.time_limit = prm->time_limit - spent;
            if (r > 0 && run.time_limit < 1e-3)
                break;
        }
        if (r > 0 && prm->stop && *prm->stop)
            break;
        tr_polish_stats one;
        int rc = polish_once(cv, &run, &one, err);
        if (rc && (r == 0 || rc == TR_ENOMEM))
            return rc;
        if (rc) /* a later run found nothing to do (the curve is the accepted one): keep it */
            break;
        spent += one.seconds;
        st->seconds = spent;
        st->outer += one.outer;
        st->inner_iters += one.inner_iters;
        st->evals += one.evals;
        st->rebuilds += one.rebuilds;
        st->restarts = r + 1;
        if (r == 0) {
            st->skipped = one.skipped;
            st->ropelength_before = st->ropelength_after = one.ropelength_before;
            st->max_viol = one.max_viol;
            st->edge_dev = one.edge_dev;
            st->why_rejected = one.why_rejected;
        }
        if (one.skipped || !one.accepted)
            break;
        st->accepted = 1;
        st->why_rejected = NULL;
        st->ropelength_after = one.ropelength_after;
        st->max_viol = one.max_viol;
        st->edge_dev = one.edge_dev;
        if (one.ropelength_before - one.ropelength_after <= prm->restart_tol * one.ropelength_before) {
            if (++idle >= 2)
                break;
        } else
            idle = 0;
        if (prm->target > 0 && one.ropelength_after <= prm->target)
            break;
    }
    return TR_OK;
}
