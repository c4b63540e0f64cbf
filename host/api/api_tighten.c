/* The public API's tighten: the tightening layer's tr_tighten (tighten.h)
 * with the public options, progress and result. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "api/api_internal.h"
#include "tighten/tighten.h"

void tightrope_tighten_options_init(tightrope_tighten_options *o)
{
    tr_tighten_options d;
    tr_tighten_options_default(&d);
    memset(o, 0, sizeof *o);
    o->time_limit = d.time_limit;
    o->n = d.n;
    o->refine_to = d.refine_to;
    o->residual = d.residual;
    o->target = d.target;
    o->steps = d.steps;
    o->device = d.device;
    o->newton = d.newton;
    o->polish = d.polish;
    o->scale = d.scale;
    o->tries = d.tries;
    o->shuffles = d.shuffles;
    o->seed = d.seed;
    o->kkt = d.kkt;
    o->checkpoint = d.checkpoint;
    o->progress_every = d.progress_every;
}

/* The caller's progress function behind the layer's. */
typedef struct progress_relay {
    tightrope_progress_fn fn;
    void *user;
} progress_relay;

static void relay_progress(const tr_tighten_progress *p, void *user)
{
    const progress_relay *r = user;
    tightrope_progress q = {.n = p->n,
                            .steps = p->steps,
                            .ropelength = p->ropelength,
                            .residual = p->residual,
                            .elapsed = p->elapsed,
                            .steps_per_s = p->steps_per_s,
                            .road = p->road,
                            .roads = p->roads};
    r->fn(&q, r->user);
}

static void kkt_out(const tr_kkt *k, double band, tightrope_kkt *o)
{
    o->residual = k->residual;
    o->band = band;
    o->radius = k->radius;
    o->tension = k->force;
    o->strut_rows = k->strut_rows;
    o->strut_active = k->strut_active;
    o->minrad_rows = k->minrad_rows;
    o->minrad_active = k->minrad_active;
    o->strut_force_max = k->strut_force_max;
    o->optimality = k->optimality;
    o->converged = k->converged;
}

int tightrope_tighten(const tightrope_curve *start, const tightrope_tighten_options *o, tightrope_curve **out,
                      tightrope_tighten_result *result, tightrope_error *err)
{
    tr_error e = {{0}};
    if (!start || !out || !result)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "tighten needs a start, an output and a result"), &e);
    *out = NULL;
    memset(result, 0, sizeof *result);
    tightrope_tighten_options po;
    if (!o) {
        tightrope_tighten_options_init(&po);
        o = &po;
    }
    if (o->time_limit < 0 || isnan(o->time_limit) || o->n < 0 || o->refine_to < 0 || o->steps < 0 ||
        o->tries < 0 || o->shuffles < 0 || (o->shuffles > 0 && o->shuffles >= o->tries) || !(o->residual >= 0))
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "bad tighten options (time_limit, n, refine_to, steps >= 0; "
                                                        "tries >= 0, 0 automatic; 0 <= shuffles < tries; "
                                                        "residual >= 0)"), &e);
    tr_tighten_options t;
    tr_tighten_options_default(&t);
    t.time_limit = o->time_limit;
    t.n = o->n;
    t.refine_to = o->refine_to;
    t.refine_given = o->refine_to > 0;
    /* the default residual is a stopping rule; another is a goal, as
     * tighten's --residual is (met, or said missed in the result) */
    t.residual_given = o->residual != t.residual;
    t.residual = o->residual;
    t.target = o->target;
    t.steps = o->steps;
    t.device = o->device;
    t.newton = o->newton;
    t.polish = o->polish;
    t.scale = o->scale;
    t.tries = o->tries;
    t.shuffles = o->shuffles;
    t.seed = o->seed;
    t.kkt = o->kkt;
    t.checkpoint = o->checkpoint;
    t.progress_every = o->progress_every;
    t.cancel = o->cancel;
    progress_relay relay = {o->progress, o->user};
    if (o->progress) {
        t.progress = relay_progress;
        t.user = &relay;
    }
    tr_tighten_result r;
    int rc = tr_tighten(&start->c, &t, &r, &e);
    if (rc)
        return tr_api_fail(err, rc, &e);
    result->n = r.n;
    result->ropelength = r.ropelength;
    result->thickness = r.thickness;
    result->minrad = r.minrad;
    result->dcsd = r.dcsd;
    result->length = r.length;
    result->residual = r.residual;
    result->kkt_residual = r.kkt_residual;
    result->certified = r.certified;
    if (r.certified) {
        tr_kkt_params kp;
        tr_kkt_params_default(&kp);
        kkt_out(&r.kkt, kp.band, &result->kkt);
    }
    snprintf(result->stopped, sizeof result->stopped, "%s", tr_stop_reason_name(r.stop));
    result->interrupted = r.interrupted;
    result->goal_missed = r.goal_missed || r.refine_short;
    result->elapsed = r.elapsed;
    result->steps = r.steps;
    result->rejected = r.rejected;
    result->steps_per_s = r.steps_per_s;
    result->tries = r.tries;
    result->road = r.road;
    result->seed = r.seed;
    result->rescaled = r.rescaled;
    memcpy(result->shift, r.shift, sizeof result->shift);
    snprintf(result->device, sizeof result->device, "%s", r.device);
    result->start_ropelength = r.start_ropelength;
    rc = tr_api_wrap(&r.curve, out, err);
    tr_tighten_result_free(&r);
    return rc;
}
