/* tightrope tighten IN -o OUT [options]
 *
 * Tightens a knot, link or clasp (engine.h), optionally through refinement
 * levels, and writes the result with its certificate: the thickness oracle's
 * numbers for the written curve (rescaled to thickness exactly 1 when no
 * vertex is constrained, so that ropelength = length), the engine's
 * residual, the KKT certificate of the written curve (kkt.h; by default up
 * to KKT_AUTO_MAX_N vertices, where it takes seconds), the steps and the
 * command line. SIGINT/SIGTERM/SIGHUP stop the run at the next step,
 * write a last checkpoint (with --checkpoint) and the output, and exit 1.
 * --time-limit is a bound on the whole command (every road, shuffle,
 * settle and solve looks at it), not only on the engine's steps. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/cli_args.h"
#include "cli/cli_interrupt.h"
#include "curve/curve_io.h"
#include "engine/engine.h"
#include "curve/generate.h"
#include "curve/perturb.h"
#include "engine/shuffle.h"
#include "util/json.h"
#include "oracle/kkt.h"
#include "util/clock.h"
#include "util/text_file.h"
#include "oracle/thickness.h"

/* The certificate costs ~0.05 s at N = 400, ~1.2 s at 1600 and ~12 s at
 * 2400 on a 2-core machine (bench/notes/2026-11-23-kkt-certificate.md),
 * growing faster than N^2:
 * above this it runs only when asked for (--kkt). */
#define KKT_AUTO_MAX_N 2400

static void usage(FILE *out)
{
    fprintf(out,
            "usage: tightrope tighten IN -o OUT [options]\n"
            "       tightrope tighten --resume CKPT -o OUT [options]\n"
            "  IN                 start curve (.vect, .tsv, KnotPlot list); distances >= 2, MinRad >= 1\n"
            "  -o, --output OUT   tightened curve with its certificate in comments\n"
            "  --scale            first scale the start (and its constraint planes) to thickness\n"
            "                     exactly 1: for curves at another scale, e.g. tight knots from\n"
            "                     other codes; one then too coarse (edges >= 0.9) is resampled\n"
            "                     along a spline to edges of about 0.5 (without --n)\n"
            "  --n N              first resample every component to N vertices (along a\n"
            "                     spline through the vertices where that adds vertices)\n"
            "  --refine-to N      tighten, then refine (doubling, low-pass) and re-tighten up to N;\n"
            "                     without --n and --refine-to a loose start of N >= 200 vertices\n"
            "                     per component goes as --n N/4 --refine-to N (said on stderr)\n"
            "  --residual R       stop when the engine's residual falls below R (default 1e-4);\n"
            "                     given, the goal is also met by a KKT residual <= R of the output\n"
            "  --target X         stop when the ropelength estimate reaches X\n"
            "  --steps S          stop after S accepted steps in all (a resumed run counts\n"
            "                     the steps before its checkpoint)\n"
            "  --time-limit T     the whole command ends within T seconds of wall clock, every\n"
            "                     road, shuffle, settle and solve included (a resumed run counts\n"
            "                     the time before its checkpoint); the best state is written\n"
            "  --checkpoint FILE  write the state to FILE when the run starts, every\n"
            "                     --checkpoint-every seconds (default 300), at the end and on\n"
            "                     SIGINT/SIGTERM/SIGHUP\n"
            "  --resume FILE      continue from a checkpoint, to the goals it was started with\n"
            "                     (--refine-to, --target, --residual, --steps, --time-limit)\n"
            "                     unless given again\n"
            "  --device D         reference | auto | a device spec (default $TIGHTROPE_DEVICE or auto)\n"
            "  --device-from N    with --refine-to, coarse levels of fewer than N vertices in all\n"
            "                     run on the serial reference, where a device's cost per kernel\n"
            "                     launch outweighs it (default 2048; 0: the device at every level)\n"
            "  --newton           at the finest level, the second-order solver (Newton steps\n"
            "                     on an augmented Lagrangian, exact strut Hessians, CHOLMOD)\n"
            "                     in the polish's place (clasps included);\n"
            "                     without it the solver still takes a tight finest level (a\n"
            "                     tightened knot refined or resampled by --n) first\n"
            "  --no-newton        never the second-order solver\n"
            "  --tries K          K roads (default 1); the shortest result at the finest N is\n"
            "                     written. With levels (--refine-to): K scouts share half\n"
            "                     the time, each tightening its coarse level only: the start\n"
            "                     as given, then the start again from other coarse counts\n"
            "                     (--n or N/4, times 1, 1, 1.5, 0.6, 1.25, 0.8, ...), some\n"
            "                     inflated 1.5 times (the coarse level picks the local\n"
            "                     minimum); the shortest scout is then refined to N with the\n"
            "                     time left. With one level: each road an equal share of the\n"
            "                     time, the shortest result so far moved by a smooth random\n"
            "                     displacement (under half the rope's diameter, so the knot\n"
            "                     stays the same) and tightened again\n"
            "  --shuffles S       the last S of the K roads start from the start shuffled: the\n"
            "                     rope inflated 4 times (6 on every second shuffled road) is\n"
            "                     walked by random crankshaft moves (the knot type kept),\n"
            "                     compacted again (harder on every second) and tightened; another\n"
            "                     conformation, where the other roads keep the start's (default 0)\n"
            "  --seed S           the roads' seed (default 1): the same S, the same roads\n"
            "  --no-polish        skip the polish stage at every level (a serial augmented-\n"
            "                     Lagrangian / L-BFGS minimisation on the host, which ends each\n"
            "                     coarse level and at the finest takes the last 80%% of its time\n"
            "                     or runs when it jams)\n"
            "  --kkt              certify the output (KKT residual) at any N; by default only\n"
            "                     up to N = %d\n"
            "  --no-kkt           never certify the output\n"
            "  --json             print a JSON summary on stdout\n"
            "  --quiet            no progress line\n",
            KKT_AUTO_MAX_N);
}

typedef struct progress_ctx {
    int tty;
    int printed;
} progress_ctx;

static void on_progress(const tr_engine_progress *p, void *user)
{
    progress_ctx *ctx = user;
    if (!ctx->tty)
        return;
    fprintf(stderr, "\rropelength %.6f  residual %.2e  %7.1f steps/s  N %zu  steps %ld  elapsed %.1f s   ",
            p->ropelength, p->residual, p->steps_per_s, p->n, p->steps, p->elapsed);
    fflush(stderr);
    ctx->printed = 1;
}


static void json_num(const char *key, double v, int comma)
{
    if (isfinite(v))
        printf("  \"%s\": %.17g%s\n", key, v, comma ? "," : "");
    else
        printf("  \"%s\": null%s\n", key, comma ? "," : "");
}

static void json_str(const char *key, const char *v, int comma)
{
    printf("  \"%s\": ", key);
    tr_json_fputs(stdout, v);
    printf("%s\n", comma ? "," : "");
}

/* Whether a and b name the same file: the same inode where both exist
 * (text_file.h), else the same path. */
static int same_file(const char *a, const char *b) { return tr_same_file(a, b) || !strcmp(a, b); }

/* What the run needs of its start and its outputs, checked before it
 * starts: --refine-to refines, it never coarsens (any component above it
 * is an error), and the output's format and both paths. */
static int check_outputs(tr_engine *e, size_t refine_to, const char *out, const char *ckpt, tr_error *err)
{
    tr_curve c = {0};
    int rc = tr_engine_get_curve(e, &c, err);
    for (int k = 0; rc == TR_OK && refine_to > 0 && k < c.ncomp; k++)
        if (tr_comp_nv(&c, k) > refine_to)
            rc = tr_fail(err, TR_EINVAL, "--refine-to %zu is below the %zu vertices of component %d of the start; "
                         "it refines, it does not coarsen (--n resamples a start)", refine_to, tr_comp_nv(&c, k), k);
    if (rc == TR_OK)
        rc = tr_curve_check_output(out, TR_FORMAT_AUTO, &c, err);
    tr_curve_free(&c);
    if (rc == TR_OK && ckpt)
        rc = tr_check_writable(ckpt, err);
    return rc;
}

/* Scales the curve about the origin by f, constraints included. */
static void scale_curve(tr_curve *c, double f)
{
    for (size_t i = 0; i < 3 * c->nv; i++)
        c->x[i] *= f;
    for (int q = 0; q < c->ncst; q++) {
        for (int a = 0; a < 3; a++)
            c->cst[q].p[a] *= f;
        c->cst[q].d *= f;
    }
}

/* The command line's options. */
typedef struct tighten_opts {
    const char *in, *out, *ckpt, *resume, *device;
    long n, refine_to, steps, device_from, tries, seed, shuffles;
    int try_index; /* which of --tries this run is (0: the start as given) */
    double inflate; /* --tries: the start scaled up by this after --scale (1: not) */
    const tr_curve *road_from; /* --tries: the shortest result so far, this road's start */
    int road_as_is; /* road_from is refined as it is, not moved off its minimum */
    int shuffled; /* --shuffles: this road starts from IN shuffled (shuffle_start) */
    int shuffle_index; /* which of the shuffled roads (0: the first), so which recipe */
    double target, residual, time_limit, ckpt_every;
    /* --time-limit as a clock time (tr_clock_seconds; 0: none): the hard
     * bound of the whole command, which the roads' shares divide */
    double bound_at;
    int residual_given; /* the default residual is a stopping rule, not a goal */
    int refine_given;   /* --refine-to given (or taken from a checkpoint): a goal */
    /* subtracted from the start's coordinates (start_shift): a knot far
     * from the origin is tightened about it (0: as it is) */
    double shift[3];
    int json, quiet, no_polish, newton, no_newton, scale, kkt; /* kkt -1: up to KKT_AUTO_MAX_N */
} tighten_opts;

/* Parses the command line into o and checks the paths against each other.
 * Returns -1 to go on, else the exit status (0 after --help, 2 for a bad
 * command line, with its message printed). */
static int parse_options(int argc, char **argv, tighten_opts *o)
{
    *o = (tighten_opts){.inflate = 1.0, .device_from = -1, .residual = 1e-4, .ckpt_every = 300, .kkt = -1, .tries = 1, .seed = 1};
    static const char *valued[] = {"-o", "--output", "--n", "--refine-to", "--target", "--residual",
                                   "--steps", "--time-limit", "--checkpoint", "--checkpoint-every",
                                   "--resume", "--device", "--device-from", "--tries", "--seed",
                                   "--shuffles"};
    /* what a bad value of each should have been, in the order of valued */
    static const char *wants[] = {"", "", "an integer >= 4, vertices per component",
                                  "an integer >= 4, vertices per component", "a number > 0", "a number >= 0",
                                  "an integer >= 1", "a number > 0 (seconds)", "", "a number > 0 (seconds)", "",
                                  "", "an integer >= 0", "an integer from 1 to 1000", "an integer >= 0",
                                  "an integer from 0 to --tries - 1"};
    unsigned char given[sizeof valued / sizeof valued[0]] = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        if (!strcmp(a, "--json")) {
            o->json = 1;
            continue;
        }
        if (!strcmp(a, "--newton")) {
            o->newton = 1;
            continue;
        }
        if (!strcmp(a, "--no-newton")) {
            o->no_newton = 1;
            continue;
        }
        if (!strcmp(a, "--no-polish")) {
            o->no_polish = 1;
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
            o->quiet = 1;
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
                o->out = v;
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
                o->ckpt = v;
            else if (!strcmp(a, "--checkpoint-every"))
                bad = tr_arg_double(v, 0, DBL_MAX, &o->ckpt_every) || o->ckpt_every <= 0;
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
        if (o->in) {
            fprintf(stderr, "tightrope tighten: unexpected argument '%s'\n", a);
            return 2;
        }
        o->in = a;
    }
    if (!o->in && !o->resume) {
        fprintf(stderr, "tightrope tighten: no input curve (see tightrope tighten --help)\n");
        return 2;
    }
    if (!o->out) {
        fprintf(stderr, "tightrope tighten: no output file (-o OUT)\n");
        return 2;
    }
    if (o->resume && o->tries > 1) {
        fprintf(stderr, "tightrope tighten: --resume continues one road; --tries starts several\n");
        return 2;
    }
    if (o->shuffles >= o->tries) {
        fprintf(stderr, "tightrope tighten: --shuffles %ld: at most --tries - 1 (%ld) of the roads are shuffled; "
                        "the first is the start as given\n", o->shuffles, o->tries - 1);
        return 2;
    }
    if (o->newton && o->no_newton) {
        fprintf(stderr, "tightrope tighten: --newton and --no-newton contradict each other\n");
        return 2;
    }
    if (o->resume && (o->in || o->n > 0 || o->scale)) {
        fprintf(stderr, "tightrope tighten: --resume continues the checkpoint's curve; %s\n",
                o->in ? "drop the input file" : o->n > 0 ? "--n cannot resample it" : "--scale cannot scale it");
        return 2;
    }
    /* the checkpoint is rewritten during the run: over the input it would
     * destroy the start, over the output the output would replace it */
    /* the output is written over whatever it names: never over an input */
    const char *src = o->in ? o->in : o->resume;
    if (same_file(o->out, src)) {
        fprintf(stderr, "tightrope tighten: the output %s is the %s %s; write the result elsewhere\n", o->out,
                o->in ? "input" : "checkpoint to resume", src);
        return 2;
    }
    if (o->ckpt && (same_file(o->ckpt, o->out) || (o->in && same_file(o->ckpt, o->in)))) {
        fprintf(stderr, "tightrope tighten: --checkpoint %s is the %s file\n", o->ckpt,
                same_file(o->ckpt, o->out) ? "output" : "input");
        return 2;
    }
    return -1;
}

/* A start at thickness 1 (after --scale) whose edges are longer than the
 * engine takes (a KnotPlot start of 101 vertices: edges of 1.31) is
 * resampled along a spline through its vertices to edges of about
 * COARSE_EDGE, and scaled to thickness 1 again (the spline changes it a
 * little), instead of being refused: the user asked for a rope, not for a
 * vertex count. --refine-to, if given, caps the count as long as the edges
 * stay below MAX_COARSE_EDGE. */
#define COARSE_EDGE 0.5
#define MAX_COARSE_EDGE 0.9
static int densify_coarse(const tighten_opts *o, tr_curve *c, tr_error *err)
{
    for (int pass = 0; pass < 3; pass++) {
        int coarse = 0;
        size_t *per = malloc((size_t)c->ncomp * sizeof *per);
        if (!per)
            return tr_fail(err, TR_ENOMEM, "out of memory");
        for (int k = 0; k < c->ncomp; k++) {
            size_t nv = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
            double len = tr_comp_length(c, k);
            per[k] = nv;
            if (len / (double)ne < MAX_COARSE_EDGE)
                continue;
            coarse = 1;
            size_t want = (size_t)ceil(len / COARSE_EDGE), least = (size_t)ceil(len / MAX_COARSE_EDGE) + 1;
            if (o->refine_to > 0 && want > (size_t)o->refine_to)
                want = (size_t)o->refine_to > least ? (size_t)o->refine_to : least;
            per[k] = want > nv ? want : nv + 1;
        }
        if (!coarse) {
            free(per);
            return TR_OK;
        }
        tr_curve r;
        int rc = tr_resample_smooth(c, per, &r, err);
        free(per);
        if (rc)
            return rc;
        tr_curve_free(c);
        *c = r;
        tr_thickness t;
        if ((rc = tr_thickness_measure(c, NULL, &t, NULL, err)))
            return tr_fail_wrap(err, rc, "%s (resampled)", o->in);
        if (!(t.thickness > 0 && isfinite(t.thickness)))
            return tr_fail(err, TR_EGEOMETRY, "%s: resampled along a spline, it has thickness %g", o->in,
                           t.thickness);
        scale_curve(c, 1.0 / t.thickness);
        fprintf(stderr, "tightrope tighten: %s: too coarse for thickness 1; resampled along a spline to %zu vertices\n",
                o->in, c->nv);
    }
    return TR_OK;
}

/* --tries: road o->try_index starts from the shortest result so far moved
 * by a smooth displacement of at most TRY_AMPLITUDE of its thickness
 * (perturb.h) and scaled back to its thickness (basin hopping). Every strand
 * moves less than half the distance 2t between strands, so along the
 * straight path from the result no two strands meet: the knot is the same,
 * only the road differs. */
#define TRY_AMPLITUDE 0.9
static int other_road(const tighten_opts *o, tr_curve *c, tr_error *err)
{
    if (c->ncst > 0)
        return tr_fail(err, TR_EINVAL, "--tries: %s has constraints; a clasp's ends on their planes leave it one road",
                       o->in);
    tr_thickness t0, t1;
    int rc = tr_thickness_measure(c, NULL, &t0, NULL, err);
    if (rc)
        return rc;
    tr_curve moved = {0};
    /* a coarse polygon bends at its vertices under the displacement: the
     * amplitude is halved until the thickness keeps half its value, so
     * that scaling back does not stretch the edges past what the engine
     * takes (a 72-gon trefoil lost 4.8 times its thickness at 0.9) */
    double amp = TRY_AMPLITUDE;
    for (int attempt = 0; attempt < 6; attempt++, amp *= 0.5) {
        tr_curve_free(&moved);
        uint64_t seed = (uint64_t)o->seed * 1000003u + (uint64_t)o->try_index;
        if ((rc = tr_curve_copy(&moved, c, err)) || (rc = tr_curve_perturb(&moved, amp * t0.thickness, seed, err)) ||
            (rc = tr_thickness_measure(&moved, NULL, &t1, NULL, err))) {
            tr_curve_free(&moved);
            return rc;
        }
        if (t1.thickness >= 0.5 * t0.thickness && isfinite(t1.thickness))
            break;
    }
    if (!(t1.thickness > 0 && isfinite(t1.thickness))) {
        tr_curve_free(&moved);
        return tr_fail(err, TR_EGEOMETRY, "--tries: road %d's start has no thickness", o->try_index + 1);
    }
    scale_curve(&moved, t0.thickness / t1.thickness);
    tr_curve_free(c);
    *c = moved;
    return TR_OK;
}

/* --tries on a route of levels (--refine-to above the coarse count): the
 * local minimum a knot ends in is chosen on its coarse level, by the road
 * the first-order steps take there, and a kick smaller than the rope's
 * radius (other_road) does not leave it (5_2 from KnotPlot: four kicked roads
 * all ended at 50.4078, the TightKnot table has 49.484). Another coarse count
 * is another road from the same start: 4_1 from --n 90 ends at 45.13, from
 * 100, 110 and 128 near 42.2; 5_2 from 100 reaches 49.482. So road t >= 1
 * starts afresh from IN at the coarse count base * ROADS[t - 1].factor,
 * base being --n or else a quarter of the finest count (at least 64), some
 * roads from the start inflated by ROAD_INFLATE: a looser start has room to
 * slide before its strands meet, and takes another road (5_2 at --n 100:
 * 50.4077 from thickness 1, 49.4822 from KnotPlot's own 1.48). The roads
 * listed first are those that found the table's minimum where others did
 * not: 5_2 (1, inflated), 7_4 (1: 64.82 at 114 vertices, the others 64.88 to
 * 65.56), 6_2 (1.5 and 0.6: 57.22 and 57.23, the others 57.6 to 58.3); past
 * the list the factors repeat, 5 % larger each round. */
static const struct {
    double factor;
    int inflated;
} ROADS[] = {{1.0, 1},  {1.0, 0},  {1.5, 0},  {0.6, 0},  {1.25, 0}, {0.8, 1},  {0.8, 0},
             {0.67, 0}, {1.12, 0}, {0.9, 0},  {1.75, 0}, {1.37, 0}, {1.25, 1}, {1.5, 1}};
#define ROAD_COUNT ((int)(sizeof ROADS / sizeof ROADS[0]))
#define ROAD_INFLATE 1.5
/* Scouting: the local minimum is chosen on the coarse level, and a coarse
 * level costs a few seconds where the route to the finest count costs
 * minutes, so with --tries on a route of levels every road stops at its
 * coarse level, in this share of the time, and only the shortest of them is
 * refined. Measured on the KnotPlot starts
 * (bench/notes/2026-11-25-batch-8-crossings-scouts.md): 6_2 at N =
 * 407, ten scouts in 101 s, the shortest (152 vertices, 57.22 where the
 * others ended at 57.6 to 58.3) refined in 104 s to 57.0440, against 57.8283
 * for three full roads in 200 s; 7_4 at 459: 64.2908 against 65.1461. */
#define SCOUT_SHARE 0.5

static int multi_level(const tighten_opts *o) { return o->refine_to > 0 && !o->resume && o->in; }

static long road_coarse_n(const tighten_opts *o, int t)
{
    long base = o->n > 0 ? o->n : (o->refine_to / 4 > 64 ? o->refine_to / 4 : 64);
    double f = ROADS[(t - 1) % ROAD_COUNT].factor * (1.0 + 0.05 * (double)((t - 1) / ROAD_COUNT));
    long n = lround((double)base * f);
    if (n >= o->refine_to)
        n = o->refine_to / 2;
    return n < 16 ? 16 : n;
}

/* Whether every component of c has the --refine-to count (0: no such count). */
static int at_refine_n(const tighten_opts *o, const tr_curve *c)
{
    if (o->refine_to <= 0)
        return 0;
    for (int k = 0; k < c->ncomp; k++)
        if ((long)tr_comp_nv(c, k) != o->refine_to)
            return 0;
    return 1;
}

/* A scout the engine gave more vertices than --refine-to asks for in some
 * component (a short knot at small N: the inflated roads add vertices),
 * resampled to that N into *out instead of refused, and at thickness 1
 * again (fewer vertices cut the tight polygon's corners; a constrained rope
 * as it is). Returns 1 with *out filled; 0 when no component is past N, or
 * (said on stderr) when it cannot be resampled: the scout is refined as it
 * is. */
static int scout_at_refine_n(const tighten_opts *o, const tr_curve *scout, tr_curve *out)
{
    int finer = 0;
    size_t *per = malloc((size_t)scout->ncomp * sizeof *per);
    for (int k = 0; per && k < scout->ncomp; k++) {
        per[k] = tr_comp_nv(scout, k);
        if ((long)per[k] > o->refine_to) {
            per[k] = (size_t)o->refine_to;
            finer = 1;
        }
    }
    tr_error err;
    tr_thickness th;
    int rc = finer ? tr_resample(scout, per, out, &err) : TR_OK;
    free(per);
    if (rc != TR_OK)
        fprintf(stderr, "tightrope tighten: warning: the scout could not be resampled to N %ld: %s\n", o->refine_to,
                err.msg);
    if (!finer || rc != TR_OK)
        return 0;
    if (out->ncst == 0 && tr_thickness_measure(out, NULL, &th, NULL, &err) == TR_OK && th.thickness > 0 &&
        isfinite(th.thickness))
        scale_curve(out, 1.0 / th.thickness);
    return 1;
}

static double road_inflate(int t) { return ROADS[(t - 1) % ROAD_COUNT].inflated ? ROAD_INFLATE : 1.0; }

/* Resamples c along a spline so that no component's edges are INFLATED_EDGE
 * or longer, with as few vertices as that takes (none added where they are
 * shorter already). */
#define INFLATED_EDGE 0.97
static int grow_count(tr_curve *c, double edge, tr_error *err)
{
    size_t *per = malloc((size_t)c->ncomp * sizeof *per);
    if (!per)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    int grow = 0;
    for (int k = 0; k < c->ncomp; k++) {
        size_t nv = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
        double len = tr_comp_length(c, k);
        per[k] = nv;
        if (len / (double)ne >= edge) {
            per[k] = (size_t)ceil(len / edge) + (nv - ne) + 1;
            grow = 1;
        }
    }
    tr_curve r;
    int rc = grow ? tr_resample_smooth(c, per, &r, err) : TR_OK;
    free(per);
    if (grow && rc == TR_OK) {
        tr_curve_free(c);
        *c = r;
    }
    return rc;
}

/* --shuffles: another kind of road, for knots whose every coarse road
 * above ends in the same local minimum. Smooth starts at other counts, kicks
 * under the rope's radius and random walks of the rope inflated 1.3 and 2
 * times at fixed thickness all left 8_4 at 76.98-77.7 (the TightKnot table:
 * 72.03): the start's conformation, not its discretisation, picks the
 * basin. Ours had writhe 1.95 where the table's has 1.62 (in absolute value;
 * ACN 15.4 against 14.6), so the way out goes through other conformations.
 * A shuffled road makes one: the start, resampled along a spline to
 * SHUFFLE_N vertices per component, is inflated (4 times in the first
 * recipe below: the rope is then thin against the knot's size) and walked by `moves`
 * crankshaft moves that keep its thickness at least 1 and the knot type
 * (engine/shuffle.h), which loses the start's shape; then
 * `anneal` more moves, each kept only if the thickness stays at least
 * `ratchet` times the largest reached (a ratchet: the walk compacts the
 * knot again, to ropelength about 110-120 for 8_4, where the engine takes
 * over in seconds). The same --seed and road number, the same start.
 * Measured (bench/notes/2026-11-27-shuffled-roads.md): 8_4 from KnotPlot, four such
 * starts (made by hand, seeds 1-4) tightened at --n 128 for 25 s: 71.67
 * (N 280), 77.13, 77.02, 76.90; the first refined to N = 514: 71.5865,
 * writhe 1.635. --scale --refine-to N --time-limit 240 --tries 10
 * --shuffles 5: 8_4 71.5869 (table 72.0301), 8_11 72.9185 (73.5029), and
 * 7_1, 7_6, 8_7, 8_21 below the table, all from shuffled roads, where every
 * road of before ended above; 8_1, 8_5, 8_8, 8_12, 8_13, 8_17 stayed above
 * (8_12 and 8_17 went below with --shuffles 9 --seed 2, 8_5 and 8_13 with
 * --shuffles 9 --seed 3, 8_8 with --tries 12 --shuffles 11 --seed 5; 8_1
 * with none tried). */
#define SHUFFLE_N 96
typedef struct shuffle_recipe {
    double inflate;
    long moves, anneal;
    double ratchet;
} shuffle_recipe;
/* The shuffled roads take these in turn. The second walks a thinner rope
 * (inflated 6 times) and compacts it twice as long with a tighter ratchet
 * (0.995): a more compact start, which reached other basins. Measured
 * (bench/notes/2026-11-27-shuffle-recipes.md): 8_1 and 8_2 ended above the table
 * from every road of the first recipe over five seeds (+0.045 % and
 * +0.164 %, the same conformations each time); with the second,
 * --tries 8 --shuffles 7 --seed 11, 8_1 71.0372 (road 3) and 8_2 71.4304
 * (road 8), both below the table's 71.0484 and 71.4327. Recipes with
 * SHUFFLE_N 128 or 64 were not kept: the crumpled polygon's edges could not
 * be made equal for the engine (the road skipped). */
static const shuffle_recipe SHUFFLE_RECIPES[] = {
    {4.0, 20000, 100000, 0.98},
    {6.0, 20000, 200000, 0.995},
};
/* Ropelength does not see where a knot is, but the engine's doubles do: a
 * trefoil moved to 1e6 tightened to 32.889 (KKT residual 0.45) where at
 * the origin it reaches 32.837 (1e-4), its differences of coordinates
 * losing six digits. So a start whose box does not hold the origin along an
 * axis is moved by the middle of its extent there (as the oracle measures,
 * curve.h), and the tight knot is written about the origin (said in its
 * comments). A box that holds the origin is left bit for bit as it is; a
 * constrained rope (a clasp) stays on its planes. */
static void start_shift(tighten_opts *o)
{
    memset(o->shift, 0, sizeof o->shift);
    tr_curve c;
    tr_error err;
    /* a pipe (cat k.vect | tighten /dev/stdin) is read once, by read_start */
    struct stat st;
    if (o->resume || !o->in || stat(o->in, &st) != 0 || !S_ISREG(st.st_mode) ||
        tr_curve_read(o->in, TR_FORMAT_AUTO, &c, &err))
        return;
    if (c.ncst == 0 && c.nv > 0)
        for (int a = 0; a < 3; a++) {
            double lo = c.x[a], hi = c.x[a];
            for (size_t i = 1; i < c.nv; i++) {
                lo = fmin(lo, c.x[3 * i + (size_t)a]);
                hi = fmax(hi, c.x[3 * i + (size_t)a]);
            }
            if (lo > 0 || hi < 0)
                o->shift[a] = 0.5 * lo + 0.5 * hi;
        }
    tr_curve_free(&c);
}

static void shift_curve(tr_curve *c, const double shift[3])
{
    for (size_t i = 0; i < c->nv; i++)
        for (int a = 0; a < 3; a++)
            c->x[3 * i + (size_t)a] -= shift[a];
}

/* What the bound keeps back of --time-limit T for the run to end in: the
 * step, settle pass or solver iteration under way when the bound passes
 * (each looks at the clock only between its own iterations: up to a second
 * at N = 9600 on a loaded machine), the certificate and the write. Beside
 * two busy loops, `--refine-to 9600 --time-limit 40` ended 0.1 to 2 s past
 * its limit without it. */
static double finish_reserve(double t) { return fmin(0.05 * t, 2.0); }

/* The command's hard bound: its --time-limit and the stop flag. */
static tr_deadline command_bound(const tighten_opts *o)
{
    return (tr_deadline){.at = o->bound_at, .stop = tr_cli_interrupt_flag()};
}

static int shuffle_start(const tighten_opts *o, tr_curve *c, tr_error *err)
{
    if (c->ncst > 0)
        return tr_fail(err, TR_EINVAL, "--shuffles: %s has constraints; a clasp's ends on their planes cannot be "
                                       "shuffled", o->in);
    size_t *per = malloc((size_t)c->ncomp * sizeof *per);
    if (!per)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    for (int k = 0; k < c->ncomp; k++)
        per[k] = SHUFFLE_N;
    tr_curve r;
    int rc = tr_resample_smooth(c, per, &r, err);
    free(per);
    if (rc)
        return rc;
    tr_thickness t;
    uint64_t seed = (uint64_t)o->seed * 1000003u + (uint64_t)o->try_index;
    if ((rc = tr_thickness_measure(&r, NULL, &t, NULL, err)))
        goto out;
    if (!(t.thickness > 0 && isfinite(t.thickness))) {
        rc = tr_fail(err, TR_EGEOMETRY, "--shuffles: %s resampled to %d vertices has thickness %g", o->in, SHUFFLE_N,
                     t.thickness);
        goto out;
    }
    const size_t nrecipes = sizeof SHUFFLE_RECIPES / sizeof *SHUFFLE_RECIPES;
    const shuffle_recipe *sr = &SHUFFLE_RECIPES[(size_t)o->shuffle_index % nrecipes];
    scale_curve(&r, sr->inflate / t.thickness);
    tr_deadline bound = command_bound(o);
    if ((rc = tr_curve_shuffle(&r, sr->moves, 1.0, 0.0, seed, &bound, NULL, err)) ||
        (rc = tr_curve_shuffle(&r, sr->anneal, 1.0, sr->ratchet, seed + 7, &bound, NULL, err)) ||
        (rc = tr_thickness_measure(&r, NULL, &t, NULL, err)))
        goto out;
    scale_curve(&r, 1.0 / t.thickness);
out:
    if (rc) {
        tr_curve_free(&r);
        return rc;
    }
    tr_curve_free(c);
    *c = r;
    return TR_OK;
}

/* Reads the start curve IN into c, resampled with --n and scaled with
 * --scale, and checks that it can be tightened: its open ends are held and
 * its thickness is at a scale the engine can work in. */
static int read_start(const tighten_opts *o, tr_curve *c, tr_error *err)
{
    const char *in = o->in;
    int rc;
    if (o->road_from) {
        /* a later road of --tries: the shortest result so far, moved off
         * its local minimum (it is at thickness 1 and at the run's N) */
        if ((rc = tr_curve_copy(c, o->road_from, err)) || (!o->road_as_is && (rc = other_road(o, c, err))))
            tr_curve_free(c);
        return rc;
    }
    rc = tr_curve_read(in, TR_FORMAT_AUTO, c, err);
    if (rc != TR_OK)
        return rc;
    if (c->ncst == 0)
        shift_curve(c, o->shift);
    /* the start's measures are within the command's bound: at 10^7
     * vertices (--n) each is tens of seconds */
    tr_deadline bound = command_bound(o);
    tr_thickness_opts bounded = {.bound = &bound};
    if (o->shuffled && (rc = shuffle_start(o, c, err))) {
        tr_curve_free(c);
        return rc;
    }
    if (o->n > 0) {
        size_t *per = malloc((size_t)c->ncomp * sizeof *per);
        tr_curve r;
        if (!per) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory");
        } else {
            /* Adding vertices on the old straight edges would keep the
             * polygon's corners: MinRad falls like 1/N and a smooth
             * start is refused as bent too tight. Along a spline
             * through the vertices the start stays the smooth curve. */
            int adds = 0;
            for (int k = 0; k < c->ncomp; k++) {
                per[k] = (size_t)o->n;
                adds |= per[k] > c->start[k + 1] - c->start[k];
            }
            tr_thickness before, after;
            rc = adds ? tr_resample_smooth(c, per, &r, err) : tr_resample(c, per, &r, err);
            free(per);
            int past = rc == TR_OK ? tr_deadline_passed(&bound) : 0;
            if (past) {
                tr_curve_free(&r);
                rc = tr_fail(err, TR_EINTERRUPTED, "%s resampled to %ld vertices: %s", in, o->n,
                             past == 2 ? "stopped by a signal" : "the time limit came");
            }
            /* A spline through a tight polygon bulges out between its
             * vertices, so strands that touched come closer than before
             * (1.99835 for the 2 x 40 Hopf link refined to 80): the added
             * vertices are scaled back to the start's strut distance,
             * which ropelength does not see. Constraint planes are fixed,
             * so a constrained rope is left as it is. */
            if (rc == TR_OK && adds && c->ncst == 0 &&
                !tr_thickness_measure(c, &bounded, &before, NULL, err) &&
                !tr_thickness_measure(&r, &bounded, &after, NULL, err) &&
                isfinite(before.dcsd) && after.dcsd < before.dcsd && after.dcsd > 0.5 * before.dcsd)
                scale_curve(&r, before.dcsd / after.dcsd);
            if (rc == TR_OK) {
                tr_curve_free(c);
                *c = r;
            }
        }
    }
    /* Ropelength is scale free: --scale takes a start at another scale
     * (a tight knot from another code at thickness 0.99995, a file in
     * its own units) to the rope's radius 1. Constraint planes and points
     * are scaled with it about the origin (scale_curve), so a clasp's ends
     * stay on their planes (KnotPlot's simple_clasp is at thickness 0.5). */
    /* The oracle looks at the start first: a curve through itself has
     * no thickness at all, and one at a scale like 1e+-300 would lose
     * the engine's squared distances to under- or overflow (the oracle
     * measures it in a rescaled frame, curve.h). */
    /* An open rope with a free end shortens by pulling that end
     * through: it comes out untied. Its ends must be held. */
    for (int k = 0; rc == TR_OK && k < c->ncomp; k++) {
        size_t ends[2] = {c->start[k], c->start[k + 1] - 1};
        for (int q = 0; rc == TR_OK && !c->closed[k] && q < 2; q++)
            if (!c->vcst || c->vcst[ends[q]] < 0)
                rc = tr_fail(err, TR_EGEOMETRY,
                             "%s: component %d is open and its %s end (vertex %zu) is free: tightening would "
                             "pull it through and untie the rope; hold both ends with a constraint (a "
                             "'# Constraint 1 Plane 0 0 1 6' comment and '# Cst: 1' after the end vertex, "
                             "as tightrope make clasp writes)",
                             in, k, q ? "last" : "first", ends[q] - c->start[k]);
    }
    tr_thickness t0;
    if (rc == TR_OK && (rc = tr_thickness_measure(c, &bounded, &t0, NULL, err)))
        tr_fail_wrap(err, rc, "%s", in);
    if (rc == TR_OK && !o->scale && tr_curve_scale_exponent(c))
        rc = tr_fail(err, TR_EGEOMETRY,
                     "%s has thickness %.3g, too far from 1 to tighten in its own units (squared "
                     "distances would %s); --scale scales a start to thickness 1",
                     in, t0.thickness, tr_curve_scale_exponent(c) > 0 ? "overflow" : "underflow");
    /* a shuffled start is ours, at thickness 1 before --n resampled it: it
     * is brought back to thickness 1 as --scale would */
    if (rc == TR_OK && (o->scale || o->shuffled)) {
        if (!(t0.thickness > 0 && isfinite(t0.thickness)))
            rc = tr_fail(err, TR_EGEOMETRY, "--scale: %s has thickness %g; no scale makes it a rope", in,
                         t0.thickness);
        else if (!isfinite(1.0 / t0.thickness))
            rc = tr_fail(err, TR_EGEOMETRY, "--scale: %s has thickness %g, too thin for the factor 1/%g to be a "
                         "double; scale the file up first", in, t0.thickness, t0.thickness);
        if (rc == TR_OK)
            scale_curve(c, 1.0 / t0.thickness);
        /* also after --n: a count too coarse for thickness 1 (a road of
         * --tries at a count below the start's length) is raised */
        if (rc == TR_OK)
            rc = densify_coarse(o, c, err);
    }
    /* an inflated road's edges grow with it: the count grows just enough
     * to keep them below INFLATED_EDGE (a coarse road is what it is for:
     * 5_2 from 100 vertices at KnotPlot's thickness 1.48, edges 0.97,
     * reaches 49.482; densified to edges of 0.5 it ends at 50.4079) */
    if (rc == TR_OK && o->inflate != 1.0) {
        scale_curve(c, o->inflate);
        rc = grow_count(c, INFLATED_EDGE, err);
    }
    if (rc != TR_OK)
        tr_curve_free(c);
    return rc;
}

/* SIGINT/SIGTERM/SIGHUP raise the interrupt flag (cli_interrupt.h): the
 * run (and a solver run at the engine's start) stops at its next step and
 * writes what it has. A closed terminal or SSH session (SIGHUP) must not
 * cost the run, and its last messages then go to a closed pipe: SIGPIPE is
 * ignored so that the write fails (and is let go) instead of killing the
 * process before the output is written. */
static void catch_signals(void)
{
    tr_cli_catch_interrupts();
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_IGN;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGPIPE, &sa, NULL);
}

/* The route for a loose start given without route flags (no --n, no
 * --refine-to): first-order steps need ~N^2 of them, so a loose start of
 * N >= AUTO_ROUTE_MIN_N vertices per component is tightened from N / 4 and
 * refined back to N, as `--n N/4 --refine-to N` would (the N = 400 trefoil
 * from `make torus 2 3`: 32.748648 in 5 s that way, 40.59 at N = 400
 * directly). Loose: fewer struts within 1e-3 of the shortest than a tenth
 * of the vertices (a tight knot has more than one per vertex). Closed,
 * unconstrained curves, or clasps (below), with the same N per component
 * only; --n N keeps the
 * start's N. A start that cannot be read is left to read_start to report. */
#define AUTO_ROUTE_MIN_N 200
/* A loose clasp (open ropes whose ends are held) of more than
 * CLASP_COARSE_N vertices per rope starts from CLASP_COARSE_N instead: the
 * first-order steps and the polish tighten a clasp there (13 s at 2 x 100)
 * but not at 2 x 1000, and every refined level goes to the second-order
 * solver (level_loop.c, is_solver_level). A clasp cannot be scaled, so it
 * is also loose at thickness above 1 (`make clasp`: 1.5, with each arch's
 * whole semicircle at the shortest distance from the other's tip, so the
 * strut count says nothing). */
#define CLASP_COARSE_N 100
static void choose_route(tighten_opts *o)
{
    if (o->resume || o->n > 0 || o->refine_to > 0 || !o->in)
        return;
    tr_curve c;
    tr_error err;
    if (tr_curve_read(o->in, TR_FORMAT_AUTO, &c, &err))
        return;
    size_t nper = tr_comp_nv(&c, 0);
    int simple = c.ncst == 0, clasp = c.ncst > 0;
    for (int k = 0; k < c.ncomp; k++) {
        simple = simple && c.closed[k] && tr_comp_nv(&c, k) == nper;
        clasp = clasp && !c.closed[k] && tr_comp_nv(&c, k) == nper;
    }
    tr_thickness th;
    tr_strut_list sl = {0};
    tr_thickness_opts to = {.strut_rel_tol = 1e-3};
    if ((simple || (clasp && nper > CLASP_COARSE_N)) && nper >= AUTO_ROUTE_MIN_N &&
        !tr_thickness_measure(&c, &to, &th, &sl, &err) && th.thickness > 0 &&
        ((double)sl.n < 0.1 * (double)c.nv || (clasp && th.thickness > 1.0 + 1e-3))) {
        o->n = clasp ? CLASP_COARSE_N : (long)(nper / 4 > 64 ? nper / 4 : 64);
        o->refine_to = (long)nper;
        if (!o->quiet)
            fprintf(stderr,
                    "tightrope tighten: %s is loose (%zu struts within 1e-3 of the shortest, %zu vertices): "
                    "tightening from %ld vertices and refining to %zu (--n %zu keeps them all)\n",
                    o->in, sl.n, c.nv, o->n, nper, nper);
    }
    tr_strut_list_free(&sl);
    tr_curve_free(&c);
}

/* --resume: what the run was asked for and the command line does not say
 * again is taken from the checkpoint (tr_engine_goals), and said on
 * stderr. Returns -1 to go on, else the exit status (message printed). */
static int resume_goals(tighten_opts *o, double *elapsed)
{
    tr_engine_goals g;
    int found;
    tr_error err;
    if (tr_engine_checkpoint_goals(o->resume, &g, &found, elapsed, &err)) {
        fprintf(stderr, "tightrope tighten: %s\n", err.msg);
        return 2;
    }
    if (!found)
        return -1;
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
    if (line && line[0] && !o->quiet)
        fprintf(stderr, "tightrope tighten: resuming with the checkpoint's goals:%s\n", line);
    free(line);
    return -1;
}

/* Opens the engine on the start (IN or the checkpoint to resume) and
 * checks the outputs before the run. Returns -1 to go on with *e, else the
 * exit status, with the message printed. */
static int open_start(const tighten_opts *o, tr_engine **e)
{
    tr_error err;
    tr_engine_params prm;
    tr_engine_params_default(&prm);
    prm.polish = !o->no_polish;
    prm.newton = o->newton;
    prm.newton_tight = !o->no_newton;
    if (o->device_from >= 0)
        prm.device_min_n = (size_t)o->device_from;
    prm.bound = command_bound(o);
    prm.goals = (tr_engine_goals){.refine_to = o->refine_to > 0 ? o->refine_to : 0,
                                  .refine_given = o->refine_given,
                                  .target = o->target,
                                  .residual = o->residual_given ? o->residual : 0.0,
                                  .residual_given = o->residual_given,
                                  .steps = o->steps,
                                  .time_limit = o->time_limit};
    *e = NULL;
    int rc;
    if (o->resume) {
        rc = tr_engine_resume(e, o->resume, o->device, &prm, &err);
    } else {
        tr_curve c;
        rc = read_start(o, &c, &err);
        if (rc == TR_OK) {
            /* the start is the finest level: a tight one goes to the
             * second-order solver first (engine.h, newton_first) */
            prm.newton_first = !o->no_newton && (o->refine_to <= 0 || c.nv / (size_t)c.ncomp >= (size_t)o->refine_to);
            prm.newton_first_limit = o->time_limit;
            prm.newton_first_stop = tr_cli_interrupt_flag();
            prm.newton_first_checkpoint = o->ckpt;
            prm.newton_first_checkpoint_every = o->ckpt ? o->ckpt_every : 0;
            catch_signals();
            rc = tr_engine_create(e, &c, o->device, &prm, &err);
            tr_curve_free(&c);
        }
    }
    /* a later road that the bound stopped before its start was settled
     * leaves the roads before it to be written: the loop says so */
    if (rc == TR_EINTERRUPTED && o->try_index > 0)
        return 1;
    if (rc) {
        fprintf(stderr, "tightrope tighten: %s%s\n", err.msg,
                rc == TR_EINTERRUPTED ? "; nothing written" : "");
        /* cli.h: a curve or an option the user can fix is 2; a device that
         * fails (kernel build, OpenCL call), memory, or a run stopped by its
         * time limit or a signal before it had a settled curve is 1 */
        return rc == TR_EOPENCL || rc == TR_ENOMEM || rc == TR_EUNSUPPORTED || rc == TR_EINTERRUPTED ? 1 : 2;
    }
    /* A run of hours must not end in "cannot write": the output's format
     * and both paths are checked before it starts. */
    rc = check_outputs(*e, (size_t)o->refine_to, o->out, o->ckpt, &err);
    if (rc) {
        fprintf(stderr, "tightrope tighten: %s\n", err.msg);
        tr_engine_destroy(*e);
        *e = NULL;
        return rc == TR_ENOMEM ? 1 : 2;
    }
    if (tr_engine_warning(*e)[0])
        fprintf(stderr, "tightrope tighten: warning: %s\n", tr_engine_warning(*e));
    if (o->resume) {
        /* both limits count the runs before the checkpoint: say so when
         * they leave this run nothing to do */
        tr_engine_progress p0;
        tr_engine_get_progress(*e, &p0);
        if (o->steps > 0 && p0.steps >= o->steps)
            fprintf(stderr, "tightrope tighten: warning: the checkpoint has %ld steps already; --steps %ld "
                            "counts them, so no step is taken\n", p0.steps, o->steps);
        if (o->time_limit > 0 && p0.elapsed >= o->time_limit)
            fprintf(stderr, "tightrope tighten: warning: the checkpoint has used %.1f s already; "
                            "--time-limit %g counts them, so no step is taken\n", p0.elapsed, o->time_limit);
    }
    return -1;
}

/* Runs the engine to its limits, stopping at SIGINT/SIGTERM. Returns -1 to
 * go on with *why, else the exit status, with the message printed. */
static int run(const tighten_opts *o, tr_engine *e, tr_stop_reason *why)
{
    catch_signals();
    progress_ctx pctx = {.tty = !o->quiet && isatty(2), .printed = 0};
    tr_engine_limits lim = {.refine_to = (size_t)o->refine_to,
                            .residual = o->residual,
                            .target = o->target,
                            .max_steps = o->steps,
                            .time_limit = o->time_limit,
                            .coarse_residual = 1e-3,
                            .checkpoint_every = o->ckpt ? o->ckpt_every : 0,
                            .checkpoint_path = o->ckpt,
                            .stop = tr_cli_interrupt_flag(),
                            .progress_every = 0.25,
                            .progress = on_progress,
                            .user = &pctx};
    tr_error err;
    int rc = tr_engine_run(e, &lim, why, &err);
    if (pctx.printed)
        fprintf(stderr, "\n");
    if (rc) {
        fprintf(stderr, "tightrope tighten: %s\n", err.msg);
        /* exit codes as cli.h: a checkpoint that cannot be written or a bad
         * option is the user's to fix (2); a refused step, a device or
         * memory failure is a run that did not get there (1) */
        return rc == TR_EIO || rc == TR_EINVAL || rc == TR_EPARSE ? 2 : 1;
    }
    return -1;
}

/* What the run came to: the engine's progress, the written curve and its
 * certificate. */
typedef struct tighten_result {
    tr_stop_reason why;
    tr_engine_progress p;
    tr_curve fin;
    tr_thickness th;
    int rescaled;  /* fin was scaled to thickness 1 */
    tr_kkt kr;
    int certified; /* kr holds the KKT certificate of fin */
    int ckpt_failures; /* checkpoints the run could not write */
    const char *ckpt_why;
    int tries, best_try; /* --tries: roads run, the one written (0-based) */
} tighten_result;

/* Takes the engine's curve into r->fin, rescaled to thickness 1 where no
 * vertex is constrained, and measures and (as --kkt/--no-kkt say)
 * certifies it. */
static int certify(const tighten_opts *o, tr_engine *e, tighten_result *r, tr_error *err)
{
    tr_engine_get_progress(e, &r->p);
    r->ckpt_failures = tr_engine_checkpoint_failures(e, &r->ckpt_why);
    /* no step ever taken (a --target the start already meets): the engine
     * has no residual to report, and 0 would read as converged */
    if (r->p.steps == 0)
        r->p.residual = NAN;
    int rc = tr_engine_get_curve(e, &r->fin, err);
    if (rc == TR_OK)
        rc = tr_thickness_measure(&r->fin, NULL, &r->th, NULL, err);
    if (rc == TR_OK && r->fin.ncst == 0 && isfinite(r->th.thickness) && r->th.thickness > 0) {
        /* certificate at thickness exactly 1: ropelength = length */
        scale_curve(&r->fin, 1.0 / r->th.thickness);
        rc = tr_thickness_measure(&r->fin, NULL, &r->th, NULL, err);
        r->rescaled = 1;
    }
    /* the certificate of what is written, computed on it alone */
    if (rc == TR_OK && r->why != TR_STOP_SIGNAL &&
        (o->kkt == 1 || (o->kkt < 0 && r->fin.nv <= KKT_AUTO_MAX_N))) {
        rc = tr_kkt_certify(&r->fin, NULL, &r->kr, err);
        r->certified = rc == TR_OK;
    }
    return rc;
}

/* Writes r->fin to OUT with its certificate and the command line in
 * comments. */
static int write_output(const tighten_opts *o, tr_engine *e, const tighten_result *r, int argc, char **argv,
                        tr_error *err)
{
    const tr_engine_progress *p = &r->p;
    const tr_thickness *th = &r->th;
    const tr_kkt *kr = &r->kr;
    tr_text cm = {0};
    tr_text_printf(&cm, "tightened by tightrope %s on %s\n", TIGHTROPE_VERSION, tr_engine_device(e));
    tr_text_printf(&cm, "command:");
    for (int i = 0; i < argc; i++)
        tr_text_printf(&cm, " %s", argv[i]);
    tr_text_printf(&cm, "\nN %zu\nlength %.17g\nMinRad %.17g\ndcsd %.17g\nthickness %.17g\nropelength %.17g\n",
            th->vertices, th->length, th->minrad, th->dcsd, th->thickness, th->ropelength);
    if (isfinite(p->residual))
        tr_text_printf(&cm, "residual %.6g\n", p->residual);
    else
        tr_text_printf(&cm, "residual not computed (no step taken)\n");
    tr_text_printf(&cm, "steps %ld\nstop %s\n%s", p->steps, tr_stop_reason_name(r->why),
            r->rescaled ? "rescaled to thickness 1\n" : "");
    if (r->certified)
        tr_text_printf(&cm, "kkt_residual %.6e (band %g: %zu/%zu struts, %zu/%zu MinRad rows hold%s)\n", kr->residual,
                       TR_KKT_DEFAULT_BAND, kr->strut_active, kr->strut_rows, kr->minrad_active, kr->minrad_rows,
                       kr->converged ? "" : "; an upper bound");
    else
        tr_text_printf(&cm, "kkt_residual not computed (%s)\n",
                       r->why == TR_STOP_SIGNAL ? "interrupted" : o->kkt == 0 ? "--no-kkt" : "N above the default limit; --kkt");
    if (p->polished && !p->newton_ran)
        tr_text_printf(&cm, "polish %s: ropelength %.9f -> %.9f in %.2f s%s%s%s\n", p->polished > 0 ? "accepted" : "rejected",
                p->polish_before, p->polish_after, p->polish_seconds, p->polish_why ? " (" : "",
                p->polish_why ? p->polish_why : "", p->polish_why ? ")" : "");
    if (p->newton_ran)
        tr_text_printf(&cm, "newton %s: ropelength %.9f -> %.9f in %.2f s, %d steps\n",
                       p->newton_ran > 0 ? "accepted" : "rejected", p->newton_before, p->newton_after,
                       p->newton_seconds, p->newton_iters);
    if (r->tries > 1)
        tr_text_printf(&cm, "tries %d, seed %ld: the shortest was road %d\n", r->tries, o->seed, r->best_try + 1);
    if (o->shift[0] != 0 || o->shift[1] != 0 || o->shift[2] != 0)
        tr_text_printf(&cm, "centred: the start was moved by (%.17g, %.17g, %.17g) to be tightened about the "
                            "origin\n", 0.0 - o->shift[0], 0.0 - o->shift[1], 0.0 - o->shift[2]);
    char *comments = tr_text_take(&cm, NULL);
    if (!comments)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    int rc = tr_curve_write(o->out, TR_FORMAT_AUTO, &r->fin, comments, err);
    free(comments);
    return rc;
}

/* Prints the summary of the run on stdout: JSON with --json, else lines. */
static void print_summary(const tighten_opts *o, tr_engine *e, const tighten_result *r)
{
    const tr_engine_progress *p = &r->p;
    const tr_thickness *th = &r->th;
    const tr_kkt *kr = &r->kr;
    if (o->json) {
        printf("{\n");
        json_str("output", o->out, 1);
        json_str("device", tr_engine_device(e), 1);
        json_str("stop", tr_stop_reason_name(r->why), 1);
        printf("  \"N\": %zu,\n  \"steps\": %ld,\n  \"rejected\": %ld,\n", th->vertices, p->steps, p->rejected);
        json_num("length", th->length, 1);
        json_num("minrad", th->minrad, 1);
        json_num("dcsd", th->dcsd, 1);
        json_num("thickness", th->thickness, 1);
        json_num("ropelength", th->ropelength, 1);
        json_num("residual", p->residual, 1);
        json_num("kkt_residual", r->certified ? kr->residual : NAN, 1);
        if (r->certified)
            printf("  \"kkt_converged\": %s,\n", kr->converged ? "true" : "false");
        json_num("elapsed_s", p->elapsed, 1);
        json_num("steps_per_s", p->steps_per_s, 0);
        printf("}\n");
    } else {
        printf("%s: N %zu  ropelength %.6f  (length %.6f, thickness %.9f, MinRad %.9f, dcsd %.9f)\n", o->out,
               th->vertices, th->ropelength, th->length, th->thickness, th->minrad, th->dcsd);
        char res[32] = "not computed";
        if (isfinite(p->residual))
            snprintf(res, sizeof res, "%.2e", p->residual);
        printf("  %ld steps in %.1f s, residual %s, stopped: %s\n", p->steps, p->elapsed, res,
               tr_stop_reason_name(r->why));
        if (r->certified)
            printf("  KKT residual %.2e (%zu/%zu struts and %zu/%zu MinRad rows hold the tension%s)\n", kr->residual,
                   kr->strut_active, kr->strut_rows, kr->minrad_active, kr->minrad_rows,
                   kr->converged ? "" : "; an upper bound");
        if (p->polished && !p->newton_ran)
            printf("  polish %s: ropelength %.6f -> %.6f in %.1f s%s%s%s\n", p->polished > 0 ? "accepted" : "rejected",
                   p->polish_before, p->polish_after, p->polish_seconds, p->polish_why ? " (" : "",
                   p->polish_why ? p->polish_why : "", p->polish_why ? ")" : "");
        if (p->newton_ran)
            printf("  newton %s: ropelength %.9f -> %.9f in %.1f s, %d steps\n",
                   p->newton_ran > 0 ? "accepted" : "rejected", p->newton_before, p->newton_after, p->newton_seconds,
                   p->newton_iters);
    }
}

/* The exit status of a finished run, with its notes on stderr: 1 when it
 * was interrupted or did not reach a requested ropelength or residual. */
static int final_status(const tighten_opts *o, const tighten_result *r)
{
    if (r->ckpt_failures > 0)
        fprintf(stderr, "tightrope tighten: warning: %d checkpoint%s could not be written (the run went on): %s\n",
                r->ckpt_failures, r->ckpt_failures > 1 ? "s" : "", r->ckpt_why);
    if (r->why == TR_STOP_SIGNAL)
        fprintf(stderr, "tightrope tighten: interrupted; %s%s%swrote %s\n", o->ckpt ? "checkpoint " : "",
                o->ckpt ? o->ckpt : "", o->ckpt ? " and " : "", o->out);
    /* a requested ropelength or residual that was not reached is a run that
     * did not reach its goal: the best state is written, the status says so;
     * so is a --refine-to whose N the time did not reach */
    int refined = 1;
    for (int k = 0; k < r->fin.ncomp; k++)
        refined = refined && (long)tr_comp_nv(&r->fin, k) >= o->refine_to;
    if (o->refine_given && !refined && r->why != TR_STOP_SIGNAL) {
        fprintf(stderr, "tightrope tighten: stopped (%s) at N %zu before reaching the requested --refine-to %ld; "
                        "wrote %s\n", tr_stop_reason_name(r->why), r->fin.nv / (size_t)r->fin.ncomp, o->refine_to,
                o->out);
        return 1;
    }
    int goal = o->target > 0 || o->residual_given;
    /* --residual is met by the engine's own force balance or, once the run
     * has stopped for another reason (jammed, steps), by the certificate of
     * what was written, which is the stricter measure (kkt.h) */
    int reached = r->why == TR_STOP_TARGET || r->why == TR_STOP_RESIDUAL ||
                  (o->target <= 0 && o->residual_given && r->certified && r->kr.residual <= o->residual);
    if (goal && !reached && r->why != TR_STOP_SIGNAL)
        fprintf(stderr, "tightrope tighten: stopped (%s) before reaching the requested %s; wrote %s\n",
                tr_stop_reason_name(r->why), o->target > 0 ? "ropelength" : "residual", o->out);
    return r->why == TR_STOP_SIGNAL || (goal && !reached) ? 1 : 0;
}

/* The report batch reads: what print_summary prints, as numbers. */
static void fill_report(const tighten_opts *o, const tighten_result *r, tr_tighten_report *rep)
{
    rep->written = 1;
    rep->interrupted = r->why == TR_STOP_SIGNAL;
    rep->stop = tr_stop_reason_name(r->why);
    rep->n = r->th.vertices;
    rep->ropelength = r->th.ropelength;
    rep->thickness = r->th.thickness;
    rep->minrad = r->th.minrad;
    rep->dcsd = r->th.dcsd;
    rep->kkt_residual = r->certified ? r->kr.residual : NAN;
    rep->elapsed = r->p.elapsed;
    rep->steps = r->p.steps;
    rep->tries = r->tries > 0 ? r->tries : 1;
    /* a resumed run continues one road of a run whose seed it does not know */
    rep->seed = o->resume ? -1 : o->seed;
    rep->road = o->resume ? 0 : r->tries > 0 ? r->best_try + 1 : 1;
}

int tr_tighten_stop_requested(void) { return tr_cli_interrupted() != 0; }

int tr_cmd_tighten(int argc, char **argv) { return tr_tighten_command(argc, argv, NULL); }

int tr_tighten_check_args(int argc, char **argv)
{
    tighten_opts o;
    return parse_options(argc, argv, &o);
}

/* One road of the run: opens the start (perturbed for try_index > 0),
 * runs and certifies it. Returns -1 with *e and *r filled, else the exit
 * status (its message printed). */
static int one_road(const tighten_opts *o, tr_engine **e, tighten_result *r)
{
    int rc = open_start(o, e);
    if (rc >= 0)
        return rc;
    *r = (tighten_result){0};
    rc = run(o, *e, &r->why);
    if (rc >= 0) {
        tr_engine_destroy(*e);
        return rc;
    }
    tr_error err;
    if ((rc = certify(o, *e, r, &err))) {
        fprintf(stderr, "tightrope tighten: %s\n", err.msg);
        tr_curve_free(&r->fin);
        tr_engine_destroy(*e);
        return 2;
    }
    return -1;
}

int tr_tighten_command(int argc, char **argv, tr_tighten_report *rep)
{
    if (rep)
        *rep = (tr_tighten_report){.kkt_residual = NAN, .stop = ""};
    tighten_opts o;
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    double elapsed_before = 0.0; /* a resumed run's seconds before its checkpoint */
    if (o.resume && (rc = resume_goals(&o, &elapsed_before)) >= 0)
        return rc;
    choose_route(&o);
    start_shift(&o);
    /* the bound counts from here: reading, shuffling and settling the
     * start are the command's time too; a resumed run's limit counts the
     * time before its checkpoint (as the engine's steps do) */
    if (o.time_limit > 0)
        o.bound_at = tr_clock_seconds() + fmax(o.time_limit - elapsed_before - finish_reserve(o.time_limit), 0.0);
    /* --tries: the roads one after the other, each with an equal share of
     * the time left; of the certified ones the finest, then the shortest,
     * is kept. A road that fails after the first is skipped (said on
     * stderr); SIGINT ends the series. On a route of levels the roads are
     * scouts: each tightens its coarse level only, in SCOUT_SHARE of the
     * time, and the shortest of them alone is refined to --refine-to with
     * the rest (scouting). */
    tr_engine *e = NULL;
    tighten_result r = {0};
    int have = 0, scouting = o.tries > 1 && multi_level(&o);
    double t0 = tr_clock_seconds();
    const double budget = scouting ? SCOUT_SHARE * o.time_limit : o.time_limit; /* the scouts' */
    tr_deadline bound = command_bound(&o);
    /* once a road has a result, no road starts past the bound: each has at
     * least its share's floor, and a thousand roads of a second's floor
     * were once a minute past a three-second limit */
    for (long t = 0; t < o.tries + scouting && !(have && tr_deadline_passed(&bound)); t++) {
        tighten_opts ot = o;
        ot.try_index = (int)t;
        tr_curve scout_at_n = {0};
        int resampled = 0;
        int refining = scouting && t == o.tries;
        /* the last --shuffles roads (never the first: --shuffles < --tries) */
        int shuffled_road = !refining && t >= o.tries - o.shuffles;
        ot.shuffle_index = shuffled_road ? (int)(t - (o.tries - o.shuffles)) : 0;
        if (refining) {
            /* the shortest scout, refined as it is (read_start takes
             * road_from before --n and --scale) */
            ot.road_from = &r.fin;
            ot.road_as_is = 1;
            if ((resampled = scout_at_refine_n(&o, &r.fin, &scout_at_n)))
                ot.road_from = &scout_at_n;
        } else if (scouting) {
            ot.refine_to = 0;
            if (shuffled_road) {
                /* a shuffled road, at the first road's coarse count */
                ot.shuffled = 1;
                ot.n = road_coarse_n(&o, 1);
            } else if (t > 0) {
                ot.n = road_coarse_n(&o, (int)t);
                ot.inflate = road_inflate((int)t);
            }
        } else if (shuffled_road)
            ot.shuffled = 1;
        else
            ot.road_from = have ? &r.fin : NULL;
        /* a road that jams early leaves its time to the roads after it */
        if (o.time_limit > 0)
            ot.time_limit = refining ? fmax(o.time_limit - (tr_clock_seconds() - t0), 0.05 * o.time_limit)
                                     : fmax(budget - (tr_clock_seconds() - t0), 0.05 * budget) / (double)(o.tries - t);
        if (refining && !o.quiet)
            fprintf(stderr, "tightrope tighten: the shortest scout (road %d, N %zu) %s to %ld vertices\n",
                    r.best_try + 1, r.fin.nv, resampled ? "resampled" : "refined", o.refine_to);
        else if (o.tries > 1 && t > 0 && !o.quiet)
            fprintf(stderr, "tightrope tighten: road %ld of %ld: %s\n", t + 1, o.tries,
                    ot.road_from ? "the shortest result so far, moved"
                    : ot.shuffled ? "the start shuffled (crankshaft moves of the thin rope, then compacted)"
                    : ot.inflate != 1.0 ? "the start again, inflated 1.5 times, from another coarse count"
                                        : "the start again, from another coarse count");
        tr_engine *et;
        tighten_result rt;
        rc = one_road(&ot, &et, &rt);
        if (resampled)
            tr_curve_free(&scout_at_n);
        if (rc >= 0) {
            if (!have)
                return rc;
            if (tr_deadline_passed(&bound)) {
                if (!o.quiet)
                    fprintf(stderr, "tightrope tighten: road %ld of %ld %s; the shortest so far is written\n", t + 1,
                            o.tries + scouting, tr_deadline_passed(&bound) == 2 ? "stopped by a signal"
                                                                               : "stopped by the time limit");
            } else if (refining)
                fprintf(stderr, "tightrope tighten: the refinement failed; the shortest scout is written\n");
            else
                fprintf(stderr, "tightrope tighten: road %ld of %ld skipped\n", t + 1, o.tries);
            continue;
        }
        if (o.tries > 1 && !o.quiet) {
            if (refining)
                fprintf(stderr, "tightrope tighten: refined: N %zu, ropelength %.9f\n", rt.fin.nv, rt.th.ropelength);
            else
                fprintf(stderr, "tightrope tighten: road %ld of %ld: ropelength %.9f\n", t + 1, o.tries,
                        rt.th.ropelength);
        }
        /* a road that ran out of time on a coarse level has not reached
         * the N asked for: the finest road wins, then the shortest; among
         * scouts (each at its own coarse count) the shortest */
        /* ... but a road at exactly the N asked for wins over one the
         * engine took past it */
        int shorter = rt.th.ropelength < r.th.ropelength, at_n = at_refine_n(&o, &rt.fin),
            same_n = at_n == at_refine_n(&o, &r.fin), finer = same_n ? rt.fin.nv > r.fin.nv : at_n;
        int better = !have || (scouting && !refining ? shorter : finer || (same_n && rt.fin.nv == r.fin.nv && shorter));
        if (better) {
            /* the refined scout keeps the scout's number */
            int best_try = refining ? r.best_try : (int)t;
            if (have) {
                tr_curve_free(&r.fin);
                tr_engine_destroy(e);
            }
            e = et;
            r = rt;
            r.best_try = best_try;
            have = 1;
        } else {
            tr_curve_free(&rt.fin);
            tr_engine_destroy(et);
        }
        r.tries = (int)(t < o.tries ? t + 1 : o.tries);
    }
    /* an interrupted series is an interrupted run, whichever road is kept */
    if (tr_cli_interrupted())
        r.why = TR_STOP_SIGNAL;
    tr_error err;
    rc = write_output(&o, e, &r, argc, argv, &err);
    if (rc) {
        fprintf(stderr, "tightrope tighten: %s\n", err.msg);
        tr_curve_free(&r.fin);
        tr_engine_destroy(e);
        return 2;
    }
    if (rep)
        fill_report(&o, &r, rep);
    else
        print_summary(&o, e, &r);
    rc = final_status(&o, &r);
    tr_curve_free(&r.fin);
    tr_engine_destroy(e);
    return rc;
}
