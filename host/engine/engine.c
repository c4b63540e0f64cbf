/* This file contains the tightening engine: the step, its control, refinement, checkpoints and
 * the level loop (engine.h). */
#include "engine/engine.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/curve_io.h"
#include "engine/polish.h"
#include "solver/newton.h"
#include "engine/refine_lowpass.h"
#include "geometry/struts.h"
#include "util/clock.h"
#include "util/text_file.h"
#include "oracle/thickness.h"

struct tr_engine {
    char device[128];
    int coarse_ref; /* this level runs on the reference, not device (device_min_n) */
    tr_engine_params prm;
    tr_backend be;
    tr_curve curve; /* topology, constraints; coordinates as of the last download */
    int *gap;       /* exclusion gap per component, fixed between rebuilds */
    double *ebar;   /* scratch, ncomp */
    int contacts_valid;
    double disp_acc; /* max vertex motion summed since the contact list was built */
    double disp_est; /* the per-step motion the contact list's tilt allows for */
    tr_contact_stats contacts; /* of the last rebuild */
    double h;
    long steps, rejected;
    double length, residual, min_strut, minrad, edge_dev;
    int jammed;
    double elapsed_base; /* seconds before this process (from a checkpoint) */
    double t0;           /* monotonic start of this process's run */
    long steps_at_t0;
    int polished; /* 0: not yet; 1: accepted; -1: ran and kept the engine's curve */
    double polish_before, polish_after, polish_seconds;
    const char *polish_why;
    int newton_ran; /* as polished, for the second-order solver */
    double newton_before, newton_after, newton_seconds;
    int newton_iters;
    /* The polished curve itself, kept when settling it onto the engine's
     * constraint set cost ropelength (the oracle's, which is scale free):
     * until the engine takes another step it is the curve handed out. */
    double *polish_x;
    long polish_steps;
};

void tr_engine_params_default(tr_engine_params *p)
{
    memset(p, 0, sizeof *p);
    p->skin = 0.1;
    p->skin_min = 1e-3;
    p->skin_motion = 4.0;
    p->tilt_edges = 1.25;
    p->tilt_motion = 0.0;
    p->max_move = 0.03;
    p->guard_move = 0.06;
    p->smooth_passes = 8;
    p->h_min = 1e-9;
    p->h_max = 10.0;
    p->grow = 1.25;
    p->shrink = 0.5;
    p->accept_viol = 1e-9;
    p->minrad_tol = 1e-6;
    p->max_edge = 1.0;
    p->correct.max_newton = 8;
    p->correct.max_cg = 400;
    p->correct.cg_rtol = 1e-9;
    p->correct.viol_tol = 1e-12;
    p->correct.active_strut = 1e-4;
    p->correct.active_curv = 1e-4;
    p->correct.strut_dist = 2.0;
    p->correct.minrad = 1.0;
    p->correct.ebar_weight = 1.0;
    p->correct.reg = 1e-12;
    p->correct.max_step = 0.03;
    p->project = 1;
    p->proj = p->correct;
    p->proj.max_newton = 3;
    p->proj.cg_rtol = 1e-4;
    p->proj.max_cg = 200;
    p->polish = 1;
    p->polish_share = 0.8;
    p->polish_coarse = 1;
    p->device_min_n = 2048;
}

const char *tr_stop_reason_name(tr_stop_reason r)
{
    switch (r) {
    case TR_STOP_RESIDUAL:
        return "residual";
    case TR_STOP_JAMMED:
        return "jammed";
    case TR_STOP_TARGET:
        return "target";
    case TR_STOP_STEPS:
        return "steps";
    case TR_STOP_TIME:
        return "time-limit";
    case TR_STOP_SIGNAL:
        return "signal";
    default:
        return "none";
    }
}

void tr_engine_contact_shape(const tr_engine_params *p, double ebar_max, double minrad, double disp,
                             double *cutoff, double *tilt)
{
    /* turning angles are at most 2 atan(ebar / (2 MinRad)) <= ebar / MinRad */
    double r = minrad < 1.0 ? fmax(minrad, 0.25) : 1.0;
    double t = p->tilt_edges * ebar_max / r + p->tilt_motion * disp;
    *tilt = t > 0.0 && t < 1.0 ? t : 1.0;
    *cutoff = p->correct.strut_dist + fmin(p->skin, fmax(p->skin_min, p->skin_motion * disp));
}

static int measure(tr_engine *e, tr_measure *m, tr_error *err)
{
    int rc = e->be.ops->measure(e->be.state, m, NULL, e->ebar, err);
    if (rc)
        return rc;
    return TR_OK;
}

/* now: a measurement of the current state (e->ebar set by it) when the
 * caller has one, else NULL. The list does not change what the tilt reads
 * (the longest edge and MinRad), so it is not measured twice. */
static int rebuild_contacts(tr_engine *e, int recompute_gap, const tr_measure *now, tr_error *err)
{
    /* the tilt needs the longest edge and MinRad as of this state */
    tr_measure m;
    int rc = TR_OK;
    if (now)
        m = *now;
    else if ((rc = measure(e, &m, err)))
        return rc;
    if (recompute_gap) {
        for (int k = 0; k < e->curve.ncomp; k++) {
            e->gap[k] = tr_exclusion_gap(1.0, e->ebar[k]);
        }
    }
    double emax = 0.0;
    for (int k = 0; k < e->curve.ncomp; k++)
        emax = fmax(emax, e->ebar[k]);
    tr_contact_params cp = {.exclude_gap = e->gap};
    tr_engine_contact_shape(&e->prm, emax, m.min_minrad, e->disp_est, &cp.cutoff, &cp.tilt);
    rc = e->be.ops->find_contacts(e->be.state, &cp, &e->contacts, err);
    if (rc)
        return rc;
    e->contacts_valid = 1;
    e->disp_acc = 0.0;
    return TR_OK;
}

static void fill_state(tr_engine *e, const tr_measure *m)
{
    e->length = m->length;
    e->min_strut = m->min_strut;
    e->minrad = m->min_minrad;
    e->edge_dev = m->edge_dev;
}

/* Brings a fresh backend state onto the constraint set (equal edges,
 * struts, chords) in damped Newton steps, guarding every one. */
static int settle(tr_engine *e, const char *what, double overlap_ok, tr_error *err)
{
    const tr_backend_ops *op = e->be.ops;
    tr_measure m;
    int rc = rebuild_contacts(e, 1, NULL, err);
    if (rc)
        return rc;
    rc = measure(e, &m, err);
    if (rc)
        return rc;
    for (int k = 0; k < e->curve.ncomp; k++)
        if (!(e->ebar[k] < e->prm.max_edge))
            return tr_fail(err, TR_EGEOMETRY,
                           "%s: component %d is too coarse for its thickness: edges of length %.3g, "
                           "need < %.3g (use more vertices)",
                           what, k, e->ebar[k], e->prm.max_edge);
    if (m.min_strut < e->prm.correct.strut_dist * (1.0 - 1e-6) - overlap_ok)
        return tr_fail(err, TR_EGEOMETRY,
                       "%s overlaps itself: two non-neighbouring parts are %.6g apart, closer than the "
                       "rope diameter 2 (tighten --scale scales a start to thickness 1)",
                       what, m.min_strut);
    if (m.min_minrad < 0.5)
        return tr_fail(err, TR_EGEOMETRY,
                       "%s is bent far tighter than the rope allows (MinRad %.4g < 1)", what, m.min_minrad);
    tr_correct_params cp = e->prm.correct;
    cp.max_newton = 1;
    for (int it = 0; it < 400; it++) {
        if (e->disp_acc + e->prm.guard_move > 0.5 * e->prm.skin && (rc = rebuild_contacts(e, 1, &m, err)))
            return rc;
        tr_correct_stats cs;
        if ((rc = op->save(e->be.state, err)) || (rc = op->correct(e->be.state, &cp, &cs, err)) ||
            (rc = measure(e, &m, err)))
            return rc;
        e->disp_acc += m.max_disp;
        e->disp_est = m.max_disp;
        if (m.min_strut < e->prm.correct.strut_dist - 0.5)
            return tr_fail(err, TR_ETOPOLOGY, "%s: equalising the edges brought strands to %.4g apart",
                           what, m.min_strut);
        if (cs.viol_after <= e->prm.accept_viol) {
            if ((rc = rebuild_contacts(e, 1, &m, err)) || (rc = measure(e, &m, err)))
                return rc;
            fill_state(e, &m);
            return TR_OK;
        }
    }
    return tr_fail(err, TR_EGEOMETRY,
                   "%s: could not bring the curve to equal edges, MinRad >= 1 and distances >= 2", what);
}

static int open_backend(tr_engine *e, const tr_curve *c, tr_error *err)
{
    int rc = tr_backend_open(e->coarse_ref ? "reference" : e->device[0] ? e->device : NULL, c, &e->be,
                             err);
    if (rc)
        return rc;
    e->contacts_valid = 0;
    return TR_OK;
}

static int alloc_comp_arrays(tr_engine *e, tr_error *err)
{
    free(e->gap);
    free(e->ebar);
    e->gap = calloc((size_t)e->curve.ncomp, sizeof *e->gap);
    e->ebar = calloc((size_t)e->curve.ncomp, sizeof *e->ebar);
    if (!e->gap || !e->ebar)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    return TR_OK;
}

static tr_engine *engine_new(const char *device, const tr_engine_params *p)
{
    tr_engine *e = calloc(1, sizeof *e);
    if (!e)
        return NULL;
    if (device)
        snprintf(e->device, sizeof e->device, "%s", device);
    if (p)
        e->prm = *p;
    else
        tr_engine_params_default(&e->prm);
    e->t0 = tr_clock_seconds();
    return e;
}

int tr_engine_create(tr_engine **out, const tr_curve *c, const char *device,
                     const tr_engine_params *p, tr_error *err)
{
    *out = NULL;
    tr_engine *e = engine_new(device, p);
    if (!e)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    int rc = tr_curve_copy(&e->curve, c, err);
    if (!rc)
        rc = alloc_comp_arrays(e, err);
    if (!rc)
        rc = open_backend(e, c, err);
    if (!rc)
        rc = settle(e, "the start curve", 0.0, err);
    if (rc) {
        tr_engine_destroy(e);
        return rc;
    }
    e->h = e->ebar[0];
    *out = e;
    return TR_OK;
}

void tr_engine_destroy(tr_engine *e)
{
    if (!e)
        return;
    tr_backend_close(&e->be);
    tr_curve_free(&e->curve);
    free(e->gap);
    free(e->ebar);
    free(e->polish_x);
    free(e);
}

const char *tr_engine_device(const tr_engine *e) { return e->be.description; }
const char *tr_engine_warning(const tr_engine *e) { return e->be.warning; }

int tr_engine_step(tr_engine *e, int *accepted, tr_error *err)
{
    const tr_backend_ops *op = e->be.ops;
    int rc;
    *accepted = 0;
    if (!e->contacts_valid && (rc = rebuild_contacts(e, 1, NULL, err)))
        return rc;
    tr_tension_params tp = {.h = e->h, .max_move = e->prm.max_move, .smooth_passes = e->prm.smooth_passes,
                            .project = e->prm.project ? &e->prm.proj : NULL};
    tr_tension_stats ts;
    tr_correct_stats cs;
    tr_measure m;
    if ((rc = op->save(e->be.state, err)) || (rc = op->tension_step(e->be.state, &tp, &ts, err)) ||
        (rc = op->correct(e->be.state, &e->prm.correct, &cs, err)) || (rc = measure(e, &m, err)))
        return rc;
    int ok = cs.viol_after <= e->prm.accept_viol && m.length < e->length &&
             m.max_disp <= e->prm.guard_move &&
             m.min_strut >= e->prm.correct.strut_dist - 10.0 * e->prm.accept_viol &&
             m.min_minrad >= e->prm.correct.minrad * (1.0 - e->prm.minrad_tol) && isfinite(m.length);
    /* The list this step ran on holds the struts a step of the last one's
     * size can reach; a bigger slide may have carried a contact out of it.
     * So the list is rebuilt at the new state, for the next step, and its
     * shortest strut (every local minimum of the distance is in it) must
     * hold too. */
    if (ok) {
        double keep = e->disp_est;
        e->disp_est = m.max_disp;
        if ((rc = rebuild_contacts(e, 1, &m, err)))
            return rc;
        if (!(e->contacts.min_dist >= e->prm.correct.strut_dist - 10.0 * e->prm.accept_viol)) {
            ok = 0;
            e->contacts_valid = 0;
            e->disp_est = fmax(keep, m.max_disp);
        }
    }
    if (!ok) {
        if ((rc = op->restore(e->be.state, err)))
            return rc;
        /* a list built at the rejected state is rebuilt now, so that a
         * checkpoint taken here resumes on the very list this run uses */
        if (!e->contacts_valid && (rc = rebuild_contacts(e, 1, NULL, err)))
            return rc;
        e->rejected++;
        e->h *= e->prm.shrink;
        if (e->h < e->prm.h_min) {
            e->h = e->prm.h_min;
            e->jammed = 1;
        }
        return TR_OK;
    }
    double dl = e->length - m.length;
    (void)dl;
    e->residual = ts.smooth2 > 0 ? sqrt(ts.free2 / ts.smooth2) : 0.0;
    fill_state(e, &m);
    e->steps++;
    e->jammed = 0;
    e->h = fmin(e->h * e->prm.grow, e->prm.h_max);
    *accepted = 1;
    return TR_OK;
}

void tr_engine_get_progress(const tr_engine *e, tr_engine_progress *p)
{
    memset(p, 0, sizeof *p);
    double t = tr_clock_seconds() - e->t0;
    p->steps = e->steps;
    p->rejected = e->rejected;
    p->n = e->curve.nv;
    p->length = e->length;
    double th = fmin(1.0, fmin(e->min_strut / 2.0, e->minrad));
    p->ropelength = e->length / th;
    p->residual = e->residual;
    p->min_strut = e->min_strut;
    p->minrad = e->minrad;
    p->edge_dev = e->edge_dev;
    p->h = e->h;
    p->elapsed = e->elapsed_base + t;
    p->steps_per_s = t > 0 ? (double)(e->steps - e->steps_at_t0) / t : 0.0;
    p->polished = e->polished;
    p->polish_before = e->polish_before;
    p->polish_after = e->polish_after;
    p->polish_seconds = e->polish_seconds;
    p->polish_why = e->polish_why;
    p->newton_ran = e->newton_ran;
    p->newton_before = e->newton_before;
    p->newton_after = e->newton_after;
    p->newton_seconds = e->newton_seconds;
    p->newton_iters = e->newton_iters;
}

int tr_engine_get_curve(tr_engine *e, tr_curve *out, tr_error *err)
{
    int rc = e->be.ops->download(e->be.state, e->curve.x, NULL, err);
    if (rc)
        return rc;
    if ((rc = tr_curve_copy(out, &e->curve, err)))
        return rc;
    if (e->polish_x && e->steps == e->polish_steps)
        memcpy(out->x, e->polish_x, 3 * out->nv * sizeof *out->x);
    return TR_OK;
}

int tr_engine_refine(tr_engine *e, size_t n, tr_error *err)
{
    int rc = e->be.ops->download(e->be.state, e->curve.x, NULL, err);
    if (rc)
        return rc;
    tr_curve fine;
    rc = tr_refine_lowpass(&e->curve, n, 0.5, 0.5, &fine, err);
    if (rc)
        return rc;
    tr_backend_close(&e->be);
    tr_curve_free(&e->curve);
    e->curve = fine;
    if ((rc = alloc_comp_arrays(e, err)) || (rc = open_backend(e, &e->curve, err)))
        return rc;
    /* resampling may bring strands slightly closer than 2 (never near
     * crossing): the correction pushes them back out */
    e->polished = 0;
    free(e->polish_x);
    e->polish_x = NULL;
    rc = settle(e, "the refined curve", 0.25, err);
    if (rc == TR_EGEOMETRY)
        return tr_fail_wrap(err, TR_ETOPOLOGY, "refining to %zu vertices", n);
    if (rc)
        return rc;
    e->h = e->ebar[0];
    e->jammed = 0;
    return TR_OK;
}

/* ---- checkpoints: exact text (hex floats) ---- */

int tr_engine_checkpoint_write(tr_engine *e, const char *path, tr_error *err)
{
    int rc = e->be.ops->download(e->be.state, e->curve.x, e->ebar, err);
    if (rc)
        return rc;
    tr_engine_progress p;
    tr_engine_get_progress(e, &p);
    const tr_curve *c = &e->curve;
    tr_text b = {0};
    tr_text_printf(&b, "tightrope-checkpoint 1\n");
    tr_text_printf(&b, "ncomp %d\n", c->ncomp);
    for (int k = 0; k < c->ncomp; k++)
        tr_text_printf(&b, "comp %zu %d %a %d\n", tr_comp_nv(c, k), c->closed[k], e->ebar[k], e->gap[k]);
    tr_text_printf(&b, "state %ld %ld %a %a %a %a %a %d\n", e->steps, e->rejected, e->h, e->disp_est,
              p.elapsed, e->residual, e->length, e->jammed);
    tr_text_printf(&b, "ncst %d\n", c->ncst);
    for (int q = 0; q < c->ncst; q++) {
        const tr_constraint *k = &c->cst[q];
        tr_text_printf(&b, "cst %d %d %a %a %a %a %a %a %a\n", (int)k->kind, k->id, k->p[0], k->p[1], k->p[2],
                  k->u[0], k->u[1], k->u[2], k->d);
    }
    for (size_t i = 0; i < c->nv; i++)
        if (c->vcst && c->vcst[i] >= 0)
            tr_text_printf(&b, "vcst %zu %d\n", i, c->vcst[i]);
    tr_text_printf(&b, "x\n");
    for (size_t i = 0; i < c->nv; i++)
        tr_text_printf(&b, "%a %a %a\n", c->x[3 * i], c->x[3 * i + 1], c->x[3 * i + 2]);
    tr_text_printf(&b, "end\n");
    size_t len;
    char *text = tr_text_take(&b, &len);
    if (!text)
        return tr_fail(err, TR_ENOMEM, "out of memory writing a checkpoint");
    rc = tr_write_file_atomic(path, text, len, err);
    free(text);
    return rc;
}

/* A whole token that is a finite number (strtod alone accepts "zzz" as 0). */
static int parse_finite(const char *tok, double *v)
{
    char *endp;
    *v = strtod(tok, &endp);
    return endp != tok && *endp == '\0' && isfinite(*v);
}

int tr_engine_resume(tr_engine **out, const char *path, const char *device,
                     const tr_engine_params *p, tr_error *err)
{
    *out = NULL;
    char *text;
    int rrc = tr_read_file(path, &text, NULL, err);
    if (rrc)
        return rrc;
    /* every vertex needs a line of at least "0 0 0\n": bounds the counts
     * before anything is allocated from them (taken before strtok cuts the text) */
    const size_t max_vertices = strlen(text) / 6;
    tr_engine *e = engine_new(device, p);
    size_t *nv = NULL;
    unsigned char *closed = NULL;
    double *ebar = NULL;
    int *gap = NULL;
    int rc = TR_OK, line = 1, ncomp = 0;
    char *save = NULL;
    char *ln = strtok_r(text, "\n", &save);
#define BAD(what)                                                                                  \
    do {                                                                                           \
        rc = tr_fail(err, TR_EPARSE, "%s:%d: %s", path, line, what);                               \
        goto fail;                                                                                 \
    } while (0)
#define NEXT()                                                                                     \
    do {                                                                                           \
        ln = strtok_r(NULL, "\n", &save);                                                          \
        line++;                                                                                    \
        if (!ln)                                                                                   \
            BAD("checkpoint ends early");                                                          \
    } while (0)
    if (!e) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory");
        goto fail;
    }
    if (!ln || strcmp(ln, "tightrope-checkpoint 1") != 0)
        BAD("not a tightrope checkpoint (expected 'tightrope-checkpoint 1')");
    NEXT();
    if (sscanf(ln, "ncomp %d", &ncomp) != 1 || ncomp <= 0 || ncomp > 1000000)
        BAD("expected 'ncomp K'");
    nv = calloc((size_t)ncomp, sizeof *nv);
    closed = calloc((size_t)ncomp, 1);
    ebar = calloc((size_t)ncomp, sizeof *ebar);
    gap = calloc((size_t)ncomp, sizeof *gap);
    if (!nv || !closed || !ebar || !gap) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory");
        goto fail;
    }
    size_t total = 0;
    for (int k = 0; k < ncomp; k++) {
        NEXT();
        int cl;
        char eb[64];
        if (sscanf(ln, "comp %zu %d %63s %d", &nv[k], &cl, eb, &gap[k]) != 4 || nv[k] < 2)
            BAD("expected 'comp NV CLOSED EBAR GAP'");
        if (nv[k] > max_vertices - total)
            BAD("more vertices than the checkpoint holds");
        total += nv[k];
        if (gap[k] < 2 || (cl != 0 && cl != 1) || (cl && nv[k] < 3))
            BAD("bad component closure or exclusion gap");
        closed[k] = (unsigned char)(cl != 0);
        if (!parse_finite(eb, &ebar[k]) || !(ebar[k] > 0))
            BAD("edge length must be a positive finite number");
    }
    NEXT();
    {
        char h[64], da[64], el[64], rs[64], le[64];
        if (sscanf(ln, "state %ld %ld %63s %63s %63s %63s %63s %d", &e->steps, &e->rejected, h, da, el, rs,
                   le, &e->jammed) != 8)
            BAD("expected the 'state' line");
        if (!parse_finite(h, &e->h) || !parse_finite(da, &e->disp_est) || !(e->disp_est >= 0) ||
            !parse_finite(el, &e->elapsed_base) || !parse_finite(rs, &e->residual) ||
            !parse_finite(le, &e->length) || !(e->h > 0) || e->steps < 0 || e->rejected < 0)
            BAD("bad number in the 'state' line");
    }
    if ((rc = tr_curve_alloc(&e->curve, ncomp, nv, closed, err)))
        goto fail;
    NEXT();
    int ncst;
    if (sscanf(ln, "ncst %d", &ncst) != 1 || ncst < 0)
        BAD("expected 'ncst C'");
    for (int q = 0; q < ncst; q++) {
        NEXT();
        tr_constraint k;
        int kind;
        char f[7][64];
        if (sscanf(ln, "cst %d %d %63s %63s %63s %63s %63s %63s %63s", &kind, &k.id, f[0], f[1], f[2], f[3],
                   f[4], f[5], f[6]) != 9)
            BAD("expected a 'cst' line");
        if (kind < TR_CST_FIXED || kind > TR_CST_PLANE)
            BAD("unknown constraint kind");
        k.kind = (tr_cst_kind)kind;
        int ok = 1;
        for (int a = 0; a < 3; a++)
            ok = ok && parse_finite(f[a], &k.p[a]) && parse_finite(f[3 + a], &k.u[a]);
        if (!ok || !parse_finite(f[6], &k.d))
            BAD("bad number in a 'cst' line");
        if ((rc = tr_curve_add_constraint(&e->curve, &k, err)) < 0)
            goto fail;
        rc = TR_OK;
    }
    NEXT();
    while (!strncmp(ln, "vcst ", 5)) {
        size_t i;
        int q;
        if (sscanf(ln, "vcst %zu %d", &i, &q) != 2 || i >= e->curve.nv || q < 0 || q >= ncst)
            BAD("bad 'vcst' line");
        e->curve.vcst[i] = q;
        NEXT();
    }
    if (strcmp(ln, "x") != 0)
        BAD("expected 'x'");
    for (size_t i = 0; i < e->curve.nv; i++) {
        NEXT();
        char *q = ln;
        for (int a = 0; a < 3; a++) {
            char *endp;
            e->curve.x[3 * i + a] = strtod(q, &endp);
            if (endp == q || !isfinite(e->curve.x[3 * i + a]))
                BAD("expected three finite coordinates");
            q = endp;
        }
        while (*q == ' ' || *q == '\t' || *q == '\r')
            q++;
        if (*q)
            BAD("unexpected text after the coordinates");
    }
    NEXT();
    if (strcmp(ln, "end") != 0)
        BAD("expected 'end' (truncated checkpoint?)");
#undef BAD
#undef NEXT
    if ((rc = alloc_comp_arrays(e, err)) || (rc = open_backend(e, &e->curve, err)))
        goto fail;
    memcpy(e->gap, gap, (size_t)ncomp * sizeof *gap);
    if ((rc = e->be.ops->upload(e->be.state, e->curve.x, ebar, err)))
        goto fail;
    /* the list is rebuilt with the saved exclusion gaps: pairs it adds beyond
     * the uninterrupted run's list are inactive and contribute exact zeros */
    {
        memcpy(e->ebar, ebar, (size_t)ncomp * sizeof *ebar);
        if ((rc = rebuild_contacts(e, 0, NULL, err)))
            goto fail;
        tr_measure m;
        if ((rc = measure(e, &m, err)))
            goto fail;
        /* a checkpoint is input like any other: never continue from a state
         * that is not a valid rope (overlap, a kink, a wrong edge length) */
        if (!(m.min_strut >= e->prm.correct.strut_dist - 100.0 * e->prm.accept_viol) ||
            !(m.min_minrad >= e->prm.correct.minrad * (1.0 - 2.0 * e->prm.minrad_tol)) ||
            !(m.edge_dev <= 1e-6)) {
            rc = tr_fail(err, TR_EGEOMETRY,
                         "%s: checkpoint is not a valid rope state (closest non-local distance %.6g, "
                         "MinRad %.6g, edge deviation %.3g)",
                         path, m.min_strut, m.min_minrad, m.edge_dev);
            goto fail;
        }
        double len = e->length;
        fill_state(e, &m);
        e->length = len;
    }
    e->steps_at_t0 = e->steps;
    free(text);
    free(nv);
    free(closed);
    free(ebar);
    free(gap);
    *out = e;
    return TR_OK;
fail:
    free(text);
    free(nv);
    free(closed);
    free(ebar);
    free(gap);
    tr_engine_destroy(e);
    return rc;
}

/* After a polish was settled: if the settled curve measures longer (oracle
 * ropelength) than the polished one in e->curve.x, keep the polished
 * coordinates for tr_engine_get_curve. scratch: 3 nv doubles. */
static int keep_if_settle_lost(tr_engine *e, double polished_rl, double *scratch, tr_error *err)
{
    size_t nx = 3 * e->curve.nv;
    free(e->polish_x);
    e->polish_x = NULL;
    double *px = malloc(nx * sizeof *px);
    if (!px)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    memcpy(px, e->curve.x, nx * sizeof *px);
    int rc = e->be.ops->download(e->be.state, scratch, NULL, err);
    tr_thickness th;
    if (rc == TR_OK) {
        memcpy(e->curve.x, scratch, nx * sizeof *scratch);
        rc = tr_thickness_measure(&e->curve, NULL, &th, NULL, err);
    }
    if (rc == TR_OK && th.ropelength > polished_rl * (1.0 + 1e-12)) {
        e->polish_x = px;
        e->polish_steps = e->steps;
        e->polish_after = polished_rl;
        return TR_OK;
    }
    free(px);
    return rc;
}

/* The polish stage: download, polish on the host, upload and settle onto
 * the engine's exact constraint set (equal edges to 1e-9). The polished
 * curve is at thickness 1 with every constraint satisfied, so settle moves
 * it by no more than its edge deviation. */
/* The second-order solver on the host curve (the polished one, or the
 * engine's where polish kept it), with its share of the time; reports
 * whether it replaced the curve. */
static int run_newton(tr_engine *e, double seconds, volatile sig_atomic_t *stop, int *accepted, tr_error *err)
{
    *accepted = 0;
    if (e->curve.ncst > 0)
        return TR_OK;
    tr_newton_params np;
    tr_newton_params_default(&np);
    np.time_limit = seconds;
    np.stop = stop;
    tr_newton_stats ns;
    int rc = tr_newton(&e->curve, &np, &ns, err);
    if (rc)
        return rc == TR_EGEOMETRY ? TR_OK : rc;
    e->newton_ran = ns.accepted ? 1 : -1;
    e->newton_before = ns.ropelength_before;
    e->newton_after = ns.ropelength_after;
    e->newton_seconds = ns.seconds;
    e->newton_iters = ns.iters;
    *accepted = ns.accepted;
    return TR_OK;
}

static int run_polish(tr_engine *e, double seconds, double target, int final, volatile sig_atomic_t *stop,
                      tr_error *err)
{
    int newton = final && e->prm.newton && e->curve.ncst == 0;
    size_t nx = 3 * e->curve.nv;
    double *keep = malloc((nx + (size_t)e->curve.ncomp) * sizeof *keep);
    if (!keep)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    int rc = e->be.ops->download(e->be.state, keep, keep + nx, err);
    if (rc) {
        free(keep);
        return rc;
    }
    memcpy(e->curve.x, keep, nx * sizeof *keep);
    tr_polish_params pp;
    tr_polish_params_default(&pp);
    pp.time_limit = seconds;
    pp.target = target;
    pp.stop = stop;
    tr_polish_stats ps;
    memset(&ps, 0, sizeof ps);
    if (newton) {
        /* at the finest level the second-order solver takes the polish's
         * place (bench/RESULTS.md, "Second-order solver") */
        int nacc = 0;
        if ((rc = run_newton(e, seconds, stop, &nacc, err))) {
            free(keep);
            return rc;
        }
        ps.accepted = nacc;
        ps.ropelength_after = e->newton_after;
        e->polished = nacc ? 1 : -1;
        e->polish_before = e->newton_before;
        e->polish_after = e->newton_after;
        e->polish_seconds = e->newton_seconds;
        e->polish_why = nacc ? NULL : "the second-order solver's result is not shorter";
    } else {
        if ((rc = tr_polish(&e->curve, &pp, &ps, err))) {
            free(keep);
            if (rc != TR_EGEOMETRY)
                return rc;
            e->polished = -1; /* nothing to polish (no finite thickness): the engine goes on */
            return TR_OK;
        }
        e->polish_before = ps.ropelength_before;
        e->polish_after = ps.ropelength_after;
        e->polish_seconds = ps.seconds;
        e->polish_why = ps.skipped ? "below thickness 1 with constrained vertices" : ps.why_rejected;
        e->polished = ps.accepted ? 1 : -1;
    }
    if (!ps.accepted) {
        free(keep);
        return TR_OK;
    }
    if ((rc = e->be.ops->upload(e->be.state, e->curve.x, NULL, err)))
        goto restore;
    e->contacts_valid = 0;
    if ((rc = settle(e, "the polished curve", 0.0, err)))
        goto restore;
    /* settling moves the polished curve by its own small violations, but
     * where the curvature limit holds along a stretch (132 MinRad rows of
     * the N = 2400 trefoil) it can cost more ropelength than polish gained:
     * then the polished curve is kept to hand out */
    if ((rc = keep_if_settle_lost(e, ps.ropelength_after, keep, err))) {
        free(keep);
        return rc;
    }
    free(keep);
    e->h = e->ebar[0];
    e->jammed = 0;
    return TR_OK;
restore:
    /* the engine could not take the polished curve on: go on from its own */
    if (rc == TR_ENOMEM || rc == TR_EOPENCL) {
        free(keep);
        return rc;
    }
    memcpy(e->curve.x, keep, 3 * e->curve.nv * sizeof *keep);
    rc = e->be.ops->upload(e->be.state, keep, keep + 3 * e->curve.nv, err);
    free(keep);
    if (rc)
        return rc;
    tr_measure m;
    if ((rc = rebuild_contacts(e, 1, NULL, err)) || (rc = measure(e, &m, err)))
        return rc;
    fill_state(e, &m);
    e->polished = -1;
    e->polish_after = e->polish_before;
    e->polish_why = "the engine could not settle the polished curve";
    return TR_OK;
}

/* ---- the run loop with levels, stops, checkpoints, progress ---- */

/* The last level of a run: no refinement asked, or n_per_comp vertices per
 * component reach refine_to. */
static int is_final_level(const tr_engine_limits *lim, size_t n_per_comp)
{
    return lim->refine_to == 0 || n_per_comp >= lim->refine_to;
}

/* Whether a level of n vertices in all runs on the reference instead of
 * the chosen device (device_min_n): only coarse levels, and only when the
 * chosen device is not the reference already. */
static int wants_coarse_ref(const tr_engine *e, size_t n, int final_level)
{
    int chosen_is_ref = !e->coarse_ref && e->be.ops->serial;
    return !final_level && n < e->prm.device_min_n && !chosen_is_ref;
}

/* Moves the state to the backend the level wants (wants_coarse_ref): the
 * positions and ebar go over as they are, the contact list is rebuilt. */
static int level_backend(tr_engine *e, int coarse_ref, tr_error *err)
{
    if (coarse_ref == e->coarse_ref)
        return TR_OK;
    int rc = e->be.ops->download(e->be.state, e->curve.x, e->ebar, err);
    if (rc)
        return rc;
    tr_backend_close(&e->be);
    e->coarse_ref = coarse_ref;
    if ((rc = open_backend(e, &e->curve, err)))
        return rc;
    return e->be.ops->upload(e->be.state, e->curve.x, e->ebar, err);
}

#define STALL_STEPS 200
#define STALL_REL 1e-5

int tr_engine_run(tr_engine *e, const tr_engine_limits *lim, tr_stop_reason *why, tr_error *err)
{
    int rc;
    double t_last_ckpt = tr_clock_seconds(), t_last_prog = 0.0;
    double level_t0 = tr_clock_seconds();
    /* Without a time limit to share out, a level is polished (and a coarse
     * one refined) once the engine stalls: less than STALL_REL shorter over
     * STALL_STEPS steps. The projection engine crawls long before it jams
     * (the 2 x 100 clasp: 8800 steps, 100 s, where polish then needs 2 s). */
    long stall_step = e->steps;
    double stall_len = INFINITY;
    double time_left_at_level = lim->time_limit > 0 ? lim->time_limit - (e->elapsed_base + tr_clock_seconds() - e->t0) : 0;
    *why = TR_STOP_NONE;
    rc = level_backend(e, wants_coarse_ref(e, e->curve.nv, is_final_level(lim, e->curve.nv / (size_t)e->curve.ncomp)),
                       err);
    if (rc)
        return rc;
    for (;;) {
        tr_engine_progress p;
        tr_engine_get_progress(e, &p);
        int final_level = is_final_level(lim, e->curve.nv / (size_t)e->curve.ncomp);
        tr_stop_reason stop = TR_STOP_NONE;
        int stalled = 0;
        if (lim->time_limit <= 0 && e->steps - stall_step >= STALL_STEPS) {
            stalled = !(p.ropelength < stall_len * (1.0 - STALL_REL));
            stall_len = p.ropelength;
            stall_step = e->steps;
        }
        int level_done = 0;
        if (lim->stop && *lim->stop)
            stop = TR_STOP_SIGNAL;
        else if (lim->time_limit > 0 && p.elapsed >= lim->time_limit)
            stop = TR_STOP_TIME;
        else if (lim->max_steps > 0 && e->steps >= lim->max_steps)
            stop = TR_STOP_STEPS;
        else if (final_level && lim->target > 0 && p.ropelength <= lim->target)
            stop = TR_STOP_TARGET;
        else if (final_level && e->steps > 0 && lim->residual > 0 && e->residual < lim->residual)
            stop = TR_STOP_RESIDUAL;
        else if (final_level && e->jammed)
            stop = TR_STOP_JAMMED;
        int can_polish = e->prm.polish && e->polished == 0;
        if (final_level && can_polish &&
            (stop == TR_STOP_RESIDUAL || stop == TR_STOP_JAMMED || (stop == TR_STOP_NONE && stalled) ||
             (stop == TR_STOP_NONE && lim->time_limit > 0 &&
              tr_clock_seconds() - level_t0 >= (1.0 - e->prm.polish_share) * time_left_at_level))) {
            double left = lim->time_limit > 0 ? lim->time_limit - p.elapsed : 0.0;
            if ((rc = run_polish(e, lim->time_limit > 0 ? fmax(left, 1e-3) : 0.0, lim->target, 1,
                                 lim->stop, err)))
                return rc;
            continue;
        }
        if (!final_level && stop == TR_STOP_NONE) {
            /* a coarse level has half the time left when it began; with
             * polish_coarse the engine gets the first half of that and the
             * polish the rest (it usually converges much sooner) */
            int pc = e->prm.polish && e->prm.polish_coarse;
            double coarse_res = lim->coarse_residual > 0 ? lim->coarse_residual : 1e-3;
            double used = tr_clock_seconds() - level_t0;
            if (e->jammed || stalled || (e->steps > 0 && e->residual < coarse_res) || (pc && e->polished != 0))
                level_done = 1;
            if (lim->time_limit > 0 && used > (pc ? 0.25 : 0.5) * time_left_at_level)
                level_done = 1;
            if (level_done && pc && e->polished == 0) {
                double budget = lim->time_limit > 0 ? fmax(0.5 * time_left_at_level - used, 1e-3) : 0.0;
                if ((rc = run_polish(e, budget, 0.0, 0, lim->stop, err)))
                    return rc;
                continue;
            }
        }
        if (lim->progress && (stop != TR_STOP_NONE || tr_clock_seconds() - t_last_prog >= lim->progress_every)) {
            lim->progress(&p, lim->user);
            t_last_prog = tr_clock_seconds();
        }
        if (stop != TR_STOP_NONE) {
            *why = stop;
            if (lim->checkpoint_path && (rc = tr_engine_checkpoint_write(e, lim->checkpoint_path, err)))
                return rc;
            return TR_OK;
        }
        if (level_done) {
            size_t n = e->curve.nv / (size_t)e->curve.ncomp;
            size_t next = 2 * n < lim->refine_to ? 2 * n : lim->refine_to;
            /* tr_engine_refine opens the next level's backend */
            e->coarse_ref = wants_coarse_ref(e, next * (size_t)e->curve.ncomp, is_final_level(lim, next));
            if ((rc = tr_engine_refine(e, next, err)))
                return rc;
            level_t0 = tr_clock_seconds();
            stall_step = e->steps;
            stall_len = INFINITY;
            time_left_at_level = lim->time_limit > 0 ? lim->time_limit - (e->elapsed_base + tr_clock_seconds() - e->t0) : 0;
            continue;
        }
        if (lim->checkpoint_path && lim->checkpoint_every > 0 && tr_clock_seconds() - t_last_ckpt >= lim->checkpoint_every) {
            if ((rc = tr_engine_checkpoint_write(e, lim->checkpoint_path, err)))
                return rc;
            t_last_ckpt = tr_clock_seconds();
        }
        int acc;
        if ((rc = tr_engine_step(e, &acc, err)))
            return rc;
    }
}
