/* tightrope tighten IN -o OUT [options]
 *
 * Tightens a knot, link or clasp with the tightening layer (tr_tighten,
 * tighten/tighten.h: the route, the roads, the start's preparation, the
 * engine, the certificate) and writes the result with its certificate: the
 * thickness oracle's numbers for the written curve (rescaled to thickness
 * exactly 1 when no vertex is constrained, so that ropelength = length),
 * the engine's residual, the KKT certificate of the written curve (by
 * default up to TR_TIGHTEN_KKT_AUTO_MAX_N vertices, where it takes
 * seconds), the steps and the command line. SIGINT/SIGTERM/SIGHUP stop the
 * run at the next step, write a last checkpoint (with --checkpoint) and
 * the output, and exit 1. This file is the command line over the layer:
 * parsing (tr_cli_tighten_parse), the progress line and notes on stderr,
 * the output file and the summary. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/cli_args.h"
#include "cli/cli_interrupt.h"
#include "cli/cli_tighten.h"
#include "curve/curve_io.h"
#include "util/clock.h"
#include "util/text_file.h"

/* What the progress line and the notes share on stderr. */
typedef struct say_ctx {
    int tty, quiet;
    int printed; /* a progress line is open */
} say_ctx;

static void end_line(say_ctx *ctx)
{
    if (ctx->printed)
        fprintf(stderr, "\n");
    ctx->printed = 0;
}

static void on_progress(const tr_tighten_progress *p, void *user)
{
    say_ctx *ctx = user;
    if (!ctx->tty)
        return;
    fprintf(stderr, "\rropelength %.6f  residual %.2e  %7.1f steps/s  N %zu  steps %ld  elapsed %.1f s   ",
            p->ropelength, p->residual, p->steps_per_s, p->n, p->steps, p->elapsed);
    fflush(stderr);
    ctx->printed = 1;
}

/* The layer's notes: the route, the roads (not with --quiet), warnings. */
static void on_note(int kind, const char *msg, void *user)
{
    say_ctx *ctx = user;
    if (kind == TR_TIGHTEN_INFO && ctx->quiet)
        return;
    end_line(ctx);
    fprintf(stderr, "tightrope tighten: %s\n", msg);
}

/* Whether a and b name the same file: the same inode where both exist
 * (text_file.h), else the same path. */
static int same_file(const char *a, const char *b) { return tr_same_file(a, b) || !strcmp(a, b); }

/* Parses the command line into o and checks the paths against each other.
 * Returns -1 to go on, else the exit status (0 after --help, 2 for a bad
 * command line, with its message printed). */
int tr_cli_tighten_parse(int argc, char **argv, tr_cli_tighten *t)
{
    *t = (tr_cli_tighten){0};
    tr_tighten_options *o = &t->opt;
    tr_tighten_options_default(o);
    int newton = 0, no_newton = 0;
    static const char *valued[] = {"-o", "--output", "--n", "--refine-to", "--target", "--residual",
                                   "--steps", "--time-limit", "--checkpoint", "--checkpoint-every",
                                   "--resume", "--device", "--device-from", "--tries", "--seed",
                                   "--shuffles", "--contacts"};
    /* what a bad value of each should have been, in the order of valued */
    static const char *wants[] = {"", "", "an integer >= 4, vertices per component",
                                  "an integer >= 4, vertices per component", "a number > 0", "a number >= 0",
                                  "an integer >= 1", "a number > 0 (seconds)", "", "a number > 0 (seconds)", "",
                                  "", "an integer >= 0", "an integer from 1 to 1000", "an integer >= 0",
                                  "an integer from 0 to --tries - 1", "segment or vertex"};
    unsigned char given[sizeof valued / sizeof valued[0]] = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            tr_cli_tighten_usage(stdout);
            return 0;
        }
        if (!strcmp(a, "--json")) {
            t->json = 1;
            continue;
        }
        if (!strcmp(a, "--newton")) {
            newton = 1;
            continue;
        }
        if (!strcmp(a, "--no-newton")) {
            no_newton = 1;
            continue;
        }
        if (!strcmp(a, "--no-polish")) {
            o->polish = 0;
            continue;
        }
        if (!strcmp(a, "--kkt") || !strcmp(a, "--no-kkt")) {
            if (o->kkt >= 0 && o->kkt != (a[2] == 'k')) {
                fprintf(stderr, "tightrope tighten: --kkt and --no-kkt contradict each other\n");
                return 2;
            }
            o->kkt = a[2] == 'k';
            continue;
        }
        if (!strcmp(a, "--quiet")) {
            t->quiet = 1;
            continue;
        }
        if (!strcmp(a, "--scale")) {
            o->scale = 1;
            continue;
        }
        int takes = 0;
        for (size_t k = 0; k < sizeof valued / sizeof valued[0]; k++)
            if (!strcmp(a, valued[k])) {
                takes = 1;
                /* -o and --output are one option */
                size_t slot = k == 1 ? 0 : k;
                if (given[slot]) {
                    fprintf(stderr, "tightrope tighten: %s given twice (which one?)\n", a);
                    return 2;
                }
                given[slot] = 1;
            }
        if (takes) {
            if (i + 1 >= argc) {
                fprintf(stderr, "tightrope tighten: %s needs a value\n", a);
                return 2;
            }
            const char *v = argv[++i];
            int bad = 0;
            if (!strcmp(a, "-o") || !strcmp(a, "--output"))
                t->out = v;
            else if (!strcmp(a, "--n"))
                bad = tr_arg_long(v, 4, LONG_MAX, &o->n);
            else if (!strcmp(a, "--refine-to")) {
                bad = tr_arg_long(v, 4, LONG_MAX, &o->refine_to);
                o->refine_given = 1;
            }
            else if (!strcmp(a, "--target"))
                bad = tr_arg_double(v, 0, DBL_MAX, &o->target) || o->target <= 0;
            else if (!strcmp(a, "--residual")) {
                bad = tr_arg_double(v, 0, DBL_MAX, &o->residual);
                o->residual_given = 1;
            }
            else if (!strcmp(a, "--steps"))
                bad = tr_arg_long(v, 1, LONG_MAX, &o->steps);
            else if (!strcmp(a, "--time-limit"))
                bad = tr_arg_double(v, 0, DBL_MAX, &o->time_limit) || o->time_limit <= 0;
            else if (!strcmp(a, "--checkpoint"))
                o->checkpoint = v;
            else if (!strcmp(a, "--checkpoint-every"))
                bad = tr_arg_double(v, 0, DBL_MAX, &o->checkpoint_every) || o->checkpoint_every <= 0;
            else if (!strcmp(a, "--resume"))
                o->resume = v;
            else if (!strcmp(a, "--device-from"))
                bad = tr_arg_long(v, 0, LONG_MAX, &o->device_from);
            else if (!strcmp(a, "--tries"))
                bad = tr_arg_long(v, 1, 1000, &o->tries);
            else if (!strcmp(a, "--seed"))
                bad = tr_arg_long(v, 0, LONG_MAX, &o->seed);
            else if (!strcmp(a, "--shuffles"))
                bad = tr_arg_long(v, 0, 999, &o->shuffles);
            else if (!strcmp(a, "--contacts")) {
                /* measure's words: Rawdon's segments, or SP-FEM's vertices */
                bad = strcmp(v, "segment") && strcmp(v, "vertex");
                o->contacts = !strcmp(v, "vertex") ? TR_CONTACTS_VERTEX : TR_CONTACTS_RAWDON;
            }
            else
                o->device = v;
            if (bad) {
                size_t k = 0;
                while (strcmp(a, valued[k]))
                    k++;
                fprintf(stderr, "tightrope tighten: bad %s '%s' (%s)\n", a, v, wants[k]);
                return 2;
            }
            continue;
        }
        if (a[0] == '-' && a[1]) {
            fprintf(stderr, "tightrope tighten: unknown option '%s' (see tightrope tighten --help)\n", a);
            return 2;
        }
        if (t->in) {
            fprintf(stderr, "tightrope tighten: unexpected argument '%s'\n", a);
            return 2;
        }
        t->in = a;
    }
    if (!t->in && !o->resume) {
        fprintf(stderr, "tightrope tighten: no input curve (see tightrope tighten --help)\n");
        return 2;
    }
    if (!t->out) {
        fprintf(stderr, "tightrope tighten: no output file (-o OUT)\n");
        return 2;
    }
    if (o->resume && o->tries > 1) {
        fprintf(stderr, "tightrope tighten: --resume continues one road; --tries starts several\n");
        return 2;
    }
    if (o->shuffles > 0 && o->tries == 0) {
        fprintf(stderr, "tightrope tighten: --shuffles %ld needs --tries K (K > %ld): which roads are shuffled "
                        "is counted from the last of K\n", o->shuffles, o->shuffles);
        return 2;
    }
    if (o->tries > 0 && o->shuffles >= o->tries) {
        fprintf(stderr, "tightrope tighten: --shuffles %ld: at most --tries - 1 (%ld) of the roads are shuffled; "
                        "the first is the start as given\n", o->shuffles, o->tries - 1);
        return 2;
    }
    if (newton && no_newton) {
        fprintf(stderr, "tightrope tighten: --newton and --no-newton contradict each other\n");
        return 2;
    }
    if (o->resume && (t->in || o->n > 0 || o->scale)) {
        fprintf(stderr, "tightrope tighten: --resume continues the checkpoint's curve; %s\n",
                t->in ? "drop the input file" : o->n > 0 ? "--n cannot resample it" : "--scale cannot scale it");
        return 2;
    }
    /* the checkpoint is rewritten during the run: over the input it would
     * destroy the start, over the output the output would replace it */
    /* the output is written over whatever it names: never over an input */
    const char *src = t->in ? t->in : o->resume;
    if (same_file(t->out, src)) {
        fprintf(stderr, "tightrope tighten: the output %s is the %s %s; write the result elsewhere\n", t->out,
                t->in ? "input" : "checkpoint to resume", src);
        return 2;
    }
    if (o->checkpoint && (same_file(o->checkpoint, t->out) || (t->in && same_file(o->checkpoint, t->in)))) {
        fprintf(stderr, "tightrope tighten: --checkpoint %s is the %s file\n", o->checkpoint,
                same_file(o->checkpoint, t->out) ? "output" : "input");
        return 2;
    }
    o->newton = newton ? 1 : no_newton ? -1 : 0;
    o->name = t->in;
    /* the vertex model's route is the solver alone (vertex_route.c): the
     * options of Rawdon's route are refused before anything is read */
    const char *conflict = tr_tighten_vertex_conflict(o);
    if (conflict) {
        fprintf(stderr, "tightrope tighten: %s\n", conflict);
        return 2;
    }
    return -1;
}

/* The exit status of a finished run, with its notes on stderr: 1 when it
 * was interrupted or did not reach a requested ropelength, residual or N. */
static int final_status(const tr_cli_tighten *t, const tr_tighten_result *r)
{
    const char *ckpt = r->checkpointed ? t->opt.checkpoint : NULL;
    if (r->checkpoint_failures > 0)
        fprintf(stderr, "tightrope tighten: warning: %d checkpoint%s could not be written (the run went on): %s\n",
                r->checkpoint_failures, r->checkpoint_failures > 1 ? "s" : "", r->checkpoint_why);
    if (r->interrupted)
        fprintf(stderr, "tightrope tighten: interrupted; %s%s%swrote %s\n", ckpt ? "checkpoint " : "",
                ckpt ? ckpt : "", ckpt ? " and " : "", t->out);
    if (r->refine_short) {
        fprintf(stderr, "tightrope tighten: stopped (%s) at N %zu before reaching %s %ld; wrote %s\n",
                tr_stop_reason_name(r->stop), r->curve.nv / (size_t)r->curve.ncomp,
                r->refine_implied ? "the start's N" : "the requested --refine-to", r->refine_to, t->out);
        return 1;
    }
    if (r->goal_missed)
        fprintf(stderr, "tightrope tighten: stopped (%s) before reaching the requested %s; wrote %s\n",
                tr_stop_reason_name(r->stop), r->goal_target ? "ropelength" : "residual", t->out);
    if (r->interrupted || r->goal_missed)
        return 1;
    /* a run that exits 0 with a result longer than its start says so: the
     * lines above already speak for the runs that exit 1. Equal lengths to
     * 1e-6 (a circle: 6.285212 both) are not longer. */
    if (isfinite(r->start_ropelength) && r->ropelength > r->start_ropelength * (1.0 + 1e-6))
        fprintf(stderr,
                "tightrope tighten: warning: the result (ropelength %.6f) is longer than the start (%.6f): it "
                "stopped (%s) before it was shorter; wrote %s\n",
                r->ropelength, r->start_ropelength, tr_stop_reason_name(r->stop), t->out);
    return 0;
}

/* The exit status of a failed tr_tighten (cli.h): a curve or an option the
 * user can fix is 2; a device that fails (kernel build, OpenCL call),
 * memory, or a run stopped by its time limit or a signal before it had a
 * settled curve is 1; in the run, a checkpoint that cannot be written or a
 * bad option is the user's (2), a refused step, a device or memory failure
 * a run that did not get there (1). */
static int failure_status(tr_tighten_stage at, int rc)
{
    switch (at) {
    case TR_TIGHTEN_AT_START:
        return rc == TR_EOPENCL || rc == TR_ENOMEM || rc == TR_EUNSUPPORTED || rc == TR_EINTERRUPTED ? 1 : 2;
    case TR_TIGHTEN_AT_CHECK:
        return rc == TR_ENOMEM ? 1 : 2;
    case TR_TIGHTEN_AT_RUN:
        return rc == TR_EIO || rc == TR_EINVAL || rc == TR_EPARSE ? 2 : 1;
    case TR_TIGHTEN_AT_TYPE:
        return 1; /* the run changed the knot: the engine's failure, not the input's */
    default:
        return 2;
    }
}

/* SIGINT/SIGTERM/SIGHUP raise the interrupt flag (cli_interrupt.h), which
 * tr_tighten polls: the run stops at its next step and writes what it
 * has. A closed terminal or SSH session (SIGHUP) must not cost the run,
 * and its last messages then go to a closed pipe: SIGPIPE is ignored so
 * that the write fails (and is let go) instead of killing the process
 * before the output is written. */
static void catch_signals(void)
{
    tr_cli_catch_interrupts();
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_IGN;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGPIPE, &sa, NULL);
}

int tr_cli_tighten_run(const tr_cli_tighten *t, int argc, char **argv, tr_tighten_report *rep)
{
    if (rep)
        *rep = (tr_tighten_report){.kkt_residual = NAN, .stop = ""};
    tr_error err;
    tr_curve start = {0};
    double began = tr_clock_seconds();
    int rc = t->in ? tr_curve_read(t->in, TR_FORMAT_AUTO, &start, &err) : TR_OK;
    if (rc) {
        fprintf(stderr, "tightrope tighten: %s\n", err.msg);
        return failure_status(TR_TIGHTEN_AT_START, rc);
    }
    say_ctx say = {.tty = !t->quiet && isatty(2), .quiet = t->quiet};
    tr_tighten_options opt = t->opt;
    opt.name = t->in;
    opt.output_check = t->out;
    opt.cancel = tr_cli_interrupt_flag();
    opt.progress = t->quiet ? NULL : on_progress;
    opt.note = on_note;
    opt.user = &say;
    /* --time-limit bounds the command: reading the start is its time too
     * (half a second for a file of 2 x 10^5 vertices) */
    opt.began = began;
    /* a pipe (cat k.vect | tighten /dev/stdin) was read once, above; it is
     * tightened where it lies, as before the layer took the start as a curve */
    struct stat st;
    if (t->in && (stat(t->in, &st) != 0 || !S_ISREG(st.st_mode)))
        opt.centre = 0;
    catch_signals();
    tr_tighten_result r;
    rc = tr_tighten(t->in ? &start : NULL, &opt, &r, &err);
    tr_curve_free(&start);
    end_line(&say);
    if (rc) {
        fprintf(stderr, "tightrope tighten: %s%s\n", err.msg,
                r.failed_at == TR_TIGHTEN_AT_START && rc == TR_EINTERRUPTED ? "; nothing written" : "");
        return failure_status(r.failed_at, rc);
    }
    if ((rc = tr_cli_tighten_write(t, &r, argc, argv, &err))) {
        fprintf(stderr, "tightrope tighten: %s\n", err.msg);
        tr_tighten_result_free(&r);
        return 2;
    }
    if (rep)
        tr_cli_tighten_report(&r, rep);
    else
        tr_cli_tighten_summary(t, &r);
    rc = final_status(t, &r);
    tr_tighten_result_free(&r);
    return rc;
}

int tr_cmd_tighten(int argc, char **argv)
{
    tr_cli_tighten t;
    int rc = tr_cli_tighten_parse(argc, argv, &t);
    return rc >= 0 ? rc : tr_cli_tighten_run(&t, argc, argv, NULL);
}

int tr_tighten_check_args(int argc, char **argv)
{
    tr_cli_tighten t;
    return tr_cli_tighten_parse(argc, argv, &t);
}

int tr_tighten_stop_requested(void) { return tr_cli_interrupted() != 0; }
