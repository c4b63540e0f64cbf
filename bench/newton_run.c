/* bench/newton_run: the second-order solver (host/newton.h) alone on a
 * curve, optionally spline-resampled to N vertices per component, with one
 * progress line per Newton step: how the solver is measured apart from the
 * engine's route (bench/RESULTS.md, "Trefoil: the ladder and the paper's
 * numbers").
 *   newton_run [--device SPEC] IN.vect OUT.vect [N | sN] [TIME_LIMIT_S] [CKPT_S]
 * N: the engine's low-pass refinement; sN: the cubic spline tighten --n
 * uses (tr_resample_smooth). --device: the strut rows by that backend
 * (backend.h strut_rows; "reference", "opencl", "pocl", ...), exactly the
 * device named (no fallback); without it the solver's own host path.
 * CKPT_S: every CKPT_S seconds the solver's best iterate goes to
 * OUT.ckpt (what a long run keeps, and what to measure when the oracle
 * rejects a result).
 * --state: the solver's state (newton.h tr_newton_state: the iterate as the
 * solver holds it, not rescaled, with its multipliers, penalty and loop
 * counters) goes to OUT.state every CKPT_S seconds (300 without CKPT_S) and
 * when the run stops unfinished (its time limit, or SIGINT, SIGTERM or
 * SIGHUP, which stop it at the next step: then OUT is not written, so that
 * a stopped rung is not taken for a finished one). --resume STATE: go on
 * from that state instead of from IN's positions; IN and N must give the
 * curve the state was taken on (its vertices per component; the start's
 * ropelength is what a result must beat). STATE is read whole at the start
 * and never written (a resumed run writes OUT.state, which must be another
 * file).
 * --state-end: a solve that converged or settled writes its state to
 * OUT.state as well (newton.h end_state). --coarse STATE: start from the
 * multipliers of STATE, the end state of the level IN was solved at, carried
 * to IN refined to N (newton.h coarse; prolong.c): how a clasp's levels are
 * measured apart from the engine's route (bench/notes/2026-11-29-clasp-prolongation.md).
 *   newton_run --restore IN.vect OUT.vect
 * the restoration alone (newton.h tr_newton_restore) on IN scaled so that
 * its closest strut is at 2: a checkpoint or result that the rescaling
 * charged for MinRad rows over is then the iterate as the solver held it
 * (struts at 2, MinRad rows over), and OUT is it restored and rescaled to
 * thickness 1 where the oracle measures that shorter, else as scaled. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <string.h>

#include "backend/backend.h"
#include "cli/cli_interrupt.h"
#include "curve/curve_io.h"
#include "curve/generate.h"
#include "engine/refine_lowpass.h"
#include "solver/newton.h"
#include "oracle/thickness.h"
#include "util/text_file.h"

/* where the checkpoints and the states go (the callbacks' user) */
typedef struct run_files {
    char ckpt[4096], state[4096];
} run_files;

static double l0_min(const tr_newton_state *s)
{
    double m = INFINITY;
    for (int k = 0; k < s->ncomp; k++)
        m = fmin(m, s->l0[k]);
    return m;
}

static int write_state(void *user, const tr_newton_state *s, tr_error *err)
{
    const char *path = ((const run_files *)user)->state;
    int rc = tr_newton_state_write(path, s, err);
    if (rc)
        fprintf(stderr, "newton_run: state not written: %s\n", err->msg);
    else
        printf("state at step %d (outer %d, mu %.1e, %ld steps and %.0f s in all) written to %s\n", s->iter, s->outer,
               s->mu * l0_min(s), s->steps, s->seconds, path);
    fflush(stdout);
    return rc;
}

static int write_ckpt(void *user, const tr_curve *best, tr_error *err)
{
    return tr_curve_write(((const run_files *)user)->ckpt, TR_FORMAT_VECT, best, "newton_run checkpoint", err);
}

static void show(void *user, const tr_newton_progress *p)
{
    (void)user;
    printf("it %3d outer %2d  length %.10f  viol %.2e (e %.0e m %.0e s %.0e)  stat %.2e  mu %.1e  lm %.1e  step %.3f  struts %zu "
           "active %zu  worst MinRad at %zu  %.2f s\n",
           p->iter, p->outer, p->length, p->viol, p->viol_edge, p->viol_minrad, p->viol_strut, p->stat, p->mu, p->lm,
           p->step, p->struts, p->active, p->worst_minrad, p->seconds);
    fflush(stdout);
}

static int restore_only(const char *in, const char *out)
{
    tr_error err = {0};
    tr_curve c = {0};
    tr_thickness th0, th1;
    if (tr_curve_read(in, TR_FORMAT_AUTO, &c, &err) || tr_thickness_measure(&c, NULL, &th0, NULL, &err)) {
        fprintf(stderr, "newton_run: %s\n", err.msg);
        return 1;
    }
    if (isfinite(th0.dcsd)) {
        double f = 2.0 / th0.dcsd;
        tr_curve_scale_by(&c, f);
    }
    double before, after;
    if (tr_newton_restore(&c, NULL, &before, &after, &err) || tr_thickness_measure(&c, NULL, &th1, NULL, &err)) {
        fprintf(stderr, "newton_run: %s\n", err.msg);
        return 1;
    }
    printf("restore: ropelength %.10f -> %.10f, row violation %.2e -> %.2e, MinRad %.12f dcsd %.12f\n",
           th0.ropelength, th1.ropelength, before, after, th1.minrad, th1.dcsd);
    if (tr_curve_write(out, TR_FORMAT_AUTO, &c, "newton_run --restore", &err)) {
        fprintf(stderr, "newton_run: %s\n", err.msg);
        return 1;
    }
    tr_curve_free(&c);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 4 && !strcmp(argv[1], "--restore"))
        return restore_only(argv[2], argv[3]);
    const char *device = NULL, *resume = NULL, *coarse = NULL;
    int vertex = 0, keep_state = 0, state_end = 0;
    for (;;) {
        if (argc > 2 && !strcmp(argv[1], "--device")) {
            device = argv[2];
            argv += 2;
            argc -= 2;
        } else if (argc > 1 && !strcmp(argv[1], "--state")) {
            keep_state = 1;
            argv++;
            argc--;
        } else if (argc > 2 && !strcmp(argv[1], "--resume")) {
            resume = argv[2];
            argv += 2;
            argc -= 2;
        } else if (argc > 2 && !strcmp(argv[1], "--coarse")) {
            /* the multipliers of a coarser level's state (newton.h coarse) */
            coarse = argv[2];
            argv += 2;
            argc -= 2;
        } else if (argc > 1 && !strcmp(argv[1], "--state-end")) {
            /* a converged or settled solve's state to OUT.state too (newton.h end_state) */
            keep_state = state_end = 1;
            argv++;
            argc--;
        } else if (argc > 1 && !strcmp(argv[1], "--vertex")) {
            /* SP-FEM's vertex contacts (newton.h vertex_contacts) */
            vertex = 1;
            argv++;
            argc--;
        } else
            break;
    }
    if (argc < 3) {
        fprintf(stderr, "usage: newton_run [--device SPEC] [--vertex] [--state] [--state-end] [--resume STATE] [--coarse STATE] IN OUT [N | sN] "
                        "[TIME_LIMIT_S] [CKPT_S]\n"
                        "       newton_run --restore IN OUT\n");
        return 2;
    }
    tr_error err = {0};
    tr_curve c = {0}, r = {0};
    run_files files;
    snprintf(files.ckpt, sizeof files.ckpt, "%s.ckpt", argv[2]);
    snprintf(files.state, sizeof files.state, "%s.state", argv[2]);
    const char *state_path = files.state;
    if (resume && (tr_same_file(resume, argv[2]) || (keep_state && tr_same_file(resume, state_path)))) {
        fprintf(stderr, "newton_run: %s is the state to resume from: it is never written over (move it first)\n",
                resume);
        return 2;
    }
    tr_newton_state from = {0};
    if (resume && tr_newton_state_read(resume, &from, &err)) {
        fprintf(stderr, "newton_run: %s\n", err.msg);
        return 2;
    }
    tr_newton_state coarse_state = {0};
    if (coarse && tr_newton_state_read(coarse, &coarse_state, &err)) {
        fprintf(stderr, "newton_run: %s\n", err.msg);
        return 2;
    }
    if (tr_curve_read(argv[1], TR_FORMAT_AUTO, &c, &err)) {
        fprintf(stderr, "newton_run: %s\n", err.msg);
        return 1;
    }
    int spline = argc > 3 && argv[3][0] == 's';
    long nn = argc > 3 ? atol(argv[3] + spline) : 0;
    if (nn > 0) {
        /* as the engine refines (tr_engine_refine), or as tighten --n adds
         * vertices */
        size_t per[64];
        if (spline && c.ncomp > 64) {
            fprintf(stderr, "newton_run: sN is for at most 64 components\n");
            return 2;
        }
        for (int k = 0; k < c.ncomp && k < 64; k++)
            per[k] = (size_t)nn;
        if (spline ? tr_resample_smooth(&c, per, &r, &err) : tr_refine_lowpass(&c, per[0], 0.5, 0.5, &r, &err)) {
            fprintf(stderr, "newton_run: %s\n", err.msg);
            return 1;
        }
        tr_curve_free(&c);
        c = r;
    }
    tr_newton_params p;
    tr_newton_params_default(&p);
    p.vertex_contacts = vertex;
    p.progress = show;
    if (argc > 4)
        p.time_limit = atof(argv[4]);
    /* the bend cap and the pass's end, for measuring them (newton.h
     * max_bend, inner_decrement, minrad_guard; 0 turns the latter two off;
     * NEWTON_MU_MAX the penalty's cap, mu_max; NEWTON_MU_LATE its late
     * rise, mu_late, 0 none; NEWTON_SKIN the strut list's skin, with a
     * step's cap skin / 8 unless NEWTON_MAX_MOVE) */
    if (getenv("NEWTON_MINRAD_GUARD"))
        p.minrad_guard = atof(getenv("NEWTON_MINRAD_GUARD"));
    if (getenv("NEWTON_MAX_BEND"))
        p.max_bend = atof(getenv("NEWTON_MAX_BEND"));
    /* loop iterations (Newton steps and multiplier updates) from the
     * solve's start (a resumed run's count goes on from its state's): a
     * stop at a given step, for measuring a resume */
    if (getenv("NEWTON_MU_MAX"))
        p.mu_max = atof(getenv("NEWTON_MU_MAX"));
    if (getenv("NEWTON_MU_LATE"))
        p.mu_late = atof(getenv("NEWTON_MU_LATE"));
    if (getenv("NEWTON_SKIN")) {
        p.skin = atof(getenv("NEWTON_SKIN"));
        p.max_move = p.skin / 8;
    }
    if (getenv("NEWTON_MAX_MOVE"))
        p.max_move = atof(getenv("NEWTON_MAX_MOVE"));
    if (getenv("NEWTON_MAX_ITER"))
        p.max_iter = atoi(getenv("NEWTON_MAX_ITER"));
    if (getenv("NEWTON_INNER_DECREMENT"))
        p.inner_decrement = atof(getenv("NEWTON_INNER_DECREMENT"));
    p.user = &files;
    if (argc > 5) {
        p.checkpoint_every = atof(argv[5]);
        p.checkpoint = write_ckpt;
    }
    if (keep_state) {
        p.state_every = argc > 5 ? atof(argv[5]) : 300.0;
        p.state = write_state;
        /* SIGINT, SIGTERM, SIGHUP: the solver stops at its next step and
         * hands its state over (the commands' flag, cli_interrupt.h) */
        tr_cli_catch_interrupts();
        p.stop = tr_cli_interrupt_flag();
    }
    tr_newton_state end_state = {0};
    if (state_end)
        p.end_state = &end_state;
    if (coarse) {
        p.coarse = &coarse_state;
        if (getenv("NEWTON_COARSE_MU"))
            p.coarse_mu = atof(getenv("NEWTON_COARSE_MU"));
    }
    if (resume) {
        /* the multipliers by the warm start instead of the state's, for
         * measuring which resumes better */
        p.resume_warm = getenv("NEWTON_RESUME_WARM") && atoi(getenv("NEWTON_RESUME_WARM"));
        p.resume = &from;
        printf("resuming from %s: step %d, outer %d, mu %.1e, %ld steps and %.0f s before%s\n", resume, from.iter,
               from.outer, from.mu * l0_min(&from), from.steps, from.seconds,
               p.resume_warm ? " (multipliers by the warm start)" : "");
    }
    tr_backend be = {0};
    if (device) {
        if (tr_backend_open_device(device, &c, 0, &be, &err)) {
            fprintf(stderr, "newton_run: %s\n", err.msg);
            return 1;
        }
        printf("strut rows on %s\n", be.description);
        p.backend = &be;
    }
    tr_newton_stats st;
    int rc = tr_newton(&c, &p, &st, &err);
    if (device)
        tr_backend_close(&be);
    if (rc) {
        fprintf(stderr, "newton_run: %s\n", err.msg);
        return 1;
    }
    printf("newton: %s%s, ropelength %.10f -> %.10f, %d steps, %d updates, %d factorizations, %d analyses, %d rebuilds, %.2f s "
           "(eval %.2f [strut rows %.2f], factor %.2f [analyses %.2f], solve %.2f, search %.2f [evaluations %.2f], rebuild %.2f), viol %.1e stat %.1e, struts %zu active %zu, warm residual %.2e%s%s\n",
           st.accepted ? "accepted" : "rejected", st.converged ? " converged" : (st.settled ? " settled" : ""), st.ropelength_before,
           st.ropelength_after, st.iters, st.outer, st.factorizations, st.analyses, st.rebuilds, st.seconds, st.t_eval, st.t_rows,
           st.t_factor, st.t_analyze, st.t_solve, st.t_search, st.t_value, st.t_rebuild, st.max_viol, st.stat, st.struts, st.active, st.warm_residual,
           st.why_rejected ? " - " : "", st.why_rejected ? st.why_rejected : "");
    printf("memory at the largest factorisation: Hessian triplets %zu (%.0f MB), compressed entries %zu (%.0f MB with the "
           "kept pattern), factor entries %zu (%.0f MB)\n",
           st.hess_triplets, 24e-6 * (double)st.hess_triplets, st.hess_entries, 20e-6 * (double)st.hess_entries,
           st.factor_entries, 8e-6 * (double)st.factor_entries);
    tr_newton_state_free(&from);
    tr_newton_state_free(&coarse_state);
    if (end_state.nv > 0) {
        if (tr_newton_state_write(state_path, &end_state, &err)) {
            fprintf(stderr, "newton_run: %s\n", err.msg);
            return 1;
        }
        printf("the end state written to %s\n", state_path);
        tr_newton_state_free(&end_state);
    }
    if (tr_cli_interrupted()) {
        fprintf(stderr, "newton_run: stopped by a signal; %s not written, the state is in %s (resume with --resume)\n",
                argv[2], state_path);
        return 1;
    }
    if (st.accepted && tr_curve_write(argv[2], TR_FORMAT_AUTO, &c, "newton_run", &err)) {
        fprintf(stderr, "newton_run: %s\n", err.msg);
        return 1;
    }
    tr_curve_free(&c);
    return 0;
}
