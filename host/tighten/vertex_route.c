/* tr_tighten in SP-FEM's vertex contact model (tighten.h, contacts
 * TR_CONTACTS_VERTEX; docs/physics.md "The vertex model"): every two
 * vertices that count (on different components, or at least K = ceil(pi / e)
 * apart along one) at least 2 apart, and MinRad at least 1.
 *
 * The route is the second-order solver alone (solver/newton.h with
 * vertex_contacts), on the start as tt_read_start makes it (--n, --scale,
 * centred). Rawdon's route does not apply: the first-order engine's steps,
 * its polish and settle hold edges 2 apart (backend.h), so they would undo
 * what the model allows (an edge dipping into the other strand's tube by its
 * sag e^2 / 8), and the KKT certificate (oracle/kkt.h) is Rawdon's rows'. The
 * options that belong to that route are refused (tr_tighten_vertex_conflict).
 * The result is judged by the vertex oracle (oracle/vertex_thickness.h),
 * independent of the solver's contact lists, and written at the model's
 * thickness 1. The solve is fastest from a start tight in Rawdon's model
 * (a tightened knot, refined: the models differ by O(e^2)); a loose start
 * is taken too, by Newton steps alone. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "curve/curve_io.h"
#include "solver/newton.h"
#include "tighten/tighten_internal.h"
#include "util/clock.h"

/* the refusals' common start */
#define ALONE "--contacts vertex runs the second-order solver alone, "

const char *tr_tighten_vertex_conflict(const tr_tighten_options *opt)
{
    if (opt->contacts != TR_CONTACTS_VERTEX)
        return NULL;
    if (opt->resume)
        return ALONE "which keeps no engine checkpoint: not with --resume (tighten the curve itself)";
    if (opt->refine_to > 0)
        return ALONE "at one N: not with --refine-to (--n resamples the start)";
    if (opt->tries > 1 || opt->shuffles > 0)
        return ALONE "one road: not with --tries or --shuffles";
    if (opt->target > 0 || opt->residual_given)
        return ALONE "to convergence, --time-limit or --steps: not with the engine's --target or --residual";
    if (opt->checkpoint)
        return ALONE "which keeps no engine checkpoint: not with --checkpoint";
    if (opt->device || opt->device_from >= 0)
        return ALONE "its vertex rows on the host: not with --device or --device-from";
    if (opt->kkt == 1)
        return ALONE "and the KKT certificate is Rawdon's model's: not with --kkt";
    if (opt->newton < 0)
        return ALONE "so not with --no-newton";
    return NULL;
}

/* what follows the solve, in oracle measures of the start: the vertex
 * oracle twice and Rawdon's once on the result, and the knot type of the
 * start and of the result (a projection and its crossings, about as dear) */
#define POST_SOLVE_MEASURES 5.0

/* The solver's progress, as the call's (tighten.h): a step's length at
 * the solver's unit (thickness 1 in the model, to the violation) stands for
 * the ropelength estimate, its unbalanced force for the residual. */
typedef struct vertex_progress {
    const tt_opts *o;
    size_t n;
    double last;
} vertex_progress;

static void on_step(void *user, const tr_newton_progress *p)
{
    vertex_progress *vp = user;
    const tr_tighten_options *call = vp->o->call;
    double every = call->progress_every > 0 ? call->progress_every : 0.25;
    if (!call->progress || p->seconds - vp->last < every)
        return;
    vp->last = p->seconds;
    tr_tighten_progress tp = {.n = vp->n,
                              .steps = p->iter + 1,
                              .ropelength = p->length,
                              .residual = p->stat,
                              .elapsed = p->seconds,
                              .steps_per_s = p->seconds > 0 ? (double)(p->iter + 1) / p->seconds : 0.0,
                              .road = 1,
                              .roads = 1};
    call->progress(&tp, call->user);
}

/* c scaled to the vertex model's thickness 1, its measures in both models */
static int measure_at_one(tr_curve *c, tr_thickness *th, tr_vertex_thickness *vt, tr_error *err)
{
    int rc = tr_vertex_thickness_measure(c, NULL, NULL, vt, err);
    if (rc)
        return rc;
    if (!(vt->thickness > 0) || !isfinite(vt->thickness))
        return tr_fail(err, TR_EGEOMETRY, "the curve has vertex-model thickness %g", vt->thickness);
    tt_scale_curve(c, 1.0 / vt->thickness);
    if ((rc = tr_thickness_measure(c, NULL, th, NULL, err)))
        return rc;
    return tr_vertex_thickness_measure(c, NULL, th, vt, err);
}

int tt_tighten_vertex(const tt_opts *o, tr_tighten_result *res, tr_error *err)
{
    double t0 = tr_clock_seconds();
    const tr_curve *s0 = o->start;
    res->failed_at = TR_TIGHTEN_AT_START;
    /* the model's exclusion K runs along a closed component (newton.h) */
    if (!s0)
        return tr_fail(err, TR_EINVAL, "no start curve");
    for (int k = 0; k < s0->ncomp; k++)
        if (!s0->closed[k])
            return tr_fail(err, TR_EINVAL, "%s: component %d is open; --contacts vertex takes closed components "
                           "without constraints only", o->in, k);
    if (s0->ncst > 0)
        return tr_fail(err, TR_EINVAL, "%s has constrained vertices; --contacts vertex takes closed components "
                       "without constraints only", o->in);
    tr_curve c;
    int rc = tt_read_start(o, &c, err);
    if (rc)
        return rc;
    /* a solve of minutes must not end in "cannot write": the output's
     * format and folder are checked first, as the engine's route does */
    res->failed_at = TR_TIGHTEN_AT_CHECK;
    if (o->out && (rc = tr_curve_check_output(o->out, TR_FORMAT_AUTO, &c, err))) {
        tr_curve_free(&c);
        return rc;
    }
    res->failed_at = TR_TIGHTEN_AT_START;
    tt_note(o, TR_TIGHTEN_INFO, "contacts vertex: the second-order solver in SP-FEM's model (%zu vertices); the "
            "first-order engine, polish and Rawdon's KKT certificate do not apply", c.nv);
    tr_newton_params np;
    tr_newton_params_default(&np);
    np.vertex_contacts = 1;
    np.stop = o->call->cancel;
    if (o->bound_at > 0) {
        /* the solve leaves the time limit room for what follows it: the
         * result's measures in both models and the knot types of start
         * and result, each about one oracle measure of the start (0.8 s
         * past a 4 s limit at N = 9600 on a loaded machine without) */
        double tm = tr_clock_seconds();
        tr_vertex_thickness probe;
        if ((rc = tr_vertex_thickness_measure(&c, NULL, NULL, &probe, err))) {
            tr_curve_free(&c);
            return rc;
        }
        double now = tr_clock_seconds(), left = o->bound_at - now;
        np.time_limit = fmax(left - fmin(POST_SOLVE_MEASURES * (now - tm), 0.5 * left), 1e-3);
    }
    if (o->steps > 0)
        np.max_iter = o->steps > 1000000000L ? 1000000000 : (int)o->steps;
    vertex_progress vp = {.o = o, .n = c.nv, .last = -INFINITY};
    np.progress = on_step;
    np.user = &vp;
    tr_newton_stats ns;
    int unstepped = 0;
    res->failed_at = TR_TIGHTEN_AT_RUN;
    if ((rc = tr_newton(&c, &np, &ns, err))) {
        /* the time limit or a signal before the solve's first step (the
         * start's measure or the first strut list, seconds under a
         * sanitizer or a loaded machine at N = 4800): c is the start, as
         * tr_newton leaves it on an error, and is written as the Rawdon
         * route writes a start the bound stopped, with where it stopped */
        if (rc != TR_EINTERRUPTED) {
            tr_curve_free(&c);
            return rc;
        }
        memset(&ns, 0, sizeof ns);
        unstepped = 1;
        ns.why_rejected = tt_cancelled(o) ? "a signal came before the solver's first step"
                                          : "the time limit came before the solver's first step";
    }
    /* accepted: c is the result at thickness 1 in the model; else the
     * start, scaled there here */
    res->failed_at = TR_TIGHTEN_AT_CERTIFY;
    tr_thickness th;
    tr_vertex_thickness vt;
    if ((rc = measure_at_one(&c, &th, &vt, err))) {
        tr_curve_free(&c);
        return rc;
    }
    if (unstepped)
        ns.ropelength_before = ns.ropelength_after = vt.ropelength;
    res->failed_at = TR_TIGHTEN_AT_NONE;
    res->curve = c;
    res->vertex = 1;
    res->vt = vt;
    res->th = th;
    res->n = vt.vertices;
    res->ropelength = vt.ropelength;
    res->thickness = vt.thickness;
    res->minrad = vt.minrad;
    res->dcsd = th.dcsd;
    res->length = vt.length;
    res->residual = NAN;
    res->kkt_residual = NAN;
    res->rescaled = 1;
    res->vertex_converged = ns.converged;
    res->vertex_why = ns.accepted ? NULL : ns.why_rejected ? ns.why_rejected : "not accepted";
    /* the solver ends converged or settled, or at its step or time limit,
     * or on the cancel flag (newton.c's loop has no other end) */
    int cancelled = tt_cancelled(o);
    res->stop = ns.converged || ns.settled ? TR_STOP_SOLVED
                : cancelled                ? TR_STOP_SIGNAL
                : ns.iters >= np.max_iter  ? TR_STOP_STEPS
                                           : TR_STOP_TIME;
    res->interrupted = cancelled;
    res->elapsed = tr_clock_seconds() - t0;
    res->steps = ns.iters;
    res->steps_per_s = ns.seconds > 0 ? ns.iters / ns.seconds : 0.0;
    res->tries = 1;
    res->seed = o->seed;
    res->road = 1;
    res->progress = (tr_engine_progress){.steps = ns.iters,
                                         .n = vt.vertices,
                                         .length = vt.length,
                                         .ropelength = vt.ropelength,
                                         .residual = NAN,
                                         .minrad = vt.minrad,
                                         .elapsed = res->elapsed,
                                         .steps_per_s = res->steps_per_s,
                                         .newton_ran = ns.accepted ? 1 : -1,
                                         .newton_before = ns.ropelength_before,
                                         .newton_after = ns.ropelength_after,
                                         .newton_seconds = ns.seconds,
                                         .newton_iters = ns.iters};
    snprintf(res->device, sizeof res->device, "the host (the vertex model's rows)");
    memcpy(res->shift, o->shift, sizeof res->shift);
    if (!ns.accepted)
        tt_note(o, TR_TIGHTEN_WARNING, "warning: the second-order solver kept the start (%s); it is written at "
                "vertex-model thickness 1", res->vertex_why);
    return TR_OK;
}
