/* tr_tighten (tighten.h): the roads one after the other, each opened,
 * run and certified on its own engine, and the best kept. --time-limit is
 * a bound on the whole call (every road, shuffle, settle and solve looks
 * at it), not only on the engine's steps. */
#include "tighten/tighten.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/curve_io.h"
#include "tighten/knot_type.h"
#include "tighten/road_checkpoint.h"
#include "tighten/tighten_internal.h"
#include "util/clock.h"
#include "util/text_file.h"

void tr_tighten_options_default(tr_tighten_options *opt)
{
    *opt = (tr_tighten_options){.name = "the start",
                                .device_from = -1,
                                .residual = 1e-4,
                                .checkpoint_every = 300,
                                .polish = 1,
                                .seed = 1,
                                .kkt = -1,
                                .auto_route = 1,
                                .centre = 1,
                                .progress_every = 0.25};
}

void tt_note(const tt_opts *o, int kind, const char *fmt, ...)
{
    if (!o->call->note)
        return;
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    o->call->note(kind, msg, o->call->user);
}

tr_deadline tt_bound(const tt_opts *o) { return (tr_deadline){.at = o->bound_at, .stop = o->call->cancel}; }

int tt_cancelled(const tt_opts *o) { return o->call->cancel && *o->call->cancel; }

void tt_scale_curve(tr_curve *c, double f)
{
    tr_curve_scale_by(c, f);
    for (int q = 0; q < c->ncst; q++) {
        for (int a = 0; a < 3; a++)
            c->cst[q].p[a] *= f;
        c->cst[q].d *= f;
    }
}

/* What the bound keeps back of the time limit T for the run to end in: the
 * step, settle pass or solver iteration under way when the bound passes
 * (each looks at the clock only between its own iterations: up to a second
 * at N = 9600 on a loaded machine), the certificate and the write. Beside
 * two busy loops, `--refine-to 9600 --time-limit 40` ended 0.1 to 2 s past
 * its limit without it. */
static double finish_reserve(double t) { return fmin(0.05 * t, 2.0); }

/* What the run needs of its start and its outputs, checked before it
 * starts: refine_to refines, it never coarsens (any component above it
 * is an error), and the output's format and both paths. */
static int check_outputs(const tt_opts *o, tr_engine *e, tr_error *err)
{
    tr_curve c = {0};
    size_t refine_to = (size_t)o->refine_to;
    int rc = tr_engine_get_curve(e, &c, err);
    for (int k = 0; rc == TR_OK && refine_to > 0 && k < c.ncomp; k++)
        if (tr_comp_nv(&c, k) > refine_to)
            rc = tr_fail(err, TR_EINVAL, "--refine-to %zu is below the %zu vertices of component %d of the start; "
                         "it refines, it does not coarsen (--n resamples a start)", refine_to, tr_comp_nv(&c, k), k);
    if (rc == TR_OK && o->out)
        rc = tr_curve_check_output(o->out, TR_FORMAT_AUTO, &c, err);
    tr_curve_free(&c);
    if (rc == TR_OK && o->ckpt)
        rc = tr_check_writable(o->ckpt, err);
    return rc;
}

/* resume: what the run was asked for and the options do not say again is
 * taken from the checkpoint (tr_engine_goals), and said in a note. */
static int resume_goals(tt_opts *o, double *elapsed, tr_error *err)
{
    tr_engine_goals g;
    int found;
    int rc = tr_engine_checkpoint_goals(o->resume, &g, &found, elapsed, err);
    if (rc || !found)
        return rc;
    tr_text said = {0};
    if (o->refine_to <= 0 && g.refine_to > 0) {
        o->refine_to = g.refine_to;
        o->refine_given = g.refine_given;
        tr_text_printf(&said, " --refine-to %ld", g.refine_to);
    }
    if (o->target <= 0 && g.target > 0) {
        o->target = g.target;
        tr_text_printf(&said, " --target %.17g", g.target);
    }
    if (!o->residual_given && g.residual_given) {
        o->residual = g.residual;
        o->residual_given = 1;
        tr_text_printf(&said, " --residual %.17g", g.residual);
    }
    if (o->steps <= 0 && g.steps > 0) {
        o->steps = g.steps;
        tr_text_printf(&said, " --steps %ld", g.steps);
    }
    if (o->time_limit <= 0 && g.time_limit > 0) {
        o->time_limit = g.time_limit;
        tr_text_printf(&said, " --time-limit %.17g", g.time_limit);
    }
    char *line = tr_text_take(&said, NULL);
    if (line && line[0])
        tt_note(o, TR_TIGHTEN_INFO, "resuming with the checkpoint's goals:%s", line);
    free(line);
    return TR_OK;
}

/* What one road came to: the engine's progress, the result and its
 * certificate. */
typedef struct road_result {
    tr_stop_reason why;
    tr_engine_progress p;
    tr_curve fin;
    tr_thickness th;
    int rescaled;  /* fin was scaled to thickness 1 */
    tr_kkt kr;
    int certified; /* kr holds the KKT certificate of fin */
    int ckpt_failures; /* checkpoints the run could not write */
    const char *ckpt_why;
    char ckpt_why_buf[256]; /* ckpt_why of a failure after the roads */
    int tries, best_try; /* roads run, the one kept (0-based) */
} road_result;

/* What became of the solver's state beside the checkpoint (engine.h):
 * taken at resume, ignored, not kept; one line when there is news. */
static void say_solver_state(const tt_opts *o, tr_engine *e)
{
    char line[640];
    int kind = tr_engine_solver_state_take_note(e, line, sizeof line);
    if (kind >= 0)
        tt_note(o, kind ? TR_TIGHTEN_WARNING : TR_TIGHTEN_INFO, "%s", line);
}

/* Opens the engine on the road's start (the call's start or the
 * checkpoint to resume) and checks the outputs before the run. *stage says
 * where a failure came. */
static int open_start(tt_opts *o, tr_engine **e, tr_tighten_stage *stage, tr_error *err)
{
    tr_engine_params prm;
    tr_engine_params_default(&prm);
    prm.polish = !o->no_polish;
    prm.newton = o->newton;
    prm.newton_tight = !o->no_newton;
    if (o->device_from >= 0)
        prm.device_min_n = (size_t)o->device_from;
    prm.bound = tt_bound(o);
    prm.goals = (tr_engine_goals){.refine_to = o->refine_to > 0 ? o->refine_to : 0,
                                  .refine_given = o->refine_given,
                                  .target = o->target,
                                  .residual = o->residual_given ? o->residual : 0.0,
                                  .residual_given = o->residual_given,
                                  .steps = o->steps,
                                  .time_limit = o->time_limit};
    *e = NULL;
    *stage = TR_TIGHTEN_AT_START;
    int rc;
    if (o->resume) {
        rc = tr_engine_resume(e, o->resume, o->device, &prm, err);
        tr_curve at = {0};
        tr_error terr = {0};
        if (rc == TR_OK && o->resume_type) {
            /* the state the run resumes from, for the result's type check */
            if (tr_engine_get_curve(*e, &at, &terr) == TR_OK)
                tt_knot_type_of(&at, o->resume_type);
            else
                snprintf(o->resume_type->why, sizeof o->resume_type->why, "%.1000s", terr.msg);
            tr_curve_free(&at);
        }
    } else {
        tr_curve c;
        double t_read = tr_clock_seconds();
        rc = tt_read_start(o, &c, err);
        /* a scout's levels, counted from its start as read (roads.c); its
         * share of the time holds its shuffle too: a scout that no longer
         * jams early runs its engine to the end of the share, and with the
         * shuffle on top the five after the first took 29-32 s of 23.5 */
        if (rc == TR_OK && o->scout_levels > 1 && o->refine_to <= 0) {
            size_t most = 0;
            for (int k = 0; k < c.ncomp; k++)
                most = tr_comp_nv(&c, k) > most ? tr_comp_nv(&c, k) : most;
            o->refine_to = (long)most * o->scout_levels;
            prm.goals.refine_to = o->refine_to;
            if (o->time_limit > 0)
                prm.goals.time_limit = o->time_limit =
                    fmax(o->time_limit - (tr_clock_seconds() - t_read), 0.05 * o->time_limit);
        }
        double t_open = tr_clock_seconds();
        if (rc == TR_OK) {
            rc = tr_engine_open(e, &c, o->device, &prm, err);
            /* the start is the finest level: a tight one goes to the
             * second-order solver before the engine settles it
             * (engine.h, tr_engine_solve), for the road's time */
            int solve_first = !o->no_newton && (o->refine_to <= 0 || c.nv / (size_t)c.ncomp >= (size_t)o->refine_to);
            tr_curve_free(&c);
            int accepted;
            double seconds = o->time_limit > 0 ? fmax(o->time_limit - (tr_clock_seconds() - t_open), 1e-3) : 0.0;
            if (rc == TR_OK && solve_first)
                rc = tr_engine_solve(*e, seconds, o->call->cancel, o->ckpt, o->ckpt ? o->ckpt_every : 0, &accepted,
                                     err);
            if (rc == TR_OK)
                rc = tr_engine_settle_start(*e, err);
            if (rc) {
                tr_engine_destroy(*e);
                *e = NULL;
            }
        }
    }
    if (rc)
        return rc;
    say_solver_state(o, *e);
    /* A run of hours must not end in "cannot write": the output's format
     * and both paths are checked before it starts. */
    *stage = TR_TIGHTEN_AT_CHECK;
    if ((rc = check_outputs(o, *e, err))) {
        tr_engine_destroy(*e);
        *e = NULL;
        return rc;
    }
    /* said once, not once a road */
    if (tr_engine_warning(*e)[0] && o->try_index == 0)
        tt_note(o, TR_TIGHTEN_WARNING, "warning: %s", tr_engine_warning(*e));
    if (o->resume) {
        /* both limits count the runs before the checkpoint: say so when
         * they leave this run nothing to do */
        tr_engine_progress p0;
        tr_engine_get_progress(*e, &p0);
        if (o->steps > 0 && p0.steps >= o->steps)
            tt_note(o, TR_TIGHTEN_WARNING, "warning: the checkpoint has %ld steps already; --steps %ld "
                    "counts them, so no step is taken", p0.steps, o->steps);
        if (o->time_limit > 0 && p0.elapsed >= o->time_limit)
            tt_note(o, TR_TIGHTEN_WARNING, "warning: the checkpoint has used %.1f s already; "
                    "--time-limit %g counts them, so no step is taken", p0.elapsed, o->time_limit);
    }
    return TR_OK;
}

/* The engine's progress, as the call's (tighten.h). */
static void on_progress(const tr_engine_progress *p, void *user)
{
    const tt_opts *o = user;
    tr_tighten_progress tp = {.n = p->n,
                              .steps = p->steps,
                              .ropelength = p->ropelength,
                              .residual = p->residual,
                              .elapsed = p->elapsed,
                              .steps_per_s = p->steps_per_s,
                              .road = o->try_index + 1,
                              .roads = o->roads};
    o->call->progress(&tp, o->call->user);
}

/* Runs the engine to its limits, stopping when the cancel flag is raised. */
static int run(const tt_opts *o, tr_engine *e, tr_stop_reason *why, tr_error *err)
{
    tr_engine_limits lim = {.refine_to = (size_t)o->refine_to,
                            .residual = o->residual,
                            .target = o->target,
                            .max_steps = o->steps,
                            .time_limit = o->time_limit,
                            .coarse_residual = 1e-3,
                            .checkpoint_every = o->ckpt ? o->ckpt_every : 0,
                            .checkpoint_path = o->ckpt,
                            .stop = o->call->cancel,
                            .progress_every = o->call->progress_every > 0 ? o->call->progress_every : 0.25,
                            .progress = o->call->progress ? on_progress : NULL,
                            .user = (void *)o};
    return tr_engine_run(e, &lim, why, err);
}

/* Takes the engine's curve into r->fin, rescaled to thickness 1 where no
 * vertex is constrained, and measures and (as kkt says) certifies it. */
static int certify(const tt_opts *o, tr_engine *e, road_result *r, tr_error *err)
{
    tr_engine_get_progress(e, &r->p);
    r->ckpt_failures = tr_engine_checkpoint_failures(e, &r->ckpt_why);
    /* no step ever taken (a target the start already meets): the engine
     * has no residual to report, and 0 would read as converged */
    if (r->p.steps == 0)
        r->p.residual = NAN;
    int rc = tr_engine_get_curve(e, &r->fin, err);
    if (rc == TR_OK)
        rc = tr_thickness_measure(&r->fin, NULL, &r->th, NULL, err);
    if (rc == TR_OK && r->fin.ncst == 0 && isfinite(r->th.thickness) && r->th.thickness > 0) {
        /* certificate at thickness exactly 1: ropelength = length */
        tt_scale_curve(&r->fin, 1.0 / r->th.thickness);
        rc = tr_thickness_measure(&r->fin, NULL, &r->th, NULL, err);
        r->rescaled = 1;
    }
    /* the certificate of what is kept, computed on it alone */
    if (rc == TR_OK && r->why != TR_STOP_SIGNAL &&
        (o->kkt == 1 || (o->kkt < 0 && r->fin.nv <= TR_TIGHTEN_KKT_AUTO_MAX_N))) {
        rc = tr_kkt_certify(&r->fin, NULL, &r->kr, err);
        r->certified = rc == TR_OK;
    }
    return rc;
}

/* One road of the run: opens the start (perturbed for try_index > 0),
 * runs and certifies it. Returns TR_OK with *e and *r filled, else the
 * error, *stage where it came. */
static int one_road(tt_opts *o, tr_engine **e, road_result *r, tr_tighten_stage *stage, tr_error *err)
{
    int rc = open_start(o, e, stage, err);
    if (rc)
        return rc;
    *r = (road_result){0};
    *stage = TR_TIGHTEN_AT_RUN;
    rc = run(o, *e, &r->why, err);
    say_solver_state(o, *e);
    /* the level it stopped at is the road's result (tighten's refine_short
     * says so); the note says why it went no further */
    if (rc == TR_OK && r->why == TR_STOP_REFINE)
        tt_note(o, TR_TIGHTEN_WARNING, "warning: %s; the run stopped at the level before it",
                tr_engine_stop_why(*e));
    if (rc) {
        tr_engine_destroy(*e);
        return rc;
    }
    *stage = TR_TIGHTEN_AT_CERTIFY;
    if ((rc = certify(o, *e, r, err))) {
        tr_curve_free(&r->fin);
        tr_engine_destroy(*e);
        return rc;
    }
    return TR_OK;
}

/* The effective options of the call from the caller's. */
static tt_opts call_options(const tr_curve *start, const tr_tighten_options *opt)
{
    return (tt_opts){.call = opt,
                     .in = opt->name ? opt->name : "the start",
                     .start = opt->resume ? NULL : start,
                     .out = opt->output_check,
                     .ckpt = opt->checkpoint,
                     .resume = opt->resume,
                     .device = opt->device,
                     .n = opt->n,
                     .refine_to = opt->refine_to,
                     .steps = opt->steps,
                     .device_from = opt->device_from,
                     .tries = opt->tries > 0 ? opt->tries : 1,
                     .seed = opt->seed,
                     .shuffles = opt->shuffles,
                     .inflate = 1.0,
                     .roads = 1,
                     .target = opt->target,
                     .residual = opt->residual,
                     .time_limit = opt->time_limit,
                     .ckpt_every = opt->checkpoint_every > 0 ? opt->checkpoint_every : 300,
                     .residual_given = opt->residual_given,
                     .refine_given = opt->refine_given,
                     .no_polish = !opt->polish,
                     .newton = opt->newton > 0,
                     .no_newton = opt->newton < 0,
                     .scale = opt->scale,
                     .kkt = opt->kkt,
                     .auto_route = opt->auto_route,
                     .auto_roads = opt->tries <= 0 && opt->shuffles <= 0,
                     .centre = opt->centre};
}

/* The call's result from the kept road's. */
static void fill_result(const tt_opts *o, tr_engine *e, road_result *r, tr_tighten_result *res)
{
    res->curve = r->fin;
    r->fin = (tr_curve){0};
    res->n = r->th.vertices;
    res->ropelength = r->th.ropelength;
    res->thickness = r->th.thickness;
    res->minrad = r->th.minrad;
    res->dcsd = r->th.dcsd;
    res->length = r->th.length;
    res->residual = r->p.residual;
    res->kkt_residual = r->certified ? r->kr.residual : NAN;
    res->stop = r->why;
    res->interrupted = r->why == TR_STOP_SIGNAL;
    res->elapsed = r->p.elapsed;
    res->steps = r->p.steps;
    res->rejected = r->p.rejected;
    res->steps_per_s = r->p.steps_per_s;
    res->tries = r->tries > 0 ? r->tries : 1;
    /* a resumed run continues one road of a run whose seed it does not know */
    res->seed = o->resume ? -1 : o->seed;
    res->road = o->resume ? 0 : r->tries > 0 ? r->best_try + 1 : 1;
    res->th = r->th;
    res->kkt = r->kr;
    res->certified = r->certified;
    res->rescaled = r->rescaled;
    res->progress = r->p;
    snprintf(res->device, sizeof res->device, "%s", tr_engine_device(e));
    memcpy(res->shift, o->shift, sizeof res->shift);
    res->checkpoint_failures = r->ckpt_failures;
    snprintf(res->checkpoint_why, sizeof res->checkpoint_why, "%s", r->ckpt_why ? r->ckpt_why : "");
    res->refine_to = o->refine_to;
    res->refine_implied = o->refine_implied;
    /* a requested ropelength or residual that was not reached is a run that
     * did not reach its goal; so is a refine_to whose N the time did not
     * reach (the best state is kept either way) */
    int refined = 1;
    for (int k = 0; k < res->curve.ncomp; k++)
        refined = refined && (long)tr_comp_nv(&res->curve, k) >= o->refine_to;
    res->refine_short = o->refine_given && !refined && !res->interrupted;
    int goal = o->target > 0 || o->residual_given;
    /* the residual is met by the engine's own force balance or, once the
     * run has stopped for another reason (jammed, steps), by the
     * certificate of the result, which is the stricter measure (kkt.h) */
    int reached = r->why == TR_STOP_TARGET || r->why == TR_STOP_RESIDUAL ||
                  (o->target <= 0 && o->residual_given && r->certified && r->kr.residual <= o->residual);
    res->goal_missed = goal && !reached && !res->interrupted;
    res->goal_target = o->target > 0;
}

/* The result is the start's knot type, or no result (knot_type.h). The
 * start is the call's curve, or the checkpoint a resumed run began from. */
static int check_type(const tr_curve *start, const tt_opts *o, tr_tighten_result *res, tr_error *err)
{
    tt_knot_type *before = malloc(sizeof *before), *after = malloc(sizeof *after);
    if (!before || !after) {
        free(before);
        free(after);
        snprintf(res->type_line, sizeof res->type_line, "knot type not checked (out of memory)");
        return TR_OK;
    }
    if (start)
        tt_knot_type_of(start, before);
    else if (o->resume_type)
        *before = *o->resume_type;
    else
        *before = (tt_knot_type){.why = "no start at hand"};
    tt_knot_type_of(&res->curve, after);
    int rc = TR_OK;
    if (!before->known || !after->known) {
        snprintf(res->type_line, sizeof res->type_line, "knot type not checked (%s: %.250s)",
                 !before->known ? "the start" : "the result", !before->known ? before->why : after->why);
    } else if (tt_knot_type_same(before, after)) {
        res->type_checked = 1;
        char now[256];
        tr_type_describe(&after->tc, now, sizeof now);
        snprintf(res->type_line, sizeof res->type_line, "knot type kept: %s (the start's)", now);
    } else {
        char was[256], now[256];
        tr_type_describe(&before->tc, was, sizeof was);
        tr_type_describe(&after->tc, now, sizeof now);
        rc = tr_fail(err, TR_EGEOMETRY, "the tightened curve is not the start's knot type (start: %s; result: %s): "
                     "nothing written", was, now);
        res->failed_at = TR_TIGHTEN_AT_TYPE;
        tr_tighten_result_free(res);
    }
    free(before);
    free(after);
    return rc;
}

/* The start's ropelength as given, for tr_tighten_result's
 * start_ropelength: NAN where a comparison would mislead (a clasp's ends
 * are held, so its length is not scaled to thickness 1) or cannot be
 * made; within the call's bound (a start of 10^6 vertices takes seconds). */
static double measure_start(const tr_curve *start, const tt_opts *o)
{
    if (!start || o->resume || start->ncst != 0)
        return NAN;
    tr_deadline bound = tt_bound(o);
    tr_thickness_opts bounded = {.bound = &bound};
    tr_thickness th;
    tr_error err;
    if (tr_thickness_measure(start, &bounded, &th, NULL, &err) != TR_OK || !(th.thickness > 0) ||
        !isfinite(th.ropelength))
        return NAN;
    return th.ropelength;
}

int tr_tighten(const tr_curve *start, const tr_tighten_options *opt, tr_tighten_result *res, tr_error *err)
{
    *res = (tr_tighten_result){.kkt_residual = NAN, .residual = NAN, .seed = -1, .start_ropelength = NAN};
    if (!opt->resume && !start) {
        res->failed_at = TR_TIGHTEN_AT_START;
        return tr_fail(err, TR_EINVAL, "no start curve and no checkpoint to resume");
    }
    const char *conflict = tr_tighten_vertex_conflict(opt);
    if (conflict) {
        res->failed_at = TR_TIGHTEN_AT_START;
        return tr_fail(err, TR_EINVAL, "%s", conflict);
    }
    int vertex = opt->contacts == TR_CONTACTS_VERTEX;
    tt_opts o = call_options(start, opt);
    /* a resumed run's type is its checkpoint's, taken as the engine opens it */
    tt_knot_type resume_type = {.known = 0, .why = "the checkpoint's state was not opened"};
    if (o.resume)
        o.resume_type = &resume_type;
    double elapsed_before = 0.0; /* a resumed run's seconds before its checkpoint */
    int rc;
    if (o.resume && (rc = resume_goals(&o, &elapsed_before, err))) {
        res->failed_at = TR_TIGHTEN_AT_RESUME;
        return rc;
    }
    /* the vertex model's route is one solve at the start's N (vertex_route.c) */
    if (!vertex)
        tt_choose_route(&o);
    tt_start_shift(&o);
    /* the bound counts from here: shuffling and settling the start are the
     * call's time too; a resumed run's limit counts the time before its
     * checkpoint (as the engine's steps do) */
    if (o.time_limit > 0) {
        double from = opt->began > 0 && opt->began <= tr_clock_seconds() ? opt->began : tr_clock_seconds();
        o.bound_at = from + fmax(o.time_limit - elapsed_before - finish_reserve(o.time_limit), 0.0);
    }
    if (vertex) {
        rc = tt_tighten_vertex(&o, res, err);
        return rc ? rc : check_type(start, &o, res, err);
    }
    double start_ropelength = measure_start(start, &o);
    /* tries: the roads one after the other, each with an equal share of the
     * time left; of the certified ones the finest, then the shortest, is
     * kept. A road that fails after the first is skipped (said in a note);
     * the cancel flag ends the series. On a route of levels the roads are
     * scouts: each tightens its coarse level only, in TT_SCOUT_SHARE of the
     * time, and the shortest of them alone is refined to refine_to with
     * the rest (scouting). */
    tr_engine *e = NULL;
    road_result r = {0};
    int have = 0, scouting = o.tries > 1 && tt_multi_level(&o), kept_ckpt = 0;
    int scout_as_is = 0; /* the resampled scout did not settle: refine it level by level */
    o.roads = (int)o.tries + scouting;
    double t0 = tr_clock_seconds();
    const double budget = scouting ? TT_SCOUT_SHARE * o.time_limit : o.time_limit; /* the scouts' */
    tr_deadline bound = tt_bound(&o);
    long scouts_ran = o.tries; /* fewer when the scouts' share ran out */
    long kept_t = -1, last_ckpt_t = -1; /* the kept road, the last to write the checkpoint */
    tt_road_checkpoint kept_files = {0}; /* the checkpoint's files as the kept road's end left them */
    tr_error files_err = {.msg = "its files could not be copied"};
    /* the scouts end at their share of the time (0: no such bound), the
     * automatic roads' and those given by --tries alike: given roads once
     * all ran, and 9 roads of 10 at N 150 of 9_10 made by name took all of
     * --time-limit 400, so the run stopped at N 150, "before reaching the
     * requested --refine-to 2400", 2 % above the knot's ropelength */
    const double scouts_end = scouting && o.time_limit > 0 ? t0 + budget : 0.0;
    /* once a road has a result, no road starts past the bound: each has at
     * least its share's floor, and a thousand roads of a second's floor
     * were once a minute past a three-second limit */
    for (long t = 0; t < o.tries + scouting && !(have && tr_deadline_passed(&bound)); t++) {
        /* the scouts' share is a bound too: a road's setup (a shuffle, a
         * settle) is not in its engine's time, and under load the scouts
         * once took all of T, leaving the refinement none (9_40 made by
         * name, T = 300 at load 7: road 9 of 10 stopped by the limit) */
        if (scouts_end > 0 && t > 0 && t < o.tries && have && tr_clock_seconds() >= scouts_end) {
            tt_note(&o, TR_TIGHTEN_INFO, "the scouts' share of the time is spent after %ld of %ld roads", t, o.tries);
            scouts_ran = t;
            t = o.tries;
        }
        /* the automatic roads refine to a count from the shortest scout */
        if (scouting && t == o.tries && o.refine_auto && have)
            o.refine_to = tt_auto_refine_n(&o, r.th.ropelength);
        tt_opts ot = o;
        ot.try_index = (int)t;
        tr_curve scout_at_n = {0};
        int resampled = 0;
        int refining = scouting && t == o.tries;
        /* the last shuffles roads (never the first: shuffles < tries) */
        int shuffled_road = !refining && t >= o.tries - o.shuffles;
        ot.shuffle_index = shuffled_road ? (int)(t - (o.tries - o.shuffles)) : 0;
        if (refining) {
            /* the shortest scout, refined as it is (tt_read_start takes
             * road_from before n and scale) */
            ot.road_from = &r.fin;
            ot.road_as_is = 1;
            if (!scout_as_is && (resampled = tt_scout_at_refine_n(&o, &r.fin, &scout_at_n)))
                ot.road_from = &scout_at_n;
        } else if (scouting) {
            ot.refine_to = 0;
            if (shuffled_road) {
                /* a shuffled road, at the first road's coarse count; on
                 * the automatic roads at the count its compacted rope
                 * takes (edges of 0.5: start.c, densify_coarse), which
                 * is far fewer than a quarter of a loose start's (9_40
                 * made by name: 1693 vertices, shuffled to ropelength
                 * ~110, 220 vertices where N / 4 is 423) */
                ot.shuffled = 1;
                ot.n = o.refine_auto ? 0 : tt_road_coarse_n(&o, 1);
                tt_scout_levels(&ot);
            } else if (t > 0) {
                ot.n = tt_road_coarse_n(&o, (int)t);
                ot.inflate = tt_road_inflate((int)t);
            } else if (o.refine_auto) {
                /* the automatic roads' first scout: the start's own
                 * conformation, compacted (roads.c, tt_shuffle_start),
                 * not a quarter of its count: 9_2 made by name has 2828
                 * vertices, and its first road at 707 took a third of
                 * the scouts' time to 436 where the others reached 88 */
                ot.shuffled = 1;
                ot.compacted = 1;
                ot.n = 0;
                tt_scout_levels(&ot);
            }
        } else if (shuffled_road)
            ot.shuffled = 1;
        else
            ot.road_from = have ? &r.fin : NULL;
        /* a scout after the first is bounded by the scouts' share too, its
         * shuffle and settle included, so that no scout takes the
         * refinement's time (the first has no road to fall back on) */
        if (scouts_end > 0 && !refining && t > 0)
            ot.bound_at = fmin(o.bound_at, scouts_end);
        /* scouts write no checkpoint: one would carry a scout's goals (its
         * coarse level, its share of the time), and --resume would go on as
         * that scout and never refine (a stopped `tighten --time-limit 60
         * --checkpoint` of 3_1 made by name resumed to N 96, "solved"); the
         * refinement checkpoints with the call's goals, and a run stopped
         * while scouting starts again */
        if (scouting && !refining)
            ot.ckpt = NULL;
        /* a road that jams early leaves its time to the roads after it */
        if (o.time_limit > 0)
            ot.time_limit = refining ? fmax(o.time_limit - (tr_clock_seconds() - t0), 0.05 * o.time_limit)
                                     : fmax(budget - (tr_clock_seconds() - t0), 0.05 * budget) / (double)(o.tries - t);
        /* the first scout's compaction has half its share: it is the one
         * road the scouts' share does not bound, and under a sanitizer
         * 10^5 moves took all of a 50 s limit, leaving no time to tighten */
        if (ot.compacted && o.time_limit > 0)
            ot.compact_until = tr_clock_seconds() + 0.5 * ot.time_limit;
        if (refining)
            tt_note(&o, TR_TIGHTEN_INFO, "the shortest scout (road %d, N %zu) %s to %ld vertices", r.best_try + 1,
                    r.fin.nv, resampled ? "resampled" : "refined", o.refine_to);
        else if (ot.compacted)
            tt_note(&o, TR_TIGHTEN_INFO, "road 1 of %ld: the start compacted (crankshaft moves that keep it thick, "
                    "at its own scale)", o.tries);
        else if (o.tries > 1 && t > 0)
            tt_note(&o, TR_TIGHTEN_INFO, "road %ld of %ld: %s", t + 1, o.tries,
                    ot.road_from ? "the shortest result so far, moved"
                    : ot.shuffled ? "the start shuffled (crankshaft moves of the thin rope, then compacted)"
                    : ot.inflate != 1.0 ? "the start again, inflated 1.5 times, from another coarse count"
                                        : "the start again, from another coarse count");
        tr_engine *et;
        road_result rt;
        tr_tighten_stage stage;
        tr_error road_err;
        rc = one_road(&ot, &et, &rt, &stage, have ? &road_err : err);
        if (ot.ckpt)
            last_ckpt_t = t;
        if (resampled)
            tr_curve_free(&scout_at_n);
        if (rc) {
            if (!have) {
                res->failed_at = stage;
                return rc;
            }
            /* a spline through a tight coarse scout bends past MinRad
             * between its vertices, more so the more vertices it adds:
             * the trefoil's scout of 96 vertices (32.95) resampled to 800
             * settled, to 1200 and to 1582 not in the settle's 400 passes
             * ("could not bring the curve to ... MinRad >= 1"), and the
             * scout itself was written. The level loop's doublings from
             * the scout as it is take it there instead. */
            if (refining && resampled && stage == TR_TIGHTEN_AT_START && rc != TR_EINTERRUPTED &&
                !tr_deadline_passed(&bound)) {
                tt_note(&o, TR_TIGHTEN_INFO, "the resampled scout did not settle at N %ld (%s): refined level by "
                        "level instead", o.refine_to, road_err.msg);
                scout_as_is = 1;
                t--;
                continue;
            }
            /* a later road that the bound stopped before its start was
             * settled leaves the roads before it to be kept: the lines
             * below say so */
            if (!(rc == TR_EINTERRUPTED && stage == TR_TIGHTEN_AT_START))
                tt_note(&o, TR_TIGHTEN_WARNING, "%s", road_err.msg);
            if (tr_deadline_passed(&bound))
                tt_note(&o, TR_TIGHTEN_INFO, "road %ld of %ld %s; the shortest so far is written", t + 1,
                        o.tries + scouting,
                        tr_deadline_passed(&bound) == 2 ? "stopped by a signal" : "stopped by the time limit");
            else if (refining)
                tt_note(&o, TR_TIGHTEN_WARNING, "the refinement failed; the shortest scout is written");
            else if (rc == TR_EINTERRUPTED && scouting && o.time_limit > 0 && tr_clock_seconds() >= t0 + budget)
                tt_note(&o, TR_TIGHTEN_INFO, "road %ld of %ld stopped: the scouts' share of the time is spent", t + 1,
                        o.tries);
            else
                tt_note(&o, TR_TIGHTEN_WARNING, "road %ld of %ld skipped", t + 1, o.tries);
            continue;
        }
        if (o.tries > 1) {
            if (refining)
                tt_note(&o, TR_TIGHTEN_INFO, "refined: N %zu, ropelength %.9f", rt.fin.nv, rt.th.ropelength);
            else
                tt_note(&o, TR_TIGHTEN_INFO, "road %ld of %ld: ropelength %.9f", t + 1, o.tries, rt.th.ropelength);
        }
        /* a road that ran out of time on a coarse level has not reached
         * the N asked for: the finest road wins, then the shortest; among
         * scouts (each at its own coarse count) the shortest */
        /* ... but a road at exactly the N asked for wins over one the
         * engine took past it */
        int shorter = rt.th.ropelength < r.th.ropelength, at_n = tt_at_refine_n(&o, &rt.fin),
            same_n = at_n == tt_at_refine_n(&o, &r.fin), finer = same_n ? rt.fin.nv > r.fin.nv : at_n;
        int better = !have || (scouting && !refining ? shorter : finer || (same_n && rt.fin.nv == r.fin.nv && shorter));
        if (better) {
            /* the refined scout keeps the scout's number */
            int best_try = refining ? r.best_try : (int)t;
            if (have) {
                tr_curve_free(&r.fin);
                tr_engine_destroy(e);
            }
            e = et;
            kept_t = t;
            kept_ckpt = ot.ckpt != NULL;
            /* only a series can leave another road's files there */
            if (kept_ckpt && t + 1 < o.tries + scouting)
                tt_road_checkpoint_take(o.ckpt, &kept_files, &files_err);
            r = rt;
            r.best_try = best_try;
            have = 1;
        } else {
            tr_curve_free(&rt.fin);
            tr_engine_destroy(et);
        }
        r.tries = (int)(t < o.tries ? t + 1 : scouts_ran);
    }
    /* the roads share the checkpoint's path and the last one's end wrote
     * it: where another road is kept, the files as the kept road's end
     * left them go back, so that --resume goes on from the written curve's
     * road (a trefoil of three roads once resumed from road 3's state to
     * 32.993 where the run had written road 1's 32.8044), with that road's
     * clock and goals and its solver state. A copy that could not be taken
     * or put back costs the checkpoint only, as in the engine (counted),
     * and is said: the files are then another road's. */
    if (have && kept_ckpt && last_ckpt_t != kept_t) {
        if (!kept_files.taken || tt_road_checkpoint_put(o.ckpt, &kept_files, &files_err)) {
            r.ckpt_failures++;
            snprintf(r.ckpt_why_buf, sizeof r.ckpt_why_buf, "%.255s", files_err.msg);
            r.ckpt_why = r.ckpt_why_buf;
            tt_note(&o, TR_TIGHTEN_WARNING, "warning: %s is road %ld's checkpoint, not the written curve's (road "
                    "%ld): %s; a --resume of it goes on from that road", o.ckpt, last_ckpt_t + 1, kept_t + 1,
                    files_err.msg);
        }
    }
    tt_road_checkpoint_free(&kept_files);
    /* an interrupted series is an interrupted run, whichever road is kept */
    if (tt_cancelled(&o))
        r.why = TR_STOP_SIGNAL;
    fill_result(&o, e, &r, res);
    res->checkpointed = kept_ckpt;
    res->start_ropelength = start_ropelength;
    if (o.ckpt && last_ckpt_t < 0 && have)
        tt_note(&o, TR_TIGHTEN_INFO, "no checkpoint: the run %s while its scouts ran, and scouts write none "
                "(the command again starts afresh)", res->interrupted ? "was interrupted" : "ended");
    tr_engine_destroy(e);
    return check_type(start, &o, res, err);
}

void tr_tighten_result_free(tr_tighten_result *res)
{
    if (!res)
        return;
    tr_curve_free(&res->curve);
    res->curve = (tr_curve){0};
}
