/* This file contains the engine's level loop, tr_engine_run (engine.h): the
 * levels of a refinement, the backend each level runs on, the polish stage
 * (or at the finest level the second-order solver), the stop rules, progress
 * and periodic checkpoints. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/engine.h"
#include "engine/engine_internal.h"
#include "engine/polish.h"
#include "oracle/thickness.h"
#include "util/clock.h"

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

/* The polish stage: download, polish on the host (or, at the finest level
 * with prm.newton, the second-order solver), upload and settle onto the
 * engine's exact constraint set (equal edges to 1e-9). The polished curve
 * is at thickness 1 with every constraint satisfied, so settle moves it by
 * no more than its edge deviation. */
static int run_polish(tr_engine *e, double seconds, double target, int solver_level, int tight_only,
                      volatile sig_atomic_t *stop, tr_error *err)
{
    int newton = solver_level && (e->prm.newton || (tight_only && e->prm.newton_tight));
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
    /* the solver at the level's start takes the curve from before the
     * settle (engine_internal.h, presettle_x) */
    if (newton && tight_only && e->presettle_x)
        memcpy(e->curve.x, e->presettle_x, nx * sizeof *keep);
    tr_polish_stats ps;
    memset(&ps, 0, sizeof ps);
    if (newton) {
        /* at the finest level the second-order solver takes the polish's
         * place (bench/RESULTS.md, "Trefoil: the ladder and the paper's
         * numbers") */
        int nacc = 0;
        if ((rc = tr_engine_i_newton(e, seconds, tight_only, stop, &nacc, err))) {
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
        /* the polish moves past a stopped solve (its state is dropped),
         * and past a solved level's */
        tr_engine_i_solver_state_drop(e);
        e->lvl_ok = e->lvl_refined = 0;
        tr_polish_params pp;
        tr_polish_params_default(&pp);
        pp.time_limit = seconds;
        pp.target = target;
        pp.stop = stop;
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
        memcpy(e->curve.x, keep, nx * sizeof *keep);
        free(keep);
        return TR_OK;
    }
    /* a refined clasp's solved curve, should the settle below fail: the
     * level has no settled state to go back to (keep is the refinement,
     * pressed through itself), so the solver's curve is the engine's */
    double *solved = NULL;
    if (newton && e->refine_unsettled) {
        if (!(solved = malloc(nx * sizeof *solved))) {
            free(keep);
            return tr_fail(err, TR_ENOMEM, "out of memory");
        }
        memcpy(solved, e->curve.x, nx * sizeof *solved);
    }
    if ((rc = e->be.ops->upload(e->be.state, e->curve.x, NULL, err)))
        goto restore;
    e->contacts_valid = 0;
    if ((rc = tr_engine_i_settle(e, "the polished curve", 0.0, err)))
        goto restore;
    free(solved);
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
restore:;
    /* the engine could not take the polished curve on (or the bound
     * stopped its settle): go on from its own */
    int rc_settle = rc;
    if (rc == TR_ENOMEM || rc == TR_EOPENCL) {
        free(keep);
        free(solved);
        return rc;
    }
    if (solved) {
        /* The refined clasp the solver took, which the engine's settle
         * could not put on its exact edge set (2 x 1600 refined to
         * 2 x 3200 on the way to 2 x 48 000: solved, accepted, the settle
         * failed, and the level was lost): the solver's curve, a rope at
         * thickness 1 to 1e-6 with its ends on their planes and its edges
         * equal to the solver's tolerance, becomes the engine's state as
         * it is. A clasp's level is the solver's (first-order steps do not
         * tighten it), so no step needs the exact edge set after it. */
        free(keep);
        memcpy(e->curve.x, solved, nx * sizeof *solved);
        free(solved);
        e->contacts_valid = 0;
        tr_measure m;
        if ((rc = e->be.ops->upload(e->be.state, e->curve.x, NULL, err)) ||
            (rc = tr_engine_i_rebuild_contacts(e, 1, NULL, err)) || (rc = tr_engine_i_measure(e, &m, err)))
            return rc;
        tr_engine_i_fill_state(e, &m);
        e->polished = 1;
        e->polish_why = NULL;
        e->h = e->ebar[0];
        e->jammed = 0;
        return TR_OK;
    }
    /* Stopped by the bound: the polished (or solved) curve is a rope at
     * thickness 1 with its constraints held, only not yet on the engine's
     * exact edge set; it is the run's best, so it is what the run hands
     * out (polish_x, as when a settle costs length), while the engine
     * goes back to its own settled state. */
    double *polished_x = NULL;
    if (rc_settle == TR_EINTERRUPTED && ps.accepted) {
        polished_x = malloc(3 * e->curve.nv * sizeof *polished_x);
        if (polished_x)
            memcpy(polished_x, e->curve.x, 3 * e->curve.nv * sizeof *polished_x);
    }
    memcpy(e->curve.x, keep, 3 * e->curve.nv * sizeof *keep);
    /* the solve's state is not the state of this curve */
    e->lvl_ok = e->lvl_refined = 0;
    rc = e->be.ops->upload(e->be.state, keep, keep + 3 * e->curve.nv, err);
    free(keep);
    tr_measure m;
    if (rc == TR_OK && (rc = tr_engine_i_rebuild_contacts(e, 1, NULL, err)) == TR_OK)
        rc = tr_engine_i_measure(e, &m, err);
    if (rc) {
        free(polished_x);
        return rc;
    }
    tr_engine_i_fill_state(e, &m);
    if (polished_x) {
        free(e->polish_x);
        e->polish_x = polished_x;
        e->polish_steps = e->steps;
        e->polished = 1;
        e->polish_after = ps.ropelength_after;
        e->polish_why = NULL;
        return TR_OK;
    }
    e->polished = -1;
    e->polish_after = e->polish_before;
    e->polish_why = rc_settle == TR_EINTERRUPTED ? "stopped before the polished curve was settled"
                                                 : "the engine could not settle the polished curve";
    return TR_OK;
}

/* ---- the run loop with levels, stops, checkpoints, progress ---- */

/* The levels the second-order solver may take: the finest, and for ropes
 * with vertex constraints (clasps) every level. A clasp's first-order
 * steps do not tighten it beyond ~100 vertices per rope
 * (bench/notes/2026-11-25-clasps-through-solver.md), while a tight
 * coarser clasp refined is pressed a
 * little through itself and the solver restores and tightens it in well
 * under a second at 2 x 200; so the route for a clasp is the first-order
 * steps at the coarsest level and the solver at each refined one. A
 * closed knot's levels go to the solver from SOLVER_LEVEL_MIN_N vertices
 * per component on (its warm start says whether the refined level is
 * tight; a loose one is handed back to the first-order steps within a
 * second or two): the first-order steps need ~N^2 of them, and from the
 * N = 400 torus knot refined to 9600 the coarse levels by first-order
 * steps and the polish took 290 s and left 9600 loose (32.8270 at the end),
 * where with the solver from 800 on the run ends at 32.7429444 in 188 s.
 * Below 800 the first-order steps converge in seconds. */
#define SOLVER_LEVEL_MIN_N 800
static int is_solver_level(const tr_engine *e, int final_level)
{
    return final_level || e->curve.ncst > 0 || e->curve.nv / (size_t)e->curve.ncomp >= SOLVER_LEVEL_MIN_N;
}

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
    if ((rc = tr_engine_i_open_backend(e, &e->curve, err)))
        return rc;
    return e->be.ops->upload(e->be.state, e->curve.x, e->ebar, err);
}

/* A checkpoint that cannot be written (the disk full, its folder gone)
 * costs the run nothing but the checkpoint: the failure is kept for the
 * caller to report (tr_engine_checkpoint_failures) and the run goes on.
 * Any other failure (reading the state back from the device) stops it. */
static int checkpoint(tr_engine *e, const char *path, tr_error *err)
{
    tr_error ce = {0};
    int rc = tr_engine_checkpoint_write(e, path, &ce);
    if (rc == TR_EIO) {
        e->ckpt_failures++;
        snprintf(e->ckpt_failure, sizeof e->ckpt_failure, "%.255s", ce.msg);
        return TR_OK;
    }
    if (rc)
        *err = ce;
    return rc;
}

#define STALL_STEPS 200
#define STALL_REL 1e-5

static int run_levels(tr_engine *e, const tr_engine_limits *lim, tr_stop_reason *why, tr_error *err);

int tr_engine_run(tr_engine *e, const tr_engine_limits *lim, tr_stop_reason *why, tr_error *err)
{
    /* the run's stop flag joins the engine's hard bound while it runs, so
     * that the settles of its refinements and polishes stop at a signal.
     * Its time_limit does not: that is this run's share of the time (a
     * road of tighten --tries), which the steps keep to; a settle begun
     * within it finishes, within the hard bound (params.bound) */
    tr_deadline keep = e->bound;
    if (lim->stop)
        e->bound.stop = lim->stop;
    int rc = run_levels(e, lim, why, err);
    e->bound = keep;
    return rc;
}

static int run_levels(tr_engine *e, const tr_engine_limits *lim, tr_stop_reason *why, tr_error *err)
{
    int rc;
    /* the first checkpoint at once, then one every checkpoint_every: a run
     * killed in its first minutes (a closed terminal, kill -9) can resume */
    double t_last_ckpt = -INFINITY, t_last_prog = 0.0;
    double level_t0 = tr_clock_seconds();
    /* Without a time limit to share out, a level is polished (and a coarse
     * one refined) once the engine stalls: less than STALL_REL shorter over
     * STALL_STEPS steps. The projection engine crawls long before it jams
     * (the 2 x 100 clasp: 8800 steps, 100 s, where polish then needs 2 s). */
    long stall_step = e->steps;
    double stall_len = INFINITY;
    e->ckpt_path = lim->checkpoint_path;
    e->ckpt_every = lim->checkpoint_every;
    double time_left_at_level = lim->time_limit > 0 ? lim->time_limit - (e->elapsed_base + tr_clock_seconds() - e->t0) : 0;
    *why = TR_STOP_NONE;
    e->stop_why[0] = '\0';
    e->stop_pending = TR_STOP_NONE;
    e->ckpt_hold = 0;
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
        int past = tr_deadline_passed(&e->bound);
        if (e->stop_why[0])
            stop = TR_STOP_REFINE;
        else if (e->stop_pending != TR_STOP_NONE)
            stop = e->stop_pending;
        else if (past == 2)
            stop = TR_STOP_SIGNAL;
        else if (past == 1 || (lim->time_limit > 0 && p.elapsed >= lim->time_limit))
            stop = TR_STOP_TIME;
        else if (lim->max_steps > 0 && e->steps >= lim->max_steps)
            stop = TR_STOP_STEPS;
        /* (a refined clasp before the solver has had it has no figures of
         * its own yet: the coarse level's residual and jam are not its) */
        else if (final_level && !e->refine_unsettled && lim->target > 0 && p.ropelength <= lim->target)
            stop = TR_STOP_TARGET;
        else if (final_level && !e->refine_unsettled && e->steps > 0 && lim->residual > 0 &&
                 e->residual < lim->residual)
            stop = TR_STOP_RESIDUAL;
        else if (final_level && !e->refine_unsettled && e->jammed)
            stop = TR_STOP_JAMMED;
        else if (final_level && e->newton_solved)
            stop = TR_STOP_SOLVED;
        /* The route: a tight start at the finest level (a converged knot
         * refined, or resampled by --n) goes to the second-order solver at
         * once, which converges there in tens of Newton steps where the
         * first-order steps need ~N^2; a loose one (the solver's warm start
         * says which, in a second) takes the first-order steps first and
         * the solver in the polish's place. */
        if (is_solver_level(e, final_level) && stop == TR_STOP_NONE && (e->prm.newton || e->prm.newton_tight) &&
            e->prm.polish && !e->newton_tried) {
            double left = lim->time_limit > 0 ? lim->time_limit - p.elapsed : 0.0;
            /* a coarse level has half the time left when it began (below) */
            if (!final_level)
                left = 0.5 * time_left_at_level - (tr_clock_seconds() - level_t0);
            if ((rc = run_polish(e, lim->time_limit > 0 ? fmax(left, 1e-3) : 0.0, lim->target, 1, 1, lim->stop,
                                 err)))
                return rc;
            if (e->refine_unsettled && !(e->newton_ran == 1 && e->polished == 1)) {
                /* a refined clasp the solver did not take goes back to its
                 * coarse level, the run's result, and the run stops there
                 * (TR_STOP_REFINE), as a closed knot's unsettled level does:
                 * a rejection here once failed the run with nothing written
                 * (2 x 48 000 with short ends, at 2 x 6400 after two hours;
                 * that rejection was the solver's own defect, newton.c,
                 * has_best) */
                size_t n = e->refine_unsettled_n;
                char why[200];
                snprintf(why, sizeof why, "%.190s",
                         e->newton_why[0]       ? e->newton_why
                         : e->newton_unfinished ? "it did not finish in the level's share of the time"
                         : e->polish_why        ? e->polish_why
                                                : "not run");
                /* A solve the run's time or a signal stopped (the solver
                 * stops a little before its limit, to restore its best,
                 * so the clock may not show the limit reached yet): the
                 * run stops on that, its result the coarse level, and the
                 * solver's own checkpoint and state of the refined level
                 * stay for a resume to go on with (a long clasp stopped
                 * at a session's end would otherwise start that level's
                 * solve again). */
                int past_now = tr_deadline_passed(&e->bound);
                int run_time = e->newton_unfinished && (past_now || (final_level && lim->time_limit > 0));
                if ((rc = tr_engine_i_refine_back(e, run_time, err)))
                    return rc;
                if (run_time) {
                    e->stop_pending = past_now == 2 ? TR_STOP_SIGNAL : TR_STOP_TIME;
                    e->ckpt_hold = 1;
                    continue;
                }
                snprintf(e->stop_why, sizeof e->stop_why,
                         "refining to %zu vertices: the second-order solver did not take the refined clasp (%s)", n,
                         why);
                continue;
            }
            tr_engine_i_refine_taken(e);
            /* a rejected solve leaves the level to the first-order polish,
             * unless it counted as solved (a clasp already at the level's
             * optimum: engine.c, tr_engine_i_newton) */
            if (e->newton_ran != 1 && !e->newton_solved)
                e->polished = 0;
            continue;
        }
        int can_polish = e->prm.polish && e->polished == 0;
        if (final_level && can_polish &&
            (stop == TR_STOP_RESIDUAL || stop == TR_STOP_JAMMED || (stop == TR_STOP_NONE && stalled) ||
             (stop == TR_STOP_NONE && lim->time_limit > 0 &&
              tr_clock_seconds() - level_t0 >= (1.0 - e->prm.polish_share) * time_left_at_level))) {
            double left = lim->time_limit > 0 ? lim->time_limit - p.elapsed : 0.0;
            if ((rc = run_polish(e, lim->time_limit > 0 ? fmax(left, 1e-3) : 0.0, lim->target, 1, 0,
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
            if (e->jammed || stalled || (e->steps > 0 && e->residual < coarse_res) || (pc && e->polished != 0) ||
                e->newton_solved)
                level_done = 1;
            if (lim->time_limit > 0 && used > (pc ? 0.25 : 0.5) * time_left_at_level)
                level_done = 1;
            if (level_done && pc && e->polished == 0) {
                double budget = lim->time_limit > 0 ? fmax(0.5 * time_left_at_level - used, 1e-3) : 0.0;
                if ((rc = run_polish(e, budget, 0.0, 0, 0, lim->stop, err)))
                    return rc;
                continue;
            }
        }
        if (stop != TR_STOP_NONE && e->refine_unsettled) {
            /* stopped before the solver had the refined clasp (a signal, the
             * time): the run's result is the coarse level it came from */
            if ((rc = tr_engine_i_refine_back(e, 0, err)))
                return rc;
            tr_engine_get_progress(e, &p);
        }
        if (lim->progress && (stop != TR_STOP_NONE || tr_clock_seconds() - t_last_prog >= lim->progress_every)) {
            lim->progress(&p, lim->user);
            t_last_prog = tr_clock_seconds();
        }
        if (stop != TR_STOP_NONE) {
            *why = stop;
            if (lim->checkpoint_path && !e->ckpt_hold && (rc = checkpoint(e, lim->checkpoint_path, err)))
                return rc;
            return TR_OK;
        }
        if (level_done) {
            size_t n = e->curve.nv / (size_t)e->curve.ncomp;
            size_t next = 2 * n < lim->refine_to ? 2 * n : lim->refine_to;
            /* tr_engine_refine opens the next level's backend */
            e->coarse_ref = wants_coarse_ref(e, next * (size_t)e->curve.ncomp, is_final_level(lim, next));
            /* a refinement whose settle the bound stopped has gone back
             * to this level: the loop then stops on the bound */
            rc = tr_engine_refine(e, next, err);
            if (rc == TR_EGEOMETRY) {
                /* back at this level, its curve the run's: the next pass
                 * stops there as on any other stop (TR_STOP_REFINE) */
                snprintf(e->stop_why, sizeof e->stop_why, "%.500s", err->msg);
                continue;
            }
            if (rc && rc != TR_EINTERRUPTED)
                return rc;
            level_t0 = tr_clock_seconds();
            stall_step = e->steps;
            stall_len = INFINITY;
            time_left_at_level = lim->time_limit > 0 ? lim->time_limit - (e->elapsed_base + tr_clock_seconds() - e->t0) : 0;
            continue;
        }
        if (lim->checkpoint_path && lim->checkpoint_every > 0 && tr_clock_seconds() - t_last_ckpt >= lim->checkpoint_every) {
            if ((rc = checkpoint(e, lim->checkpoint_path, err)))
                return rc;
            t_last_ckpt = tr_clock_seconds();
        }
        int acc;
        if ((rc = tr_engine_step(e, &acc, err)))
            return rc;
    }
}
