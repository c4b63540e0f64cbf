/* tightrope bench [--device SPEC]... [--n LIST] [--steps K] [--json]
 *
 * Throughput of the tightening step on each device: for every N a torus-knot
 * trefoil T(2,3) with N vertices (or --start FILE resampled to N); per device one validation step against the
 * serial reference on the same state (a device that disagrees is reported
 * and not timed), one untimed warm-up step, then timed steps and timed
 * neighbour searches. Per-kernel device times come from a separate profiled
 * run (profiling synchronises every launch). Prints a table; --json prints
 * one object a script reads.
 *
 * The timed step is the engine's (save, tension_step with tangent
 * projection, correct, measure) with its default parameters except that the
 * solver does a fixed amount of work: 2 Gauss-Newton iterations of 20 CG
 * iterations, and 1 projection pass of 10 (tolerances 0). The engine's own
 * iteration counts depend on the state (and, where CG is far from
 * converged, on rounding), which would make steps/s at different N or on
 * different devices incomparable; fixed work measures throughput.
 *
 * Every timed step (and the timed searches) starts from the same state, the
 * one after the warm-up, restored untimed: the fixed, unconverged solver work
 * does not hold a tight curve together over repeated steps (from the tight
 * trefoil at N = 10^4, five such steps in a row took MinRad from 0.97 to
 * 0.01), so later steps would time a crumpled curve, a different one on each
 * device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/backend.h"
#include "cli/cli.h"
#include "cli/cli_args.h"
#include "curve/curve_io.h"
#include "engine/engine.h"
#include "engine/refine_lowpass.h"
#include "curve/generate.h"
#include "util/json.h"
#include "util/clock.h"
#include "util/device_spec.h"
#include "geometry/struts.h"

#define MAX_DEV 8
#define MAX_N 16
#define MAX_K TR_BACKEND_PROFILE_MAX

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct result {
    char device[192];
    size_t n;
    int valid;         /* validation passed (reference: 1) */
    double valid_diff; /* max |x_dev - x_ref| after the validation step */
    int steps;
    double step_min, step_med; /* seconds per step */
    double contacts_s;         /* seconds per neighbour search */
    size_t pairs;
    double cg_per_step;
    double ratio;              /* reference step time / this step time (median) */
    int nk;
    tr_kernel_time k[MAX_K];
    double k_steps;            /* steps the kernel times cover */
    char error[300];
} result;

typedef struct bench_ctx {
    tr_engine_params prm;
    int *gap;
    int search; /* 0: --no-search, the contact list stays empty */
    double cutoff, tilt; /* the engine's contact list for this curve (see below) */
} bench_ctx;

static int one_step(tr_backend *b, const bench_ctx *bc, double h, int *cg, tr_error *err)
{
    const tr_backend_ops *o = b->ops;
    tr_tension_params tp = {.h = h, .max_move = bc->prm.max_move,
                            .smooth_passes = bc->prm.smooth_passes,
                            .project = bc->prm.project ? &bc->prm.proj : NULL};
    tr_tension_stats ts;
    tr_correct_stats cs;
    tr_measure m;
    int rc;
    if ((rc = o->save(b->state, err)) || (rc = o->tension_step(b->state, &tp, &ts, err)) ||
        (rc = o->correct(b->state, &bc->prm.correct, &cs, err)) ||
        (rc = o->measure(b->state, &m, NULL, NULL, err)))
        return rc;
    if (cg)
        *cg = cs.cg_iters;
    return TR_OK;
}

static int contacts(tr_backend *b, const bench_ctx *bc, size_t *pairs, tr_error *err)
{
    tr_contact_params cp = {.cutoff = bc->cutoff, .tilt = bc->tilt, .exclude_gap = bc->gap};
    tr_contact_stats cs = {0, INFINITY};
    int rc = bc->search ? b->ops->find_contacts(b->state, &cp, &cs, err) : TR_OK;
    if (pairs)
        *pairs = cs.pairs;
    return rc;
}

/* The validation: neighbour search, a tension step without projection (the
 * same arithmetic per vertex: identical positions), then a correction of one
 * Gauss-Newton iteration with two CG iterations (reordered dot products:
 * tests/backend/opencl/test_opencl_backend.c bounds it at 1e-11 of |x|); short enough that
 * CG's own rounding sensitivity does not enter. */
static int validation_step(tr_backend *b, const bench_ctx *bc, double h, size_t *pairs,
                           tr_error *err)
{
    const tr_backend_ops *o = b->ops;
    tr_tension_params tp = {.h = h, .max_move = bc->prm.max_move,
                            .smooth_passes = bc->prm.smooth_passes, .project = NULL};
    tr_tension_stats ts;
    tr_correct_params cp = bc->prm.correct;
    cp.max_newton = 1;
    cp.max_cg = 2;
    tr_correct_stats cs;
    int rc;
    if ((rc = contacts(b, bc, pairs, err)) || (rc = o->tension_step(b->state, &tp, &ts, err)) ||
        (rc = o->correct(b->state, &cp, &cs, err)))
        return rc;
    return TR_OK;
}

/* Times one device at one N; ref_x (3N, after the validation step on the
 * reference) is NULL when this is the reference itself. */
static void bench_one(const char *spec, const tr_curve *c, const bench_ctx *bc, int steps,
                      double target_s, const double *ref_x, double h, result *r)
{
    tr_error err = {{0}};
    tr_backend b;
    memset(r, 0, sizeof *r);
    r->n = c->nv;
    int rc = tr_backend_open_device(spec, c, 0, &b, &err);
    if (rc != TR_OK) {
        snprintf(r->device, sizeof r->device, "%s", spec);
        snprintf(r->error, sizeof r->error, "%.290s", err.msg);
        return;
    }
    char how[64];
    tr_backend_describe(&b, how, sizeof how);
    snprintf(r->device, sizeof r->device, "%.150s%s%.38s", b.description, how[0] ? ", " : "", how);
    double *x = malloc(3 * c->nv * sizeof *x);
    if (!x) {
        snprintf(r->error, sizeof r->error, "out of memory");
        tr_backend_close(&b);
        return;
    }
    /* validation step (also the warm-up of every kernel at this size) */
    if ((rc = validation_step(&b, bc, h, &r->pairs, &err)) ||
        (rc = b.ops->download(b.state, x, NULL, &err)))
        goto fail;
    r->valid = 1;
    if (ref_x) {
        /* see validation_step: 1e-10 of |x| leaves a factor 10 */
        double d = 0, scale = 0;
        for (size_t i = 0; i < 3 * c->nv; i++) {
            double e = fabs(x[i] - ref_x[i]);
            d = isfinite(e) ? fmax(d, e) : INFINITY;
            scale = fmax(scale, fabs(ref_x[i]));
        }
        r->valid_diff = d;
        r->valid = d <= 1e-10 * scale;
        if (!r->valid) {
            snprintf(r->error, sizeof r->error,
                     "validation failed: positions differ from the reference by %.3g", d);
            goto done;
        }
    }
    if ((rc = one_step(&b, bc, h, NULL, &err))) /* untimed warm-up */
        goto fail;
    /* calibrate: one timed step sets the count for about target_s; its save
     * holds the state every later timed step starts from */
    double t0 = tr_clock_seconds();
    int cg = 0;
    if ((rc = one_step(&b, bc, h, &cg, &err)))
        goto fail;
    double t1 = tr_clock_seconds() - t0;
    int k = steps > 0 ? steps : (int)fmin(fmax(target_s / fmax(t1, 1e-6), 3.0), 50.0);
    double *ts = malloc((size_t)k * sizeof *ts);
    if (!ts) {
        snprintf(r->error, sizeof r->error, "out of memory");
        goto done;
    }
    long cgsum = 0;
    for (int i = 0; i < k; i++) {
        if ((rc = b.ops->restore(b.state, &err))) {
            free(ts);
            goto fail;
        }
        double a = tr_clock_seconds();
        if ((rc = one_step(&b, bc, h, &cg, &err))) {
            free(ts);
            goto fail;
        }
        ts[i] = tr_clock_seconds() - a;
        cgsum += cg;
    }
    qsort(ts, (size_t)k, sizeof *ts, cmp_double);
    r->steps = k;
    r->step_min = ts[0];
    r->step_med = ts[k / 2];
    r->cg_per_step = (double)cgsum / k;
    free(ts);
    int kc = bc->search ? 3 : 0;
    if ((rc = b.ops->restore(b.state, &err)))
        goto fail;
    double a = tr_clock_seconds();
    for (int i = 0; i < kc; i++)
        if ((rc = contacts(&b, bc, &r->pairs, &err)))
            goto fail;
    r->contacts_s = kc ? (tr_clock_seconds() - a) / kc : NAN;
    goto done;
fail:
    snprintf(r->error, sizeof r->error, "%.290s", err.msg);
done:
    free(x);
    tr_backend_close(&b);
}

/* Per-kernel device times from a profiled backend: two steps after a warm-up,
 * each from the warm-up's start state (see the top of this file). */
static void profile_kernels(const char *spec, const tr_curve *c, const bench_ctx *bc, double h,
                            result *r)
{
    tr_error err;
    tr_backend b;
    if (tr_backend_open_device(spec, c, 1, &b, &err) != TR_OK)
        return;
    int ok = contacts(&b, bc, NULL, &err) == TR_OK && one_step(&b, bc, h, NULL, &err) == TR_OK;
    if (ok) {
        tr_kernel_time before[MAX_K];
        int nb = tr_backend_profile(&b, before, MAX_K);
        ok = b.ops->restore(b.state, &err) == TR_OK && one_step(&b, bc, h, NULL, &err) == TR_OK &&
             b.ops->restore(b.state, &err) == TR_OK && one_step(&b, bc, h, NULL, &err) == TR_OK &&
             b.ops->restore(b.state, &err) == TR_OK && contacts(&b, bc, NULL, &err) == TR_OK;
        if (ok) {
            r->nk = tr_backend_profile(&b, r->k, MAX_K);
            for (int i = 0; i < r->nk; i++)
                for (int j = 0; j < nb; j++)
                    if (!strcmp(r->k[i].kernel, before[j].kernel)) {
                        r->k[i].launches -= before[j].launches;
                        r->k[i].seconds -= before[j].seconds;
                    }
            r->k_steps = 2;
        }
    }
    tr_backend_close(&b);
}

/* "1e3,1e4": each an integer from 8 to 5e7, written any way strtod reads
 * (so 1e5 works), nothing else; -1 on any bad or empty item. */
static int parse_list(const char *s, size_t *out, int max)
{
    int n = 0;
    const char *p = s;
    for (;;) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char item[64];
        double v;
        if (n == max || len == 0 || len >= sizeof item)
            return -1;
        memcpy(item, p, len);
        item[len] = 0;
        if (tr_arg_double(item, 8, 5e7, &v) || v != floor(v))
            return -1;
        out[n++] = (size_t)v;
        if (!comma)
            return n;
        p = comma + 1;
    }
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: tightrope bench [--device SPEC]... [--n LIST] [--start FILE] [--contacts C,T] [--steps K]\n"
            "                      [--time S] [--no-kernels] [--no-search] [--json]\n"
            "  --device SPEC  reference, auto, P:D or a name part; repeatable (default: the\n"
            "                 reference and every usable OpenCL device)\n"
            "  --n LIST       vertex counts, e.g. 1e3,1e4,1e5 (default 1000,10000,100000)\n"
            "  --steps K      timed steps per device and N (default: about --time seconds)\n"
            "  --time S       target seconds of timed steps per device and N (default 2)\n"
            "  --no-kernels   skip the profiled per-kernel run\n"
            "  --start FILE   start from this curve (e.g. a tight knot) resampled to each N\n"
            "                 by a Fourier low-pass, instead of the torus knot T(2,3)\n"
            "  --contacts C,T the contact list's cutoff and tilt (default: the engine's for\n"
            "                 a step that moves vertices one edge length; 2.1,1 is the\n"
            "                 plain cutoff list of earlier versions)\n"
            "  --no-search    no neighbour search (empty contact list)\n"
            "  --json         one JSON object instead of the table\n");
}

/* The command line, once read. */
typedef struct bench_opts {
    const char *devs[MAX_DEV];
    char pd[MAX_DEV][16]; /* the default devices' ids */
    int ndev, json, steps, kernels, search;
    const char *start;
    double shape_cut, shape_tilt; /* 0: the engine's */
    double target;
    size_t ns[MAX_N];
    int nn;
} bench_opts;

/* Step 1: the options into o. Returns -1 to go on, else the exit status. */
static int parse_options(int argc, char **argv, bench_opts *o)
{
    memset(o, 0, sizeof *o);
    o->kernels = 1;
    o->search = 1;
    o->target = 2.0;
    o->ns[0] = 1000;
    o->ns[1] = 10000;
    o->ns[2] = 100000;
    o->nn = 3;
    static const char *valued[] = {"--device", "--n", "--contacts", "--start", "--steps", "--time"};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--json")) {
            o->json = 1;
            continue;
        }
        if (!strcmp(a, "--no-kernels")) {
            o->kernels = 0;
            continue;
        }
        if (!strcmp(a, "--no-search")) {
            o->search = 0;
            continue;
        }
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        int takes = 0;
        for (size_t k = 0; k < sizeof valued / sizeof valued[0]; k++)
            takes |= !strcmp(a, valued[k]);
        if (!takes) {
            fprintf(stderr, "tightrope bench: unknown %s '%s' (see tightrope bench --help)\n",
                    a[0] == '-' ? "option" : "argument", a);
            return 2;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "tightrope bench: %s needs a value\n", a);
            return 2;
        }
        const char *v = argv[++i];
        int bad = 0;
        if (!strcmp(a, "--device")) {
            if (o->ndev == MAX_DEV) {
                fprintf(stderr, "tightrope bench: at most %d devices\n", MAX_DEV);
                return 2;
            }
            /* an unknown or unusable device is refused now, not after the
             * other devices' runs */
            tr_error derr;
            int drc = tr_backend_check_spec(v, &derr);
            if (drc != TR_OK) {
                fprintf(stderr, "tightrope bench: %s\n", derr.msg);
                return drc == TR_EINVAL ? 2 : 1;
            }
            o->devs[o->ndev++] = v;
        } else if (!strcmp(a, "--n")) {
            o->nn = parse_list(v, o->ns, MAX_N);
            if (o->nn <= 0) {
                fprintf(stderr, "tightrope bench: bad --n list '%s' (integers from 8 to 5e7, e.g. 1e3,1e4)\n", v);
                return 2;
            }
        } else if (!strcmp(a, "--contacts")) {
            char tail;
            if (sscanf(v, "%lf,%lf%c", &o->shape_cut, &o->shape_tilt, &tail) != 2 ||
                !(o->shape_cut > 2.0) || !(o->shape_cut < 100.0) || !(o->shape_tilt > 0.0) ||
                !(o->shape_tilt <= 1.0)) {
                fprintf(stderr, "tightrope bench: bad --contacts '%s' (CUTOFF,TILT: 2 < CUTOFF, 0 < TILT <= 1)\n",
                        v);
                return 2;
            }
        } else if (!strcmp(a, "--start")) {
            o->start = v;
        } else if (!strcmp(a, "--steps")) {
            bad = tr_arg_int(v, 1, 100000, &o->steps);
        } else {
            bad = tr_arg_double(v, 0, 3600, &o->target) || !(o->target > 0 && o->target < 3600);
        }
        if (bad) {
            fprintf(stderr, "tightrope bench: bad %s '%s'\n", a, v);
            return 2;
        }
    }
    return -1;
}

/* Step 2: without --device, the reference and every usable OpenCL device. */
static void default_devices(bench_opts *o)
{
    if (o->ndev > 0)
        return;
    o->devs[o->ndev++] = "reference";
    tr_device_list l;
    tr_error err;
    if (tr_backend_list_devices(&l, &err) == TR_OK) {
        for (int i = 0; i < l.n && o->ndev < MAX_DEV; i++)
            if (l.dev[i].usable) {
                snprintf(o->pd[o->ndev], sizeof o->pd[o->ndev], "%.15s", l.dev[i].id);
                o->devs[o->ndev] = o->pd[o->ndev];
                o->ndev++;
            }
        tr_backend_device_list_free(&l);
    }
}

/* Step 3: the engine's parameters with a fixed solver work per step (see the
 * top of this file). */
static void bench_params(bench_ctx *bc, int search)
{
    tr_engine_params_default(&bc->prm);
    bc->search = search;
    bc->prm.correct.max_newton = 2;
    bc->prm.correct.max_cg = 20;
    bc->prm.correct.cg_rtol = 0.0;
    bc->prm.correct.viol_tol = 0.0;
    bc->prm.proj.max_newton = 1;
    bc->prm.proj.max_cg = 10;
    bc->prm.proj.cg_rtol = 0.0;
}

/* Step 4: every device at the j-th N, into res[j ndev ..]: the reference's
 * validation state, then each device timed (and profiled). Returns -1 to go
 * on, else the exit status; *status becomes 1 when a device fails. */
static int bench_size(const bench_opts *o, bench_ctx *bc, const tr_curve *start_curve, int j,
                      result *res, int *status)
{
    tr_curve c;
    tr_error err;
    int crc = o->start ? tr_refine_lowpass(start_curve, o->ns[j], 0.5, 0.5, &c, &err)
                       : tr_make_torus(&c, 2, 3, o->ns[j], &err);
    if (crc != TR_OK) {
        fprintf(stderr, "tightrope bench: %s\n", err.msg);
        /* an N or a start curve the user can change */
        return crc == TR_ENOMEM ? 1 : 2;
    }
    int gap = tr_exclusion_gap(1.0, tr_curve_length(&c) / (double)c.nv);
    bc->gap = &gap;
    double h = tr_curve_length(&c) / (double)c.nv; /* the engine starts with h = ebar */
    /* the engine's tilt after a step that moved vertices by one edge
     * length (tighter steps move less, loose ones more) */
    tr_engine_contact_shape(&bc->prm, h, 1.0, h, &bc->cutoff, &bc->tilt);
    if (o->shape_cut > 0.0) {
        bc->cutoff = o->shape_cut;
        bc->tilt = o->shape_tilt;
    }
    /* the reference's state after the validation step */
    double *ref_x = malloc(3 * c.nv * sizeof *ref_x);
    tr_backend rb;
    int have_ref = ref_x && tr_backend_open("reference", &c, &rb, &err) == TR_OK;
    if (have_ref) {
        have_ref = validation_step(&rb, bc, h, NULL, &err) == TR_OK &&
                   rb.ops->download(rb.state, ref_x, NULL, &err) == TR_OK;
        tr_backend_close(&rb);
    }
    if (!o->json)
        fprintf(stderr, "N = %zu ...\n", o->ns[j]);
    double ref_med = 0;
    for (int d = 0; d < o->ndev; d++) {
        result *r = &res[j * o->ndev + d];
        int is_ref = tr_device_spec_is_reference(o->devs[d]);
        bench_one(o->devs[d], &c, bc, o->steps, o->target, is_ref || !have_ref ? NULL : ref_x, h, r);
        if (!is_ref && !have_ref) {
            r->valid = 0;
            snprintf(r->error, sizeof r->error, "no reference state to validate against: %.200s",
                     err.msg);
        }
        if (is_ref && !r->error[0])
            ref_med = r->step_med;
        if (!is_ref && o->kernels && r->valid && !r->error[0])
            profile_kernels(o->devs[d], &c, bc, h, r);
        if (r->error[0])
            *status = 1;
    }
    for (int d = 0; d < o->ndev; d++) {
        result *r = &res[j * o->ndev + d];
        r->ratio = ref_med > 0 && r->step_med > 0 ? ref_med / r->step_med : NAN;
    }
    free(ref_x);
    tr_curve_free(&c);
    return -1;
}

/* Step 5: the report as JSON. Returns 1 when it could not be written. */
static int print_json(const bench_opts *o, const result *res)
{
    int status = 0;
    tr_text t = {0};
    tr_text_printf(&t, "{\"benchmark\": \"tightening step (tension_step with projection 1x10 CG, "
                       "correct 2x20 CG, measure) on %s\",\n \"results\": [",
                   o->start ? "the --start curve, Fourier-resampled to each N" : "a T(2,3) torus knot");
    for (int i = 0; i < o->ndev * o->nn; i++) {
        const result *r = &res[i];
        tr_text_printf(&t, "%s\n  {\"device\": ", i ? "," : "");
        tr_json_string(&t, r->device);
        tr_text_printf(&t, ", \"n\": %zu, \"valid\": %s, \"validation_diff\": ", r->n,
                       r->valid ? "true" : "false");
        tr_json_number(&t, "%.3g", r->valid_diff);
        if (r->error[0]) {
            tr_text_printf(&t, ", \"error\": ");
            tr_json_string(&t, r->error);
            tr_text_printf(&t, "}");
            continue;
        }
        tr_text_printf(&t, ", \"steps\": %d, \"step_s_min\": %.6g, \"step_s_median\": %.6g, "
                           "\"steps_per_s\": %.6g, \"vertex_steps_per_s\": %.6g, "
                           "\"cg_iters_per_step\": %.1f, \"contacts_s\": ",
                       r->steps, r->step_min, r->step_med, 1.0 / r->step_med,
                       (double)r->n / r->step_med, r->cg_per_step);
        /* null without a search (--no-search) or without the reference in the run */
        tr_json_number(&t, "%.6g", r->contacts_s);
        tr_text_printf(&t, ", \"pairs\": %zu, \"speedup_vs_reference\": ", r->pairs);
        tr_json_number(&t, "%.4g", r->ratio);
        if (r->nk) {
            tr_text_printf(&t, ", \"kernels_per_step\": {");
            for (int k = 0; k < r->nk; k++)
                tr_text_printf(&t, "%s\"%s\": {\"launches\": %.1f, \"s\": %.6g}", k ? ", " : "",
                               r->k[k].kernel, r->k[k].launches / r->k_steps,
                               r->k[k].seconds / r->k_steps);
            tr_text_printf(&t, "}");
        }
        tr_text_printf(&t, "}");
    }
    tr_text_printf(&t, "\n ]}\n");
    char *doc = tr_text_take(&t, NULL);
    if (!doc) {
        fprintf(stderr, "tightrope bench: out of memory writing the JSON report\n");
        status = 1;
    } else {
        fputs(doc, stdout);
        free(doc);
    }
    return status;
}

/* Step 5 without --json: the table, the kernels per step and the growth of
 * the step and search times with N. */
static void print_table(const bench_opts *o, result *res)
{
    printf("%-58s %9s %6s %11s %11s %13s %8s %10s %9s %8s\n", "device", "N", "steps", "step ms",
           "steps/s", "vertex-st/s", "cg/step", "search ms", "pairs", "vs ref");
    for (int i = 0; i < o->ndev * o->nn; i++) {
        const result *r = &res[i];
        if (r->error[0]) {
            printf("%-58.58s %9zu  %s\n", r->device, r->n, r->error);
            continue;
        }
        /* no search (--no-search) or no reference in the run: a dash, not "nan" */
        char search[16] = "-", ratio[16] = "-";
        if (isfinite(r->contacts_s))
            snprintf(search, sizeof search, "%.2f", 1e3 * r->contacts_s);
        if (isfinite(r->ratio))
            snprintf(ratio, sizeof ratio, "%.3g", r->ratio);
        printf("%-58.58s %9zu %6d %11.3f %11.3f %13.4g %8.1f %10s %9zu %8s\n", r->device, r->n,
               r->steps, 1e3 * r->step_med, 1.0 / r->step_med, (double)r->n / r->step_med,
               r->cg_per_step, search, r->pairs, ratio);
    }
    for (int i = 0; i < o->ndev * o->nn; i++) {
        const result *r = &res[i];
        if (!r->nk)
            continue;
        printf("\nkernels per step, %s, N = %zu (profiled run; total %s):\n", r->device, r->n,
               "device time of each kernel");
        /* largest first */
        for (int a = 0; a < r->nk; a++)
            for (int b = a + 1; b < r->nk; b++)
                if (r->k[b].seconds > r->k[a].seconds) {
                    tr_kernel_time t = res[i].k[a];
                    res[i].k[a] = r->k[b];
                    res[i].k[b] = t;
                }
        for (int k = 0; k < r->nk && k < 12; k++)
            printf("  %-18s %8.1f launches %10.3f ms\n", r->k[k].kernel, r->k[k].launches / r->k_steps,
                   1e3 * r->k[k].seconds / r->k_steps);
    }
    /* cost growth: exponent of step time between successive N, per device */
    for (int d = 0; d < o->ndev && o->nn > 1; d++) {
        printf("\n%s: step time grows like N^p:", res[d].device);
        for (int j = 1; j < o->nn; j++) {
            const result *a = &res[(j - 1) * o->ndev + d], *b = &res[j * o->ndev + d];
            if (a->error[0] || b->error[0])
                continue;
            printf("  %zu->%zu p = %.2f", a->n, b->n,
                   log(b->step_med / a->step_med) / log((double)b->n / (double)a->n));
        }
        printf("\n");
        if (!o->search)
            continue;
        printf("%s: search time grows like N^p:", res[d].device);
        for (int j = 1; j < o->nn; j++) {
            const result *a = &res[(j - 1) * o->ndev + d], *b = &res[j * o->ndev + d];
            if (a->error[0] || b->error[0] || !(a->contacts_s > 0) || !(b->contacts_s > 0))
                continue;
            printf("  %zu->%zu p = %.2f", a->n, b->n,
                   log(b->contacts_s / a->contacts_s) / log((double)b->n / (double)a->n));
        }
        printf("\n");
    }
}

int tr_cmd_bench(int argc, char **argv)
{
    bench_opts o;
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    default_devices(&o);
    bench_ctx bc;
    bench_params(&bc, o.search);
    result *res = calloc((size_t)(o.ndev * o.nn), sizeof *res);
    if (!res) {
        fprintf(stderr, "tightrope bench: out of memory\n");
        return 1;
    }
    int status = 0;
    tr_curve start_curve;
    if (o.start) {
        tr_error err;
        if (tr_curve_read(o.start, TR_FORMAT_AUTO, &start_curve, &err) != TR_OK) {
            fprintf(stderr, "tightrope bench: %s\n", err.msg);
            free(res);
            return 2;
        }
    }
    for (int j = 0; j < o.nn && rc < 0; j++)
        rc = bench_size(&o, &bc, o.start ? &start_curve : NULL, j, res, &status);
    if (rc < 0) {
        if (o.json)
            status |= print_json(&o, res);
        else
            print_table(&o, res);
        rc = status;
    }
    if (o.start)
        tr_curve_free(&start_curve);
    free(res);
    return rc;
}
