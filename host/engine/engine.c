/* This file contains the tightening engine's life and step: create, destroy,
 * one step with its control, the contact list, refinement (engine.h); the
 * checkpoint format is checkpoint.c, the level loop level_loop.c. */
#include "engine/engine.h"
#include "engine/engine_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/curve_io.h"
#include "engine/polish.h"
#include "engine/refine_lowpass.h"
#include "geometry/struts.h"
#include "util/clock.h"
#include "util/text_file.h"
#include "oracle/thickness.h"
#include "solver/newton.h"

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
    p->newton_tight = 1;
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
    case TR_STOP_SOLVED:
        return "solved";
    case TR_STOP_REFINE:
        return "refine-failed";
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

int tr_engine_i_measure(tr_engine *e, tr_measure *m, tr_error *err)
{
    int rc = e->be.ops->measure(e->be.state, m, NULL, e->ebar, err);
    if (rc)
        return rc;
    return TR_OK;
}

/* now: a measurement of the current state (e->ebar set by it) when the
 * caller has one, else NULL. The list does not change what the tilt reads
 * (the longest edge and MinRad), so it is not measured twice. */
int tr_engine_i_rebuild_contacts(tr_engine *e, int recompute_gap, const tr_measure *now, tr_error *err)
{
    /* the tilt needs the longest edge and MinRad as of this state */
    tr_measure m;
    int rc = TR_OK;
    if (now)
        m = *now;
    else if ((rc = tr_engine_i_measure(e, &m, err)))
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

void tr_engine_i_fill_state(tr_engine *e, const tr_measure *m)
{
    e->length = m->length;
    e->min_strut = m->min_strut;
    e->minrad = m->min_minrad;
    e->edge_dev = m->edge_dev;
}

/* Brings a fresh backend state onto the constraint set (equal edges,
 * struts, chords) in damped Newton steps, guarding every one. */
int tr_engine_i_settle(tr_engine *e, const char *what, double overlap_ok, tr_error *err)
{
    const tr_backend_ops *op = e->be.ops;
    tr_measure m;
    int rc = tr_engine_i_rebuild_contacts(e, 1, NULL, err);
    if (rc)
        return rc;
    rc = tr_engine_i_measure(e, &m, err);
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
        /* 400 passes at N = 9600 are a minute and a half on a loaded
         * machine: each pass looks at the clock and the stop flag */
        int past = tr_deadline_passed(&e->bound);
        if (past)
            return tr_fail(err, TR_EINTERRUPTED, "%s: %s before it was settled", what,
                           past == 2 ? "stopped by a signal" : "the time limit came");
        if (e->disp_acc + e->prm.guard_move > 0.5 * e->prm.skin && (rc = tr_engine_i_rebuild_contacts(e, 1, &m, err)))
            return rc;
        tr_correct_stats cs;
        if ((rc = op->save(e->be.state, err)) || (rc = op->correct(e->be.state, &cp, &cs, err)) ||
            (rc = tr_engine_i_measure(e, &m, err)))
            return rc;
        e->disp_acc += m.max_disp;
        e->disp_est = m.max_disp;
        if (m.min_strut < e->prm.correct.strut_dist - 0.5)
            return tr_fail(err, TR_ETOPOLOGY, "%s: equalising the edges brought strands to %.4g apart",
                           what, m.min_strut);
        if (cs.viol_after <= e->prm.accept_viol) {
            if ((rc = tr_engine_i_rebuild_contacts(e, 1, &m, err)) || (rc = tr_engine_i_measure(e, &m, err)))
                return rc;
            tr_engine_i_fill_state(e, &m);
            return TR_OK;
        }
    }
    return tr_fail(err, TR_EGEOMETRY,
                   "%s: could not bring the curve to equal edges, MinRad >= 1 and distances >= 2", what);
}

int tr_engine_i_keep_presettle(tr_engine *e, tr_error *err)
{
    free(e->presettle_x);
    e->presettle_x = malloc(3 * e->curve.nv * sizeof *e->presettle_x);
    if (!e->presettle_x)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    memcpy(e->presettle_x, e->curve.x, 3 * e->curve.nv * sizeof *e->presettle_x);
    return TR_OK;
}

int tr_engine_i_open_backend(tr_engine *e, const tr_curve *c, tr_error *err)
{
    int rc = tr_backend_open(e->coarse_ref ? "reference" : e->device[0] ? e->device : NULL, c, &e->be,
                             err);
    if (rc)
        return rc;
    e->contacts_valid = 0;
    return TR_OK;
}

int tr_engine_i_alloc_comp_arrays(tr_engine *e, tr_error *err)
{
    free(e->gap);
    free(e->ebar);
    e->gap = calloc((size_t)e->curve.ncomp, sizeof *e->gap);
    e->ebar = calloc((size_t)e->curve.ncomp, sizeof *e->ebar);
    if (!e->gap || !e->ebar)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    return TR_OK;
}

static void coarse_drop(tr_engine *e);

tr_engine *tr_engine_i_new(const char *device, const tr_engine_params *p)
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
    e->bound = e->prm.bound;
    return e;
}

/* The solver's checkpoint: its shortest iterate so far at thickness 1,
 * with the edge targets and gaps of that curve, in the engine's format, so
 * that --resume goes on from it. A failure is counted as the level loop's
 * are (tr_engine_checkpoint_failures); the solve goes on. */
int tr_engine_i_solver_checkpoint(tr_engine *e, const tr_curve *best, tr_error *err)
{
    int nc = best->ncomp, rc;
    double *ebar = malloc((size_t)nc * sizeof *ebar);
    int *gap = malloc((size_t)nc * sizeof *gap);
    if (!ebar || !gap)
        rc = tr_fail(err, TR_ENOMEM, "out of memory writing a checkpoint");
    else {
        for (int k = 0; k < nc; k++) {
            ebar[k] = tr_comp_length(best, k) / (double)tr_comp_ne(best, k);
            gap[k] = tr_exclusion_gap(1.0, ebar[k]);
        }
        rc = tr_engine_i_checkpoint_curve(e, best, ebar, gap, e->ckpt_path, err);
    }
    free(ebar);
    free(gap);
    if (rc) {
        e->ckpt_failures++;
        snprintf(e->ckpt_failure, sizeof e->ckpt_failure, "%.255s", err->msg);
    }
    return rc;
}

/* The solver's checkpoint callback: the curve also kept, for the
 * checkpoint that goes with each of its states (solver_state.c). */
static int newton_checkpoint(void *user, const tr_curve *best, tr_error *err)
{
    tr_engine *e = user;
    tr_engine_i_solver_state_keep_best(e, best);
    return tr_engine_i_solver_checkpoint(e, best, err);
}

/* A clasp level is fine, for the solver's penalty cap (tr_engine_i_newton),
 * when its edges are below FINE_CLASP_EDGE, and finer still, for its first
 * penalty, below FINEST_CLASP_EDGE: 2 x 32 000 vertices between the walls
 * +-1.5 have edges of 2.27e-4, 2 x 25 600 of 2.84e-4, 2 x 12 800 of 5.7e-4. */
#define FINE_CLASP_EDGE 4e-4
#define FINEST_CLASP_EDGE 2.5e-4

/* The shortest mean edge of the curve's components. */
static double finest_edge(const tr_curve *c)
{
    double m = INFINITY;
    for (int k = 0; k < c->ncomp; k++)
        if (tr_comp_ne(c, k) > 0)
            m = fmin(m, tr_comp_length(c, k) / (double)tr_comp_ne(c, k));
    return m;
}

int tr_engine_i_newton(tr_engine *e, double seconds, int tight_only, volatile sig_atomic_t *stop, int *accepted,
                       tr_error *err)
{
    *accepted = 0;
    tr_newton_params np;
    tr_newton_params_default(&np);
    /* the share asked for, within the hard bound */
    double left = tr_deadline_left(&e->bound);
    if (isfinite(left))
        seconds = seconds > 0 ? fmin(seconds, fmax(left, 1e-3)) : fmax(left, 1e-3);
    np.time_limit = seconds;
    /* A refined clasp has no other road than the solver (its settle is
     * skipped: engine.c, tr_engine_refine), so it is solved even when the
     * warm start reads it loose: 2 x 1600 refined to 2 x 3200 on the way
     * to 2 x 48 000 was read loose, not run, and the refinement failed */
    np.tight_only = tight_only && !e->refine_unsettled;
    np.stop = stop ? stop : e->bound.stop;
    if (e->ckpt_path && e->ckpt_every > 0) {
        np.checkpoint = newton_checkpoint;
        np.checkpoint_every = e->ckpt_every;
        np.user = e;
    }
    /* its state beside the checkpoint, or the resumed one's */
    tr_engine_i_solver_state_before(e, &np);
    tr_newton_stats ns;
    /* tried, whatever comes of it: the level loop must not try again */
    e->newton_tried = 1;
    e->newton_unfinished = 0;
    /* The solver's strut rows on the run's device (backend.h strut_rows):
     * the open backend, or, for the solve before the settle (tr_engine_solve,
     * before the engine opens one), one opened for the solve on the same
     * spec; a device that cannot be opened leaves the rows to the solver,
     * as does the serial reference, whose rows are the solver's own. */
    tr_backend own;
    memset(&own, 0, sizeof own);
    if (!e->be.ops) {
        tr_error e2;
        if (tr_backend_open(e->device[0] ? e->device : NULL, &e->curve, &own, &e2) != TR_OK)
            memset(&own, 0, sizeof own);
    }
    const tr_backend *be = e->be.ops ? &e->be : own.ops ? &own : NULL;
    np.backend = be && !be->ops->serial ? be : NULL;
    /* A clasp's level starts from the multipliers its coarser level's
     * solve ended with (engine_internal.h lvl; prolong.c says why), and
     * keeps its own for the next: from 2 x 3200 (walls +-1.5) the warm
     * start's took MinRad 13 % over in one step and the refinement to
     * 2 x 6400 failed; carried, the route reaches 2 x 6400 in one command
     * (its levels 62 to 1388 steps), and 2 x 12 800's level still runs out
     * of the solver's iterations (bench/notes/2026-11-29-clasp-prolongation.md). */
    /* Only an accepted solve's: a rejected one leaves the level's curve as
     * it was, not where its state's multipliers hold. */
    tr_newton_state *end = NULL;
    if (e->curve.ncst > 0) {
        if (e->lvl_refined && e->lvl && e->lvl->ncomp == e->curve.ncomp && e->lvl->nv < e->curve.nv) {
            np.coarse = e->lvl;
            /* the fine levels (edges below FINE_CLASP_EDGE: 2 x 25 600
             * and past, walls +-1.5) cap the penalty at 1e7 / l0, where the
             * default 1e5 closed the tip's MinRad rows by 1 % an update and
             * left them 2e-7 over after 1020 steps; the finest (below
             * FINEST_CLASP_EDGE: 2 x 32 000 and past) also start at a first
             * penalty of 1e3 / l0 instead of mu0, whose first full steps
             * bent the carried curve 100 % past MinRad. So the chain that
             * made the committed 2 x 32 000 (bench/notes/2026-11-29-clasp-
             * fine.md): its 2 x 25 600 settled with mu0 and the cap 1e7 in
             * 893 steps, where the first penalty 1e3 there left the one
             * command's level unsettled after 4688 steps (2 h). The coarser
             * levels keep the defaults, with which they are solved in
             * minutes (with these settings on every level the route was
             * still at 2 x 3200 after 25 minutes) */
            double edge = finest_edge(&e->curve);
            if (edge < FINE_CLASP_EDGE)
                np.mu_max = 1e7;
            if (edge < FINEST_CLASP_EDGE)
                np.coarse_mu = 1e3;
        }
        if ((end = calloc(1, sizeof *end)))
            np.end_state = end;
    }
    e->lvl_ok = e->lvl_refined = 0;
    int rc = tr_newton(&e->curve, &np, &ns, err);
    /* the result's low parts, kept beside it (engine_internal.h newton_lo) */
    free(e->newton_x);
    free(e->newton_lo);
    e->newton_x = e->newton_lo = NULL;
    if (rc == TR_OK && ns.accepted && e->curve.lo && (e->newton_x = malloc(3 * e->curve.nv * sizeof *e->newton_x))) {
        memcpy(e->newton_x, e->curve.x, 3 * e->curve.nv * sizeof *e->newton_x);
        e->newton_nv = e->curve.nv;
        e->newton_lo = e->curve.lo;
        e->curve.lo = NULL;
    }
    tr_curve_drop_lo(&e->curve);
    tr_engine_i_solver_state_after(e, rc, &ns);
    e->newton_unfinished =
        rc == TR_EINTERRUPTED || (rc == TR_OK && !ns.converged && !ns.settled && !ns.skipped && !ns.loose);
    tr_backend_close(&own);
    snprintf(e->newton_why, sizeof e->newton_why, "%.150s",
             rc ? err->msg : ns.why_rejected ? ns.why_rejected : ns.skipped ? "skipped" : "");
    /* a solve the bound stopped before its first step (the strut list of
     * an absurd N) has nothing to keep: the engine goes on, and stops on
     * the bound itself */
    if (rc || ns.loose) {
        tr_newton_state_free(end);
        free(end);
    }
    if (rc)
        return rc == TR_EGEOMETRY || rc == TR_EINTERRUPTED ? TR_OK : rc;
    if (ns.loose)
        return TR_OK; /* not run: nothing to report */
    e->newton_ran = ns.accepted ? 1 : -1;
    e->newton_before = ns.ropelength_before;
    e->newton_after = ns.ropelength_after;
    e->newton_seconds = ns.seconds;
    e->newton_iters = ns.iters;
    /* for a clasp, converged or settled, kept or not: a settled solve
     * that is not shorter says the start was already the level's optimum
     * (a converged clasp at the route's first level), and the first-order
     * steps a rejection would hand the level to only move a clasp's ends
     * (at 2 x 2000 they folded them through themselves before the next
     * refinement). A closed knot's rejected solve leaves the level to the
     * first-order steps as before. */
    e->newton_solved = (ns.converged || ns.settled) && (ns.accepted || e->curve.ncst > 0);
    if (end && ns.accepted && e->newton_solved && end->nv > 0) {
        tr_newton_state_free(e->lvl);
        free(e->lvl);
        e->lvl = end;
        end = NULL;
        e->lvl_ok = 1;
    }
    tr_newton_state_free(end);
    free(end);
    *accepted = ns.accepted;
    return TR_OK;
}

int tr_engine_solve(tr_engine *e, double seconds, volatile sig_atomic_t *stop, const char *checkpoint,
                    double checkpoint_every, int *accepted, tr_error *err)
{
    *accepted = 0;
    if (e->be.ops)
        return tr_fail(err, TR_EINVAL, "tr_engine_solve: the start is settled already (solve before "
                                       "tr_engine_settle_start)");
    e->ckpt_path = checkpoint;
    e->ckpt_every = checkpoint ? checkpoint_every : 0;
    /* (tr_engine_i_newton keeps the solve within e->bound too) */
    int rc = tr_engine_i_newton(e, seconds, 1, stop, accepted, err);
    if (rc == TR_OK && *accepted) {
        e->polished = 1;
        e->polish_before = e->newton_before;
        e->polish_after = e->newton_after;
        e->polish_seconds = e->newton_seconds;
    }
    return rc;
}

/* A start whose MinRad alone is a little under 1 while its struts are at 2
 * (a spline through a tight knot rings where the curvature jumps: MinRad
 * 0.92 at N = 38 400) can be more than the settle's damped steps take in
 * their 400 tries; scaled to thickness 1 instead it is feasible and the
 * run goes on from a start a few per cent loose, rather than ending with
 * nothing after the solver's time. Anything else stays the settle's error
 * (rc), and a constrained rope is not rescaled (its planes would have to
 * move with it). */
static int settle_scaled(tr_engine *e, int rc, tr_error *err)
{
    tr_thickness th;
    tr_error e2;
    /* within the run's bound: at 2 x 10^5 vertices the measure is a third
     * of a second, past the limit (the settle's error stands then) */
    tr_thickness_opts within = {.bound = &e->bound};
    if (e->curve.ncst > 0 || tr_thickness_measure(&e->curve, &within, &th, NULL, &e2) || !isfinite(th.dcsd) ||
        !(th.dcsd >= 2.0 * (1.0 - 1e-6)) || !(th.minrad < 1.0) || !(th.minrad >= 0.85))
        return rc;
    for (size_t i = 0; i < 3 * e->curve.nv; i++)
        e->curve.x[i] /= th.minrad;
    tr_backend_close(&e->be);
    if ((rc = tr_engine_i_open_backend(e, &e->curve, err)) || (rc = tr_engine_i_keep_presettle(e, err)))
        return rc;
    return tr_engine_i_settle(e, "the start curve (scaled to MinRad 1)", 0.0, err);
}

/* The start's settle stopped by the bound (the time limit, or a signal
 * 2 s into a run): the curve before the settle is the run's best, the
 * solver's result where tr_engine_solve took the start (a rope already, its
 * edges equal to the solver's tolerance), else the start as it came (it
 * passed the settle's checks: no overlap, not too coarse). The engine
 * holds it as it is, and the run, stopping on the bound at once, writes it
 * (scaled to thickness 1 and certified as any result) where nothing would
 * have been. */
static int keep_unsettled_start(tr_engine *e, tr_error *err)
{
    memcpy(e->curve.x, e->presettle_x, 3 * e->curve.nv * sizeof *e->curve.x);
    tr_measure m;
    int rc = e->be.ops->upload(e->be.state, e->curve.x, NULL, err);
    if (rc == TR_OK)
        rc = tr_engine_i_rebuild_contacts(e, 1, NULL, err);
    if (rc == TR_OK)
        rc = tr_engine_i_measure(e, &m, err);
    if (rc == TR_OK)
        tr_engine_i_fill_state(e, &m);
    return rc;
}

int tr_engine_open(tr_engine **out, const tr_curve *c, const char *device, const tr_engine_params *p,
                   tr_error *err)
{
    *out = NULL;
    tr_engine *e = tr_engine_i_new(device, p);
    if (!e)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    int rc = tr_curve_copy(&e->curve, c, err);
    /* the engine's steps move vertices in doubles: a start's low parts
     * (curve.h) would no longer be its vertices' */
    tr_curve_drop_lo(&e->curve);
    if (!rc)
        rc = tr_engine_i_alloc_comp_arrays(e, err);
    if (rc) {
        tr_engine_destroy(e);
        return rc;
    }
    *out = e;
    return TR_OK;
}

int tr_engine_settle_start(tr_engine *e, tr_error *err)
{
    int rc = tr_engine_i_open_backend(e, &e->curve, err);
    if (!rc)
        rc = tr_engine_i_keep_presettle(e, err);
    if (!rc)
        rc = tr_engine_i_settle(e, "the start curve", 0.0, err);
    if (rc == TR_EINTERRUPTED && e->presettle_x)
        rc = keep_unsettled_start(e, err);
    if (rc == TR_EGEOMETRY)
        rc = settle_scaled(e, rc, err);
    if (rc)
        return rc;
    e->h = e->ebar[0];
    return TR_OK;
}

int tr_engine_create(tr_engine **out, const tr_curve *c, const char *device,
                     const tr_engine_params *p, tr_error *err)
{
    tr_engine *e;
    int rc = tr_engine_open(&e, c, device, p, err);
    if (rc)
        return rc;
    if ((rc = tr_engine_settle_start(e, err))) {
        tr_engine_destroy(e);
        return rc;
    }
    *out = e;
    return TR_OK;
}

void tr_engine_destroy(tr_engine *e)
{
    if (!e)
        return;
    free(e->presettle_x);
    tr_engine_i_solver_state_free(e);
    tr_newton_state_free(e->lvl);
    free(e->lvl);
    tr_backend_close(&e->be);
    tr_curve_free(&e->curve);
    free(e->gap);
    free(e->ebar);
    free(e->polish_x);
    free(e->newton_x);
    free(e->newton_lo);
    coarse_drop(e);
    free(e);
}

const char *tr_engine_device(const tr_engine *e) { return e->be.description; }
const char *tr_engine_warning(const tr_engine *e) { return e->be.warning; }

const char *tr_engine_stop_why(const tr_engine *e) { return e->stop_why; }

int tr_engine_checkpoint_failures(const tr_engine *e, const char **why)
{
    if (why)
        *why = e->ckpt_failure;
    return e->ckpt_failures;
}

int tr_engine_step(tr_engine *e, int *accepted, tr_error *err)
{
    const tr_backend_ops *op = e->be.ops;
    int rc;
    *accepted = 0;
    /* the engine moves past a stopped solve: its state no longer goes
     * with the engine's curve, nor a solved level's */
    tr_engine_i_solver_state_drop(e);
    e->lvl_ok = e->lvl_refined = 0;
    if (!e->contacts_valid && (rc = tr_engine_i_rebuild_contacts(e, 1, NULL, err)))
        return rc;
    tr_tension_params tp = {.h = e->h, .max_move = e->prm.max_move, .smooth_passes = e->prm.smooth_passes,
                            .project = e->prm.project ? &e->prm.proj : NULL};
    tr_tension_stats ts;
    tr_correct_stats cs;
    tr_measure m;
    if ((rc = op->save(e->be.state, err)) || (rc = op->tension_step(e->be.state, &tp, &ts, err)) ||
        (rc = op->correct(e->be.state, &e->prm.correct, &cs, err)) || (rc = tr_engine_i_measure(e, &m, err)))
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
        if ((rc = tr_engine_i_rebuild_contacts(e, 1, &m, err)))
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
        if (!e->contacts_valid && (rc = tr_engine_i_rebuild_contacts(e, 1, NULL, err)))
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
    tr_engine_i_fill_state(e, &m);
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
    /* (e->curve holds no low parts: tr_engine_open and the solve drop them) */
    if (e->polish_x && e->steps == e->polish_steps)
        memcpy(out->x, e->polish_x, 3 * out->nv * sizeof *out->x);
    if (e->newton_lo && e->newton_nv == out->nv && !memcmp(out->x, e->newton_x, 3 * out->nv * sizeof *out->x)) {
        if ((rc = tr_curve_want_lo(out, err))) {
            tr_curve_free(out);
            return rc;
        }
        memcpy(out->lo, e->newton_lo, 3 * out->nv * sizeof *out->lo);
    }
    return TR_OK;
}

void tr_engine_i_refine_taken(tr_engine *e)
{
    e->refine_unsettled = 0;
    coarse_drop(e);
}

/* Drops the coarse level tr_engine_refine held (e->coarse). */
static void coarse_drop(tr_engine *e)
{
    if (!e->coarse.held)
        return;
    tr_curve_free(&e->coarse.curve);
    free(e->coarse.ebar);
    free(e->coarse.polish_x);
    memset(&e->coarse, 0, sizeof e->coarse);
}

/* Goes back from a refined level that could not be settled, or that the
 * solver did not take, to the settled coarse level it came from (held in
 * e->coarse, taken over), with the coarse level's flags. */
int tr_engine_i_refine_back(tr_engine *e, int keep_state, tr_error *err)
{
    if (!e->coarse.held)
        return tr_fail(err, TR_EINVAL, "no coarse level to go back to");
    /* a solver state of the refined level is no state of the coarse one,
     * unless the run stops here and its resume goes on with that solve */
    if (!keep_state)
        tr_engine_i_solver_state_drop(e);
    tr_backend_close(&e->be);
    tr_curve_free(&e->curve);
    e->curve = e->coarse.curve;
    double *ebar = e->coarse.ebar;
    int rc = tr_engine_i_alloc_comp_arrays(e, err);
    if (rc == TR_OK)
        rc = tr_engine_i_open_backend(e, &e->curve, err);
    if (rc == TR_OK)
        rc = e->be.ops->upload(e->be.state, e->curve.x, ebar, err);
    free(ebar);
    e->polished = e->coarse.polished;
    free(e->polish_x);
    e->polish_x = e->coarse.polish_x; /* the coarse level's polished curve, if it kept one */
    e->newton_tried = e->coarse.newton_tried;
    e->newton_solved = e->coarse.newton_solved;
    e->h = e->coarse.h;
    e->residual = e->coarse.residual;
    e->disp_est = e->coarse.disp_est;
    e->jammed = e->coarse.jammed;
    memset(&e->coarse, 0, sizeof e->coarse);
    e->refine_unsettled = 0;
    e->lvl_ok = e->lvl_refined = 0;
    free(e->presettle_x);
    e->presettle_x = NULL;
    tr_measure m;
    if (rc == TR_OK && (rc = tr_engine_i_rebuild_contacts(e, 1, NULL, err)) == TR_OK &&
        (rc = tr_engine_i_measure(e, &m, err)) == TR_OK)
        tr_engine_i_fill_state(e, &m);
    return rc;
}

int tr_engine_refine(tr_engine *e, size_t n, tr_error *err)
{
    tr_engine_i_solver_state_drop(e);
    /* the solved level's state goes with its refinement */
    e->lvl_refined = e->lvl_ok;
    e->lvl_ok = 0;
    coarse_drop(e);
    int rc = e->be.ops->download(e->be.state, e->curve.x, NULL, err);
    if (rc)
        return rc;
    tr_curve fine;
    rc = tr_refine_lowpass(&e->curve, n, 0.5, 0.5, &fine, err);
    if (rc)
        return rc;
    /* the settled coarse level, to go back to should the refined level
     * not be settled (the bound stops its settle: a run's best is then the
     * coarse level, not a half-settled finer one; its first-order passes
     * cannot put it on the constraint set; the solver does not take it) */
    double *coarse_ebar = malloc((size_t)e->curve.ncomp * sizeof *coarse_ebar);
    if (!coarse_ebar || (rc = tr_curve_copy(&e->coarse.curve, &e->curve, err))) {
        free(coarse_ebar);
        tr_curve_free(&fine);
        return coarse_ebar ? rc : tr_fail(err, TR_ENOMEM, "out of memory");
    }
    memcpy(coarse_ebar, e->ebar, (size_t)e->curve.ncomp * sizeof *coarse_ebar);
    e->coarse.held = 1;
    e->coarse.ebar = coarse_ebar;
    e->coarse.polished = e->polished;
    e->coarse.polish_x = e->polish_x;
    e->coarse.newton_tried = e->newton_tried;
    e->coarse.newton_solved = e->newton_solved;
    e->coarse.h = e->h;
    e->coarse.residual = e->residual;
    e->coarse.disp_est = e->disp_est;
    e->coarse.jammed = e->jammed;
    e->polish_x = NULL; /* the coarse level's (e->coarse.polish_x), until the settle is done */
    tr_backend_close(&e->be);
    tr_curve_free(&e->curve);
    e->curve = fine;
    if ((rc = tr_engine_i_alloc_comp_arrays(e, err)) || (rc = tr_engine_i_open_backend(e, &e->curve, err)))
        return rc; /* the engine is unusable; destroy frees what it holds */
    /* resampling may bring strands slightly closer than 2 (never near
     * crossing): the correction pushes them back out */
    e->polished = 0;
    /* the new level may go to the solver again (level_loop.c,
     * is_solver_level: a clasp's every level) */
    e->newton_tried = 0;
    e->newton_solved = 0;
    if ((rc = tr_engine_i_keep_presettle(e, err)))
        return rc;
    /* A refined clasp is pressed through itself where strands touch, and
     * its planes forbid scaling it out: the settle's 400 damped passes do
     * not always restore it (the 2 x 800 clasp refined to 2 x 1000), and
     * the solver takes the level from the curve before the settle
     * (presettle_x; level_loop.c, run_polish) whatever the settle did. As
     * first-order steps do not tighten a clasp beyond ~100 vertices per
     * rope, a clasp whose levels the solver takes is not settled at all:
     * make clasp in one command, with the rejected-but-settled levels
     * counted as solved (tr_engine_i_newton), went from 74 s to 33.5 s at
     * 2 x 1000 and from 111 s to 25 s at 2 x 2000
     * (bench/notes/2026-11-25-clasps-through-solver.md).
     * Should the solver not take the level, the engine goes back to the
     * coarse level, held until then (level_loop.c). */
    int to_solver = e->curve.ncst > 0 && (e->prm.newton || e->prm.newton_tight) && e->prm.polish;
    rc = to_solver ? TR_EGEOMETRY : tr_engine_i_settle(e, "the refined curve", 0.25, err);
    /* A closed knot's refined level that the settle's first-order passes
     * cannot put on the constraint set (the converged 4_1 of 513 vertices,
     * at N 800 refined to 1600: 400 passes, 130 s) failed the whole run
     * with nothing written. It goes back to the coarse level, which is
     * the run's result (tighten says the refinement stopped short, and
     * why). Given to the solver as a clasp's level is, the low-pass curve
     * settled at 1600 (254 steps), but at 2400 from the converged 1600 the
     * solver ran 4688 steps and rejected it (the spline's 2400 settled in
     * 382): a rejection there would lose the run again. */
    int take = rc == TR_EGEOMETRY && e->presettle_x && to_solver;
    if (rc == TR_EINTERRUPTED || (rc == TR_EGEOMETRY && !take)) {
        tr_error e2;
        if (rc == TR_EGEOMETRY)
            tr_fail_wrap(err, rc, "refining to %zu vertices", n);
        int rc2 = tr_engine_i_refine_back(e, 0, &e2);
        if (rc2)
            *err = e2;
        return rc2 ? rc2 : rc;
    }
    e->refine_unsettled = 0;
    if (take) {
        /* the coarse level stays held until the solver has had the level */
        e->refine_unsettled = 1;
        e->refine_unsettled_n = n;
        rc = TR_OK;
    } else
        coarse_drop(e);
    if (rc)
        return rc;
    e->h = e->ebar[0];
    e->jammed = 0;
    return TR_OK;
}
