/* tightrope batch SRC -o OUT [options] [-- tighten options]
 *
 * Tightens every knot of a manifest or a folder (batch_manifest.h) with
 * tighten's own code (tr_cli_tighten_parse and tr_cli_tighten_run over the
 * tightening layer, in this process: the same checks, certificate and
 * output as `tightrope tighten`), one after the
 * other, into OUT: NAME.vect (the tight curve, its certificate in
 * comments), NAME.ckpt while it runs, NAME.row.tsv once it is done
 * (batch_row.h), and the table of every knot done, table.tsv and
 * table.json (batch_table.h). A knot the manifest names (`knot 3_1`) has
 * its start made by the batch into OUT/starts (batch_start.h). A knot
 * with a record is skipped and one with
 * a checkpoint resumes from it, so a batch killed at any moment is started
 * again with the same command. A record and a checkpoint name the start
 * they came from (NAME.start beside a checkpoint), so that neither is
 * taken for the knot's once the manifest points it at another file.
 * Everything a run of hours would fail on late is checked before anything
 * runs: a file the batch writes that is one it reads, every knot's
 * options. Scale-out is left to existing engines:
 * --only NAME and --job I --jobs J select independent parts, which GNU
 * parallel or a SLURM array (scripts/slurm_batch.sh) run at once into the
 * same OUT; each rewrites the table under a lock, and --table-only
 * rebuilds it from the records. --merge OTHER keeps the shorter of two
 * batches' results per knot (batch_merge.h): the roads of another seed,
 * run anywhere, join the table. --retry R (with --compare) does the same
 * within the batch: a knot still above its reference is tightened again
 * with the next seed, up to R times, each round into OUT/retry-J, and the
 * shorter result kept. */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/batch_knotinfo.h"
#include "cli/batch_manifest.h"
#include "cli/batch_merge.h"
#include "cli/batch_row.h"
#include "cli/batch_start.h"
#include "cli/batch_table.h"
#include "cli/cli.h"
#include "cli/cli_args.h"
#include "cli/cli_tighten.h"
#include "curve/curve.h"
#include "curve/curve_io.h"
#include "solver/newton.h"
#include "util/clock.h"
#include "util/text_file.h"

static void usage(FILE *out)
{
    fprintf(out,
            "usage: tightrope batch SRC -o OUT [options] [-- TIGHTEN-OPTIONS...]\n"
            "  SRC                a folder of curve files (.vect, .tsv, .txt, .dat, .knot; each knot\n"
            "                     named by its file without the extension) or a manifest: lines\n"
            "                     name<TAB>start<TAB>N<TAB>options ('#' comments; start a file relative\n"
            "                     to the manifest, or 'knot NAME' / 'link NAME' (also knot:NAME): a\n"
            "                     knot of KnotInfo's table or a link of LinkInfo's, made as tightrope\n"
            "                     make knot|link NAME makes it, into OUT/starts/; a file so called\n"
            "                     is ./knot...; N the vertices per component of the tight curve,\n"
            "                     tighten --refine-to N, or --n N for a start with more, '-' none;\n"
            "                     options: tighten's, space-separated, for this knot)\n"
            "  -o, --out OUT      output folder: NAME.vect (tight curve and certificate), NAME.ckpt and\n"
            "                     NAME.start (while it runs), NAME.row.tsv (done), table.tsv and\n"
            "                     table.json, starts/NAME.vect (a start by name)\n"
            "  --only NAME        this knot only (GNU parallel: one job per name of --list)\n"
            "  --job I --jobs J   the knots at places I, I+J, I+2J, ... of SRC (0 <= I < J):\n"
            "                     one of J independent jobs (a SLURM array, scripts/slurm_batch.sh)\n"
            "  --list             print the selected knots' names, one a line, and tighten nothing\n"
            "  --table-only       tighten nothing: rebuild the table from the knots done in OUT\n"
            "  --merge OTHER      tighten nothing: take each selected knot's result from OTHER (a batch\n"
            "                     output folder of the same knots, e.g. another --seed) where OUT has\n"
            "                     none or OTHER's is shorter at the same N; then rebuild the table.\n"
            "                     A record in OTHER of another start than the knot's file now (another\n"
            "                     knot under the name) refuses the whole merge: exit 2, nothing merged;\n"
            "                     one written before records named their start is merged on its name\n"
            "                     alone, and said so on stderr\n"
            "  --compare REF      add a reference table's N and ropelength (a TSV with a header: knot\n"
            "                     name first, a column 'ropelength...'; '.' and '_' match in names)\n"
            "                     and the difference, ours - reference, absolute and in %%.\n"
            "                     --compare knotinfo: KnotInfo's ropelengths, built in (a knot by name\n"
            "                     takes its knot's, one from a file its name's; links have none; a\n"
            "                     file called knotinfo is ./knotinfo)\n"
            "  --retry R          with --compare: a knot whose ropelength is above the reference's is\n"
            "                     tightened again, up to R times, each time with the next seed (the\n"
            "                     options' --seed S, or 1, plus the round) into OUT/retry-ROUND/, and the\n"
            "                     shorter result kept in OUT (as --merge would)\n"
            "  --retry-options \"OPTS\"  tighten options the retries take in place of the same options\n"
            "                     of the knot's (space-separated), e.g. \"--tries 8 --shuffles 7\": other\n"
            "                     roads for a knot that one recipe leaves in one basin whatever the seed;\n"
            "                     given K times (at most 8), round r takes the ((r - 1) mod K + 1)-th\n"
            "  --checkpoint-every S  seconds between a knot's checkpoints (default 30)\n"
            "  --quiet            no progress lines\n"
            "A knot done (its NAME.row.tsv exists) is skipped; one with a checkpoint resumes from it.\n"
            "A record names the start it came from (a hash of the start file's bytes, or of a start by\n"
            "name's name and braid word; the table's columns start and source) and whether the tight\n"
            "curve kept its start's knot type (type_check: kept, unchecked): a record or checkpoint of\n"
            "another start (the manifest points the knot at another file or name, or the file was\n"
            "edited) is not skipped or resumed, the knot is tightened afresh, and the table leaves the\n"
            "record out until then.\n"
            "Before anything runs or is written, batch refuses (one line, exit 2) a file it would write\n"
            "for any knot (curve, checkpoint, record, table, OUT/retry-R's) that is one it reads (a start,\n"
            "the manifest, --compare's), and any knot's options that tighten refuses (the line's with\n"
            "those after --, and with each --retry-options), naming FILE:LINE.\n"
            "TIGHTEN-OPTIONS go to every knot (before the manifest's own), e.g. -- --scale --time-limit 120;\n"
            "batch sets -o, --checkpoint, --checkpoint-every, --resume and --json itself; a resumed run\n"
            "leaves out --n, --scale, --tries, --shuffles and --seed (the checkpoint continues one road).\n"
            "Exit status: 0 every selected knot done (or running in another batch process); 1\n"
            "interrupted (SIGINT/SIGTERM: the running knot keeps its checkpoint) or a knot's run\n"
            "failed; 2 bad SRC, option or input.\n");
}

/* --retry-options at most */
#define MAX_RECIPES 8

typedef struct batch_opts {
    const char *src, *out, *only, *compare, *merge;
    long job, jobs; /* jobs 0: all */
    long retry;     /* rounds of retries above the reference */
    /* --retry-options as given, in order (round r takes recipe (r - 1) mod
     * nrecipes), each split into words (tr_cmd_batch), each a copy */
    const char *retry_text[MAX_RECIPES];
    char **ropts[MAX_RECIPES];
    int nropts[MAX_RECIPES];
    int nrecipes;
    double ckpt_every;
    int list, table_only, quiet;
    char **topts; /* tighten options after -- */
    int ntopts;
} batch_opts;

/* Parses the command line; -1 to go on, else the exit status. */
static int parse_options(int argc, char **argv, batch_opts *o)
{
    *o = (batch_opts){.job = -1, .ckpt_every = 30};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--")) {
            o->topts = argv + i + 1;
            o->ntopts = argc - i - 1;
            break;
        }
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        int *flag = !strcmp(a, "--list") ? &o->list
                    : !strcmp(a, "--table-only") ? &o->table_only
                    : !strcmp(a, "--quiet") ? &o->quiet
                    : NULL;
        if (flag) {
            *flag = 1;
            continue;
        }
        static const char *valued[] = {"-o", "--out", "--only", "--compare", "--job", "--jobs",
                                       "--checkpoint-every", "--merge", "--retry", "--retry-options"};
        size_t k = 0;
        while (k < sizeof valued / sizeof valued[0] && strcmp(a, valued[k]))
            k++;
        if (k == sizeof valued / sizeof valued[0]) {
            if (a[0] == '-' && a[1]) {
                fprintf(stderr, "tightrope batch: unknown option '%s' (tighten's options go after --; "
                                "see tightrope batch --help)\n", a);
                return 2;
            }
            if (o->src) {
                fprintf(stderr, "tightrope batch: unexpected argument '%s'\n", a);
                return 2;
            }
            o->src = a;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "tightrope batch: %s needs a value\n", a);
            return 2;
        }
        const char *v = argv[++i];
        int bad = 0;
        if (k <= 1)
            o->out = v;
        else if (k == 2)
            o->only = v;
        else if (k == 3)
            o->compare = v;
        else if (k == 4)
            bad = tr_arg_long(v, 0, 1000000000, &o->job);
        else if (k == 5)
            bad = tr_arg_long(v, 1, 1000000000, &o->jobs);
        else if (k == 7)
            o->merge = v;
        else if (k == 8)
            bad = tr_arg_long(v, 0, 1000, &o->retry);
        else if (k == 9 && o->nrecipes == MAX_RECIPES) {
            fprintf(stderr, "tightrope batch: --retry-options at most %d times\n", MAX_RECIPES);
            return 2;
        } else if (k == 9)
            o->retry_text[o->nrecipes++] = v;
        else
            bad = tr_arg_double(v, 0, 1e9, &o->ckpt_every) || o->ckpt_every <= 0;
        if (bad) {
            fprintf(stderr, "tightrope batch: bad %s '%s' (%s)\n", a, v,
                    k == 4 ? "an integer >= 0" : k == 5 ? "an integer >= 1" : k == 8 ? "an integer from 0 to 1000"
                                                                                : "a number > 0 (seconds)");
            return 2;
        }
    }
    const char *bad = NULL;
    if (!o->src)
        bad = "no SRC (a manifest or a folder of curves; see tightrope batch --help)";
    else if (!o->out && !o->list)
        bad = "no output folder (-o OUT)";
    else if ((o->job >= 0) != (o->jobs > 0))
        bad = "--job I and --jobs J go together";
    else if (o->jobs > 0 && o->job >= o->jobs)
        bad = "--job I needs 0 <= I < J (--jobs J)";
    else if (o->only && o->jobs > 0)
        bad = "--only and --job select differently; give one";
    else if (o->table_only && (o->only || o->jobs > 0 || o->list))
        bad = "--table-only rebuilds the whole table; it takes no --only, --job or --list";
    else if (o->merge && (o->table_only || o->list))
        bad = "--merge tightens nothing already; it takes no --table-only or --list";
    else if (o->merge && o->ntopts > 0)
        bad = "--merge tightens nothing; it takes no tighten options after --";
    else if (o->retry > 0 && !o->compare)
        bad = "--retry needs --compare REF (a knot is retried while it is above the reference)";
    else if (o->nrecipes > 0 && o->retry == 0)
        bad = "--retry-options goes with --retry R (R >= 1)";
    else if (o->retry > 0 && (o->merge || o->table_only || o->list))
        bad = "--retry tightens; it takes no --merge, --table-only or --list";
    for (int j = 0; !bad && j < o->ntopts; j++)
        if (tr_batch_reserved_option(o->topts[j])) {
            fprintf(stderr, "tightrope batch: tighten option %s: %s\n", o->topts[j],
                    tr_batch_reserved_option(o->topts[j]));
            return 2;
        }
    if (bad) {
        fprintf(stderr, "tightrope batch: %s\n", bad);
        return 2;
    }
    return -1;
}

/* Whether the tighten options after -- set the vertex count. */
static int topts_set_n(const batch_opts *o)
{
    for (int j = 0; j < o->ntopts; j++)
        if (!strcmp(o->topts[j], "--n") || !strcmp(o->topts[j], "--refine-to"))
            return 1;
    return 0;
}

/* OUT/NAME.EXT into buf (sized for the longest name). */
static void knot_path(char *buf, size_t size, const char *out, const char *name, const char *ext)
{
    snprintf(buf, size, "%s/%s.%s", out, name, ext);
}

#define PATH_SIZE 4400

static int exists(const char *path) { return access(path, F_OK) == 0; }

/* The options of a resumed run: the checkpoint holds the resampled and
 * scaled start, and tighten refuses --n and --scale with --resume; it
 * continues the road that was interrupted, so --tries, --shuffles (which
 * tighten refuses without --tries above it) and --seed go too. */
static int start_only(char **opts, int j)
{
    if (!strcmp(opts[j], "--scale"))
        return 1;
    return !strcmp(opts[j], "--n") || !strcmp(opts[j], "--tries") || !strcmp(opts[j], "--shuffles") ||
                   !strcmp(opts[j], "--seed")
               ? 2
               : 0;
}

/* Whether opts[j] (an option) is followed by its value: the next word is
 * not an option itself (a number may be negative) */
static int has_value(char **opts, int nopts, int j)
{
    if (j + 1 >= nopts)
        return 0;
    const char *v = opts[j + 1];
    return v[0] != '-' || isdigit((unsigned char)v[1]) || v[1] == '.';
}

/* Whether option opt is one of over's (the retries' own, which replace it) */
static int overridden(const char *opt, char **over, int nover)
{
    if (opt[0] != '-')
        return 0;
    for (int j = 0; j < nover; j++)
        if (!strcmp(opt, over[j]))
            return 1;
    return 0;
}

/* Appends the options to args, leaving out the start's when resuming,
 * --seed where the batch sets its own (a retry round) and those that over
 * (nover words) gives anew. */
static void add_opts(char **args, int *na, char **opts, int nopts, int resume, int own_seed, char **over,
                     int nover)
{
    for (int j = 0; j < nopts; j++) {
        int skip = resume ? start_only(opts, j) : 0;
        if (own_seed && !strcmp(opts[j], "--seed"))
            skip = 2;
        if (!skip && overridden(opts[j], over, nover))
            skip = 1 + has_value(opts, nopts, j);
        if (skip) {
            j += skip - 1;
            continue;
        }
        args[(*na)++] = opts[j];
    }
}

/* What knot k's start is, for a message: its file, or the name it was
 * made from ("knot:3_1") */
static const char *start_of(const tr_batch_knot *k) { return k->source ? k->source : k->file; }

/* How N reaches tighten: --refine-to N refines the start's components up
 * to N; a start with more vertices than that is resampled to N (--n N). */
static const char *n_option(const tr_batch_knot *k, int resume, tr_error *err, int *rc)
{
    *rc = TR_OK;
    if (resume)
        return "--refine-to";
    tr_curve c;
    if ((*rc = tr_curve_read(k->file, TR_FORMAT_AUTO, &c, err)) != TR_OK)
        return NULL;
    size_t most = 0;
    for (int q = 0; q < c.ncomp; q++)
        if (tr_comp_nv(&c, q) > most)
            most = tr_comp_nv(&c, q);
    tr_curve_free(&c);
    return most > (size_t)k->n ? "--n" : "--refine-to";
}

/* The tighten command line of one run of knot k into folder dir: from its
 * start, or (resume) from dir/NAME.ckpt; n_opt says how N reaches tighten
 * (n_option); seed >= 0 is a retry round's, with recipe's options
 * (o->ropts) in place of the same options of the batch's and the knot's.
 * The run and the checks before anything runs (check_args) build it here
 * alike, so what is checked is what runs. */
typedef struct run_args {
    char vect[PATH_SIZE], ckpt[PATH_SIZE], nbuf[32], every[32], sbuf[32];
    char **argv;
    int argc;
} run_args;

static int build_args(const batch_opts *o, const tr_batch_knot *k, const char *dir, long seed, int recipe,
                      int resume, const char *n_opt, run_args *a)
{
    int own_seed = seed >= 0, has_recipe = own_seed && recipe >= 0 && recipe < o->nrecipes;
    char **ropts = has_recipe ? o->ropts[recipe] : NULL;
    int nropts = has_recipe ? o->nropts[recipe] : 0;
    knot_path(a->vect, sizeof a->vect, dir, k->name, "vect");
    knot_path(a->ckpt, sizeof a->ckpt, dir, k->name, "ckpt");
    a->argv = malloc((size_t)(16 + o->ntopts + k->nopts + nropts) * sizeof *a->argv);
    if (!a->argv)
        return -1;
    char **args = a->argv;
    int na = 0;
    args[na++] = "tighten";
    if (resume) {
        args[na++] = "--resume";
        args[na++] = a->ckpt;
    } else {
        args[na++] = k->file;
    }
    snprintf(a->every, sizeof a->every, "%g", o->ckpt_every);
    char *fixed[] = {"-o", a->vect, "--checkpoint", a->ckpt, "--checkpoint-every", a->every, "--quiet"};
    for (size_t j = 0; j < sizeof fixed / sizeof fixed[0]; j++)
        args[na++] = fixed[j];
    if (k->n > 0) {
        snprintf(a->nbuf, sizeof a->nbuf, "%ld", k->n);
        args[na++] = (char *)n_opt;
        args[na++] = a->nbuf;
    }
    /* a retry's own options replace the same options of the batch's and the knot's */
    add_opts(args, &na, o->topts, o->ntopts, resume, own_seed, ropts, nropts);
    add_opts(args, &na, k->opts, k->nopts, resume, own_seed, ropts, nropts);
    if (own_seed)
        add_opts(args, &na, ropts, nropts, resume, own_seed, NULL, 0);
    if (own_seed && !resume) {
        snprintf(a->sbuf, sizeof a->sbuf, "%ld", seed);
        args[na++] = "--seed";
        args[na++] = a->sbuf;
    }
    args[na] = NULL;
    a->argc = na;
    return 0;
}

/* Whether knot k's run into dir resumes: its checkpoint exists and
 * continues the start the knot has now (start, tr_batch_start_id). A
 * checkpoint of another start (the manifest points the knot at another
 * file, or the file was edited) is removed with its NAME.start, both the
 * batch's own, and the knot starts afresh: resuming would tabulate the
 * other curve under this name. A checkpoint without NAME.start (made by a
 * tightrope before records named their start) resumes as before, its
 * start unknown. *id gets the identity the run's record will carry.
 * Returns 0 or 1, or -1 with the message printed. */
static int decide_resume(const batch_opts *o, const tr_batch_knot *k, const char *dir, const char *start,
                         char id[TR_BATCH_ID_SIZE]);

/* The solver's state tighten keeps beside a knot's checkpoint (CKPT.newton,
 * host/engine/solver_state.c) goes with the checkpoint; only a solver
 * state is removed. */
static void unlink_solver_state(const char *ckpt)
{
    char p[PATH_SIZE + 8];
    int n = snprintf(p, sizeof p, "%s.newton", ckpt);
    if (n > 0 && (size_t)n < sizeof p && tr_newton_state_is_file(p))
        unlink(p);
}

static int decide_resume(const batch_opts *o, const tr_batch_knot *k, const char *dir, const char *start,
                         char id[TR_BATCH_ID_SIZE])
{
    char ckpt[PATH_SIZE], side[PATH_SIZE];
    knot_path(ckpt, sizeof ckpt, dir, k->name, "ckpt");
    knot_path(side, sizeof side, dir, k->name, "start");
    snprintf(id, TR_BATCH_ID_SIZE, "%s", start);
    if (!exists(ckpt))
        return 0;
    tr_error err;
    int rc = tr_batch_start_read(side, id, &err);
    if (rc < 0) {
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
        return -1;
    }
    if (rc == 1 || !id[0] || !start[0] || !strcmp(id, start))
        return 1;
    if (!o->quiet)
        fprintf(stderr, "batch: %s: %s is of another start (%s; %s is %s now): it starts afresh\n", k->name, ckpt,
                id, start_of(k), start);
    if ((unlink(ckpt) && errno != ENOENT) || (unlink(side) && errno != ENOENT)) {
        fprintf(stderr, "tightrope batch: %s: cannot remove %s: %s\n", k->name, ckpt, strerror(errno));
        return -1;
    }
    unlink_solver_state(ckpt);
    snprintf(id, TR_BATCH_ID_SIZE, "%s", start);
    return 0;
}

/* Runs tighten on knot k into folder dir, from its start or (resume, as
 * decide_resume says) from its checkpoint, with --seed seed and the retry
 * options of recipe (o->ropts) where seed >= 0, and writes its record,
 * which names the start (id, from decide_resume). Returns tighten's exit
 * status, or 2 when the record cannot be written; *rep says what the run
 * came to. */
static int run_knot(const batch_opts *o, const tr_batch_knot *k, const char *dir, long seed, int recipe,
                    int resume, const char *id, tr_tighten_report *rep)
{
    *rep = (tr_tighten_report){0};
    char row[PATH_SIZE], side[PATH_SIZE];
    knot_path(row, sizeof row, dir, k->name, "row.tsv");
    knot_path(side, sizeof side, dir, k->name, "start");
    tr_error err;
    int rc = TR_OK;
    /* a start by name is made afresh for a run from the start (the same
     * curve every time: tr_batch_make_start); a resumed run reads only its
     * checkpoint */
    if (!resume && (rc = tr_batch_make_start(k, &err)) != TR_OK) {
        fprintf(stderr, "tightrope batch: %s: its start %s: %s\n", k->name, k->source, err.msg);
        return rc == TR_ENOMEM || rc == TR_EGEOMETRY ? 1 : 2;
    }
    const char *n_opt = k->n > 0 ? n_option(k, resume, &err, &rc) : NULL;
    if (rc != TR_OK) {
        fprintf(stderr, "tightrope batch: %s: %s\n", k->name, err.msg);
        return rc == TR_ENOMEM ? 1 : 2;
    }
    /* the start's identity before the checkpoint it belongs to exists */
    if (!resume && tr_batch_start_write(side, id, &err)) {
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
        return 2;
    }
    run_args a;
    if (build_args(o, k, dir, seed, recipe, resume, n_opt, &a)) {
        fprintf(stderr, "tightrope batch: out of memory\n");
        return 1;
    }
    /* the run's words (the same the checks before the batch passed, and
     * the command line the output's comments record) parsed into tighten's
     * options, and the run on that struct (cli_tighten.h, tr_tighten) */
    tr_cli_tighten t;
    *rep = (tr_tighten_report){.kkt_residual = NAN, .stop = ""};
    int status = tr_cli_tighten_parse(a.argc, a.argv, &t);
    if (status < 0)
        status = tr_cli_tighten_run(&t, a.argc, a.argv, rep);
    free(a.argv);
    if (!rep->written || rep->interrupted) {
        if (resume && !rep->written)
            fprintf(stderr, "tightrope batch: %s: resuming from %s failed; remove it to start the knot afresh\n",
                    k->name, a.ckpt);
        /* a run that failed before its first checkpoint leaves nothing to continue */
        if (!exists(a.ckpt))
            unlink(side);
        return status;
    }
    tr_batch_row r = {.n = rep->n, .ropelength = rep->ropelength, .thickness = rep->thickness,
                      .minrad = rep->minrad, .dcsd = rep->dcsd, .kkt_residual = rep->kkt_residual,
                      .time_s = rep->elapsed, .tries = rep->tries, .steps = rep->steps, .resumed = resume,
                      .seed = rep->seed, .road = rep->road};
    snprintf(r.knot, sizeof r.knot, "%s", k->name);
    snprintf(r.stop, sizeof r.stop, "%s", rep->stop);
    snprintf(r.start, sizeof r.start, "%s", id);
    snprintf(r.source, sizeof r.source, "%s", k->source ? k->source : "file");
    r.type_checked = rep->type_checked ? 1 : 0;
    /* the record last: with it the knot is done, and its checkpoint is
     * no longer needed */
    if (tr_batch_row_write(row, &r, &err)) {
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
        return 2;
    }
    unlink(a.ckpt);
    unlink_solver_state(a.ckpt);
    unlink(side);
    return status;
}

/* Rebuilds OUT/table.* from the records of the knots of l (in l's order),
 * under an exclusive lock on OUT/.batch.lock, so that of several jobs
 * finishing at once the last to write has read every record. A record of
 * another start than the knot's now is left out (said unless --quiet):
 * the table never shows another curve's numbers under a knot's name; the
 * knot is tightened again when a batch selects it. */
static int write_table(const batch_opts *o, const tr_batch_list *l, const tr_batch_ref *ref, size_t *rows_out)
{
    char lock[PATH_SIZE], row[PATH_SIZE];
    snprintf(lock, sizeof lock, "%s/.batch.lock", o->out);
    int fd = open(lock, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0 || flock(fd, LOCK_EX)) {
        fprintf(stderr, "tightrope batch: %s: %s\n", lock, strerror(errno));
        if (fd >= 0)
            close(fd);
        return 2;
    }
    tr_batch_row *rows = malloc((l->count + 1) * sizeof *rows);
    int status = rows ? 0 : 1;
    size_t n = 0;
    tr_error err;
    for (size_t i = 0; status == 0 && i < l->count; i++) {
        knot_path(row, sizeof row, o->out, l->knots[i].name, "row.tsv");
        if (!exists(row))
            continue;
        char start[TR_BATCH_ID_SIZE];
        if (tr_batch_row_read(row, &rows[n], &err) || tr_batch_knot_start_id(&l->knots[i], start, &err)) {
            fprintf(stderr, "tightrope batch: %s\n", err.msg);
            status = 2;
        } else if (tr_batch_other_start(&rows[n], start)) {
            if (!o->quiet)
                fprintf(stderr, "batch: %s: %s is of another start than %s now; left out of the table until the "
                                "knot is tightened again\n", l->knots[i].name, row, start_of(&l->knots[i]));
        } else
            n++;
    }
    if (status == 0 && tr_batch_table_write(o->out, rows, n, ref, &err)) {
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
        status = 2;
    }
    if (!rows)
        fprintf(stderr, "tightrope batch: out of memory\n");
    free(rows);
    close(fd); /* releases the lock */
    *rows_out = n;
    return status;
}

/* Takes the knot's lock (OUT/.NAME.lock, kept: a lock file removed while
 * another process waits on it would let two hold "the" lock), so that two
 * batches over one OUT (overlapping --job sets, a SLURM task requeued
 * while it still runs) never tighten one knot at once. Returns the
 * descriptor that holds it, -1 when another process holds it, -2 (with
 * the message printed) when it cannot be taken. */
static int lock_knot(const char *out, const char *name)
{
    char path[PATH_SIZE];
    snprintf(path, sizeof path, "%s/.%s.lock", out, name);
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) == 0)
        return fd;
    int busy = fd >= 0 && errno == EWOULDBLOCK;
    if (!busy)
        fprintf(stderr, "tightrope batch: %s: %s\n", path, strerror(errno));
    if (fd >= 0)
        close(fd);
    return busy ? -1 : -2;
}

/* Whether knot i of l is selected by --only or --job/--jobs. */
static int selected(const batch_opts *o, const tr_batch_list *l, size_t i)
{
    if (o->only)
        return !strcmp(l->knots[i].name, o->only);
    return o->jobs == 0 || (long)(i % (size_t)o->jobs) == o->job;
}

/* The counts behind the progress lines. */
typedef struct batch_progress {
    size_t total, at, done, skipped, failed, busy;
    double t0, run_seconds; /* clock at the start; seconds of the knots run here */
} batch_progress;

static void progress_line(const batch_opts *o, const batch_progress *p, const char *name, const char *fmt,
                          const char *what)
{
    if (o->quiet)
        return;
    double el = tr_clock_seconds() - p->t0;
    fprintf(stderr, "batch [%zu/%zu] %s: ", p->at, p->total, name);
    fprintf(stderr, fmt, what);
    fprintf(stderr, " (%zu done, %zu skipped, %zu failed", p->done, p->skipped, p->failed);
    if (p->busy)
        fprintf(stderr, ", %zu running elsewhere", p->busy);
    fprintf(stderr, "; %.0f s", el);
    size_t left = p->total - p->at;
    if (p->done > 0 && left > 0)
        fprintf(stderr, ", about %.0f s left", p->run_seconds / (double)p->done * (double)left);
    fprintf(stderr, ")\n");
}

/* The seed of the knot's own runs: the last --seed of its options (the
 * manifest's after the batch's, as tighten reads them), or tighten's 1 */
static void last_seed(char **opts, int nopts, long *seed)
{
    long v;
    for (int j = 0; j + 1 < nopts; j++)
        if (!strcmp(opts[j], "--seed") && !tr_arg_long(opts[j + 1], 0, 1000000000, &v))
            *seed = v;
}
static long base_seed(const batch_opts *o, const tr_batch_knot *k)
{
    long seed = 1;
    last_seed(o->topts, o->ntopts, &seed);
    last_seed(k->opts, k->nopts, &seed);
    return seed;
}

/* --retry: knot k, done in OUT (its lock held), tightened again while its
 * record is above the reference's, round r into OUT/retry-r with the seed
 * base + r, each round's result merged into OUT (batch_merge.h). A round
 * with a record is not run again, one with a checkpoint resumes: a batch
 * killed during a retry and started again ends with the same table.
 * Returns 0, 1 (interrupted, or a run failed) or 2 (a record or folder
 * could not be read or written). */
static int retry_knot(const batch_opts *o, const tr_batch_knot *k, const char *start, const tr_batch_ref *ref,
                      batch_progress *p)
{
    long line = tr_batch_ref_find(ref, k->name);
    if (line < 0)
        return 0;
    double target = ref->ropelength[line];
    char row[PATH_SIZE], dir[PATH_SIZE / 2], rrow[PATH_SIZE], what[700];
    knot_path(row, sizeof row, o->out, k->name, "row.tsv");
    long base = base_seed(o, k);
    for (long r = 1; r <= o->retry; r++) {
        tr_batch_row cur;
        tr_error err;
        if (tr_batch_row_read(row, &cur, &err)) {
            fprintf(stderr, "tightrope batch: %s\n", err.msg);
            return 2;
        }
        if (isfinite(cur.ropelength) && cur.ropelength <= target)
            return 0;
        if (snprintf(dir, sizeof dir, "%s/retry-%ld", o->out, r) >= (int)sizeof dir) {
            fprintf(stderr, "tightrope batch: the output folder's name is too long for --retry\n");
            return 2;
        }
        if (mkdir(dir, 0777) && errno != EEXIST) {
            fprintf(stderr, "tightrope batch: cannot make the folder %s: %s\n", dir, strerror(errno));
            return 2;
        }
        knot_path(rrow, sizeof rrow, dir, k->name, "row.tsv");
        /* a round's record of another start (the knot's start changed since) is run again */
        tr_batch_row done;
        int again = !exists(rrow);
        if (!again && tr_batch_row_read(rrow, &done, &err)) {
            fprintf(stderr, "tightrope batch: %s\n", err.msg);
            return 2;
        }
        if (again || tr_batch_other_start(&done, start)) {
            int recipe = o->nrecipes > 0 ? (int)((r - 1) % o->nrecipes) : -1;
            int at = snprintf(what, sizeof what, "%.6f is above the reference's %.6f: retry %ld of %ld, seed %ld",
                              cur.ropelength, target, r, o->retry, base + r);
            if (recipe >= 0 && at > 0 && (size_t)at < sizeof what)
                snprintf(what + at, sizeof what - (size_t)at, ", %s", o->retry_text[recipe]);
            char id[TR_BATCH_ID_SIZE];
            int resume = decide_resume(o, k, dir, start, id);
            if (resume < 0)
                return 2;
            progress_line(o, p, k->name, "%s", what);
            double t = tr_clock_seconds();
            tr_tighten_report rep;
            int rc = run_knot(o, k, dir, base + r, recipe, resume, id, &rep);
            p->run_seconds += tr_clock_seconds() - t;
            if (rep.interrupted || tr_tighten_stop_requested()) {
                if (!o->quiet)
                    fprintf(stderr, "batch: interrupted; %s's retry %ld goes on when the batch is run again\n",
                            k->name, r);
                return 1;
            }
            if (!rep.written || rc == 2) {
                snprintf(what, sizeof what, "retry %ld FAILED (tighten's exit status %d; its message above)", r, rc);
                progress_line(o, p, k->name, "%s", what);
                return rc == 2 ? 2 : 1;
            }
        }
        tr_merge_outcome how;
        char merged[512];
        int mc = tr_batch_merge_knot(o->out, dir, k->name, start, &how, merged, sizeof merged, &err);
        if (mc != TR_OK) {
            fprintf(stderr, "tightrope batch: %s\n", err.msg);
            return mc == TR_ENOMEM ? 1 : 2;
        }
        if (how == TR_MERGE_OTHER_START) {
            /* the start changed while the round ran: nothing of it is this knot's */
            fprintf(stderr, "tightrope batch: %s: retry %ld: %s\n", k->name, r, merged);
            return 1;
        }
        snprintf(what, sizeof what, "retry %ld: %s", r, merged);
        progress_line(o, p, k->name, "%s", what);
    }
    return 0;
}

/* Tightens knot k (or resumes it) into OUT, with its progress lines.
 * Returns 0 done (*done = 1), -1 interrupted (the run keeps its
 * checkpoint), or the exit status of a failed run (1 or 2). */
static int tighten_one(const batch_opts *o, const tr_batch_knot *k, const char *start, batch_progress *p,
                       int *done)
{
    char what[160], id[TR_BATCH_ID_SIZE];
    int resume = decide_resume(o, k, o->out, start, id);
    if (resume < 0) {
        p->failed++;
        return 2;
    }
    progress_line(o, p, k->name, "%s", resume ? "resuming from its checkpoint" : "tightening");
    double t = tr_clock_seconds();
    tr_tighten_report rep;
    int rc = run_knot(o, k, o->out, -1, -1, resume, id, &rep);
    if (rep.interrupted || tr_tighten_stop_requested()) {
        /* a run whose roads were scouts wrote no checkpoint (tighten says
         * why): the knot then starts again, and is not said to resume */
        char ckpt[PATH_SIZE];
        knot_path(ckpt, sizeof ckpt, o->out, k->name, "ckpt");
        if (!o->quiet && rep.interrupted)
            fprintf(stderr, "batch: interrupted; %s %s when the batch is run again\n", k->name,
                    exists(ckpt) ? "resumes from its checkpoint" : "starts again (its run wrote no checkpoint)");
        else if (!o->quiet)
            fprintf(stderr, "batch: interrupted after %s\n", k->name);
        return -1;
    }
    if (rep.written && rc != 2) {
        p->done++;
        p->run_seconds += tr_clock_seconds() - t;
        snprintf(what, sizeof what, "ropelength %.6f, KKT residual %.1e, %.1f s, stopped: %s", rep.ropelength,
                 rep.kkt_residual, rep.elapsed, rep.stop);
        progress_line(o, p, k->name, "done, %s", what);
        *done = 1;
        return 0;
    }
    p->failed++;
    snprintf(what, sizeof what, "%d", rc);
    progress_line(o, p, k->name, "FAILED (tighten's exit status %s; its message above)", what);
    return rc == 2 ? 2 : 1;
}

/* What knot k's record in OUT (path row) says of it, its start's identity
 * being start now: 0 no record, 1 done from this start, 2 done from one
 * unknown (a record of a tightrope before records named their start: kept,
 * as it was), 3 done from another start (the manifest points the knot at
 * another file, or the file was edited: to be tightened again), -1 the
 * record cannot be read (message printed). */
static int record_state(const char *row, const char *start)
{
    if (!exists(row))
        return 0;
    tr_batch_row r;
    tr_error err;
    if (tr_batch_row_read(row, &r, &err)) {
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
        return -1;
    }
    return tr_batch_other_start(&r, start) ? 3 : r.start[0] ? 1 : 2;
}

/* Tightens the selected knots in turn (and retries them: --retry).
 * Returns the exit status. */
static int run_all(const batch_opts *o, const tr_batch_list *l, const size_t *sel, size_t nsel, const tr_batch_ref *ref)
{
    batch_progress p = {.total = nsel, .t0 = tr_clock_seconds()};
    int status = 0;
    for (size_t s = 0; s < nsel; s++) {
        const tr_batch_knot *k = &l->knots[sel[s]];
        char row[PATH_SIZE], ckpt[PATH_SIZE], side[PATH_SIZE];
        knot_path(row, sizeof row, o->out, k->name, "row.tsv");
        knot_path(ckpt, sizeof ckpt, o->out, k->name, "ckpt");
        p.at = s + 1;
        if (tr_tighten_stop_requested())
            return 1;
        int lock = lock_knot(o->out, k->name);
        if (lock == -2)
            return 2;
        if (lock == -1) {
            p.busy++;
            progress_line(o, &p, k->name, "%s", "another batch process is running it, skipped");
            continue;
        }
        /* looked at under the lock: another process may just have finished it */
        char start[TR_BATCH_ID_SIZE];
        tr_error err;
        int state = tr_batch_knot_start_id(k, start, &err) ? -2 : record_state(row, start);
        if (state < 0) {
            if (state == -2)
                fprintf(stderr, "tightrope batch: %s: %s\n", k->name, err.msg);
            close(lock);
            p.failed++;
            status = 2;
            continue;
        }
        int done = state == 1 || state == 2, rc_run;
        if (state == 3)
            progress_line(o, &p, k->name, "%s", "its record is of another start than its file now: tightened again");
        if (done) {
            /* a run killed between its record and the checkpoint's removal */
            knot_path(side, sizeof side, o->out, k->name, "start");
            unlink(ckpt);
            unlink(side);
            p.skipped++;
            progress_line(o, &p, k->name, "%s",
                          state == 1 ? "done before, skipped"
                                     : "done before, skipped (its record names no start: made by an older tightrope)");
        } else if ((rc_run = tighten_one(o, k, start, &p, &done)) != 0) {
            close(lock);
            if (rc_run < 0)
                return 1;
            status = rc_run == 2 || status == 2 ? 2 : 1;
            continue;
        }
        /* a knot done here or before: retried while above its reference */
        int rs = done && o->retry > 0 ? retry_knot(o, k, start, ref, &p) : 0;
        close(lock);
        if (rs == 1 && tr_tighten_stop_requested())
            return 1;
        if (rs)
            status = rs == 2 || status == 2 ? 2 : 1;
    }
    return status;
}

/* Whether path is a folder; else says so for option opt. */
static int is_folder(const char *path, const char *opt)
{
    struct stat st;
    if (stat(path, &st)) {
        fprintf(stderr, "tightrope batch: %s: no folder %s: %s\n", opt, path, strerror(errno));
        return 0;
    }
    if (!S_ISDIR(st.st_mode)) {
        fprintf(stderr, "tightrope batch: %s: %s is not a folder\n", opt, path);
        return 0;
    }
    return 1;
}

/* Where knot k comes from, for a message: its manifest's FILE:LINE, or a
 * folder's curve file. */
static void knot_where(const batch_opts *o, const tr_batch_knot *k, char *buf, size_t size)
{
    if (k->line > 0)
        snprintf(buf, size, "%s:%d", o->src, k->line);
    else
        snprintf(buf, size, "%s", k->file);
}

/* --merge, before anything is written: every record of OTHER for a
 * selected knot is read, and one of another start than the knot's now
 * (OTHER's batch had another curve under this name: a trefoil there, an
 * unknot here) refuses the whole merge, said in one line with the first
 * such knot: two folders that disagree on what a name is do not hold the
 * same knots, and which of the others to believe cannot be told. Returns
 * -1 to go on, else the exit status. */
static int merge_check(const batch_opts *o, const tr_batch_list *l, const size_t *sel, size_t nsel)
{
    if (tr_same_file(o->merge, o->out)) {
        fprintf(stderr, "tightrope batch: --merge %s is the output folder itself\n", o->merge);
        return 2;
    }
    const tr_batch_knot *first = NULL;
    char theirs[TR_BATCH_ID_SIZE], ours[TR_BATCH_ID_SIZE];
    size_t others = 0;
    for (size_t s = 0; s < nsel; s++) {
        const tr_batch_knot *k = &l->knots[sel[s]];
        char row[PATH_SIZE], start[TR_BATCH_ID_SIZE];
        knot_path(row, sizeof row, o->merge, k->name, "row.tsv");
        if (!exists(row))
            continue;
        tr_batch_row r;
        tr_error err;
        if (tr_batch_row_read(row, &r, &err) || tr_batch_knot_start_id(k, start, &err)) {
            fprintf(stderr, "tightrope batch: --merge: %s\n", err.msg);
            return 2;
        }
        if (!tr_batch_other_start(&r, start) || others++)
            continue;
        first = k;
        memcpy(theirs, r.start, sizeof theirs);
        memcpy(ours, start, sizeof ours);
    }
    if (!others)
        return -1;
    char row[PATH_SIZE], where[PATH_SIZE], more[64] = "";
    knot_path(row, sizeof row, o->merge, first->name, "row.tsv");
    knot_where(o, first, where, sizeof where);
    if (others > 1)
        snprintf(more, sizeof more, " (and %zu more such knots)", others - 1);
    fprintf(stderr, "tightrope batch: --merge: %s is of another start than %s's %s (%s, not %s): another knot "
                    "under the name %s%s; nothing merged\n", row, where, start_of(first), theirs, ours, first->name, more);
    return 2;
}

/* --merge: each selected knot's result from o->merge where it is shorter
 * (batch_merge.h), under the knot's lock; merge_check has passed. A record
 * of another start found now (OTHER changed since) is left, said, and
 * makes the exit status 2. Returns the exit status. */
static int merge_all(const batch_opts *o, const tr_batch_list *l, const size_t *sel, size_t nsel)
{
    size_t counts[5] = {0};
    int status = 0;
    for (size_t s = 0; s < nsel; s++) {
        const tr_batch_knot *k = &l->knots[sel[s]];
        const char *name = k->name;
        char start[TR_BATCH_ID_SIZE];
        tr_error err;
        if (tr_batch_knot_start_id(k, start, &err)) {
            fprintf(stderr, "tightrope batch: --merge: %s\n", err.msg);
            return 2;
        }
        int lock = lock_knot(o->out, name);
        if (lock == -2)
            return 2;
        if (lock == -1) {
            if (!o->quiet)
                fprintf(stderr, "batch merge [%zu/%zu] %s: another batch process is running it, left\n", s + 1,
                        nsel, name);
            continue;
        }
        tr_merge_outcome how;
        char what[512];
        int rc = tr_batch_merge_knot(o->out, o->merge, name, start, &how, what, sizeof what, &err);
        close(lock);
        if (rc != TR_OK) {
            fprintf(stderr, "tightrope batch: --merge: %s\n", err.msg);
            return rc == TR_ENOMEM ? 1 : 2;
        }
        counts[how]++;
        if (how == TR_MERGE_OTHER_START) {
            fprintf(stderr, "tightrope batch: --merge: %s: %s\n", name, what);
            status = 2;
        } else if (!o->quiet)
            fprintf(stderr, "batch merge [%zu/%zu] %s: %s\n", s + 1, nsel, name, what);
    }
    if (!o->quiet)
        fprintf(stderr, "batch merge: %zu taken, %zu shorter, %zu kept, %zu not in %s\n", counts[TR_MERGE_TAKEN],
                counts[TR_MERGE_SHORTER], counts[TR_MERGE_KEPT], counts[TR_MERGE_ABSENT], o->merge);
    return status;
}

static void free_retry_options(batch_opts *o)
{
    for (int q = 0; q < o->nrecipes; q++) {
        for (int j = 0; j < o->nropts[q]; j++)
            free(o->ropts[q][j]);
        free(o->ropts[q]);
        o->ropts[q] = NULL;
        o->nropts[q] = 0;
    }
}

/* each --retry-options split into o->ropts (batch_manifest.h, as a
 * manifest's options are); -1 to go on, else the exit status. */
static int split_retry_options(batch_opts *o)
{
    for (int q = 0; q < o->nrecipes; q++) {
        char *text = strdup(o->retry_text[q]);
        int bad = !text || tr_batch_split_options(text, &o->ropts[q], &o->nropts[q]);
        free(text);
        if (bad) {
            fprintf(stderr, "tightrope batch: out of memory\n");
            free_retry_options(o);
            return 1;
        }
        for (int j = 0; j < o->nropts[q]; j++) {
            const char *why = tr_batch_reserved_option(o->ropts[q][j]);
            if (why) {
                fprintf(stderr, "tightrope batch: --retry-options %s: %s\n", o->ropts[q][j], why);
                free_retry_options(o);
                return 2;
            }
        }
    }
    return -1;
}

/* Runs tighten's own checks (tr_tighten_check_args) on one run's command
 * line and catches what they print: their one line, tighten's name taken
 * off, goes into msg, for batch to print in its own line, which says
 * where the options came from (a manifest's FILE:LINE, --retry-options).
 * Checking with tighten's parser, not a copy of its option table, keeps
 * the two from drifting apart. Returns 1 when the line passes. */
static int args_pass(const run_args *a, char *msg, size_t size)
{
    msg[0] = '\0';
    for (int j = 1; j < a->argc; j++)
        if (!strcmp(a->argv[j], "--help") || !strcmp(a->argv[j], "-h")) {
            snprintf(msg, size, "%s is no option of a run (tightrope tighten --help lists them)", a->argv[j]);
            return 0;
        }
    /* stderr into a pipe for the call (its write end non-blocking: a
     * message longer than the pipe holds is cut, never waited on) */
    int p[2], saved = -1, caught = 0;
    fflush(stderr);
    if (pipe(p) == 0) {
        saved = dup(STDERR_FILENO);
        caught = saved >= 0 && fcntl(p[1], F_SETFL, O_NONBLOCK) == 0 && dup2(p[1], STDERR_FILENO) >= 0;
        close(p[1]);
        if (!caught) {
            close(p[0]);
            if (saved >= 0)
                close(saved);
        }
    }
    int rc = tr_tighten_check_args(a->argc, a->argv);
    if (!caught)
        return rc < 0;
    fflush(stderr);
    dup2(saved, STDERR_FILENO);
    close(saved);
    clearerr(stderr);
    size_t got = 0;
    for (ssize_t r; got + 1 < size && (r = read(p[0], msg + got, size - 1 - got)) != 0;) {
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            break;
        got += (size_t)r;
    }
    close(p[0]);
    msg[got] = '\0';
    msg[strcspn(msg, "\n")] = '\0';
    static const char prefix[] = "tightrope tighten: ";
    if (!strncmp(msg, prefix, sizeof prefix - 1))
        memmove(msg, msg + sizeof prefix - 1, strlen(msg + sizeof prefix - 1) + 1);
    if (rc >= 0 && !msg[0])
        snprintf(msg, size, "tighten refuses these options (exit status %d)", rc);
    return rc < 0;
}

/* Whether the command lines of knot k's runs pass tighten's checks: the
 * run from its start and the one from its checkpoint (which leaves out
 * the start's options), a retry round's (recipe >= 0) with its own seed.
 * *msg gets tighten's message; *resumed says which failed. */
static int knot_args_pass(const batch_opts *o, const tr_batch_knot *k, int recipe, char *msg, size_t size,
                          int *resumed)
{
    long seed = recipe >= 0 ? base_seed(o, k) + 1 : -1;
    for (*resumed = 0; *resumed < 2; ++*resumed) {
        run_args a;
        /* --n and --refine-to take the same values: which one a run gives is
         * the start's affair; --list has no OUT, and a folder of no file
         * stands in for it (tighten compares the output with the input) */
        if (build_args(o, k, o->out ? o->out : "(no -o)", seed, recipe, *resumed, "--refine-to", &a)) {
            snprintf(msg, size, "out of memory");
            return 0;
        }
        int ok = args_pass(&a, msg, size);
        free(a.argv);
        if (!ok)
            return 0;
    }
    return 1;
}

/* Every knot's tighten options (the batch's after --, the manifest's,
 * each --retry-options with each knot it can retry: one with a reference
 * line) checked before anything runs or is written, so that a bad one is
 * one line naming where it came from, exit 2, and not the failure of a
 * knot an hour into the batch. Options that fail together but not apart
 * (--shuffles after -- with each line's --tries) are judged together:
 * what is blamed is what fails alone. Returns -1 to go on, else the exit
 * status. */
static int check_args(const batch_opts *o, const tr_batch_list *l, const tr_batch_ref *ref)
{
    char msg[1024], alone[1024], where[PATH_SIZE];
    int resumed, resumed_alone;
    /* the first knot's start and the batch's options, the manifest's left out */
    tr_batch_knot bare = l->knots[0];
    bare.n = 0;
    bare.opts = NULL;
    bare.nopts = 0;
    for (int q = -1; q < (o->retry > 0 ? o->nrecipes : 0); q++)
        for (size_t i = 0; i < l->count; i++) {
            const tr_batch_knot *k = &l->knots[i];
            if (q >= 0 && tr_batch_ref_find(ref, k->name) < 0)
                continue;
            if (knot_args_pass(o, k, q, msg, sizeof msg, &resumed))
                continue;
            const char *as = " (as a resumed run takes them)";
            if (!knot_args_pass(o, &bare, q, alone, sizeof alone, &resumed_alone)) {
                if (q < 0)
                    fprintf(stderr, "tightrope batch: the tighten options after --: %s%s\n", alone,
                            resumed_alone ? as : "");
                else
                    fprintf(stderr, "tightrope batch: --retry-options '%s': %s%s\n", o->retry_text[q], alone,
                            resumed_alone ? as : "");
                return 2;
            }
            knot_where(o, k, where, sizeof where);
            if (q < 0)
                fprintf(stderr, "tightrope batch: %s: %s%s\n", where, msg, resumed ? as : "");
            else
                fprintf(stderr, "tightrope batch: --retry-options '%s' with %s: %s%s\n", o->retry_text[q], where,
                        msg, resumed ? as : "");
            return 2;
        }
    return -1;
}

/* A file the batch reads, by identity (stat's device and inode). */
typedef struct batch_input {
    dev_t dev;
    ino_t ino;
    const char *path;
    const tr_batch_knot *k; /* whose start it is (a manifest line), or NULL */
    const char *what;       /* what it is when k is NULL, or --merge's */
} batch_input;

static int by_identity(const void *pa, const void *pb)
{
    const batch_input *a = pa, *b = pb;
    if (a->dev != b->dev)
        return a->dev < b->dev ? -1 : 1;
    return a->ino < b->ino ? -1 : a->ino > b->ino;
}

/* Appends path to in (sized for it) when it exists. */
static void add_input(batch_input *in, size_t *n, const char *path, const tr_batch_knot *k, const char *what)
{
    struct stat st;
    if (stat(path, &st) == 0)
        in[(*n)++] = (batch_input){.dev = st.st_dev, .ino = st.st_ino, .path = path, .k = k, .what = what};
}

/* The input that path is, or NULL (in sorted by identity). */
static const batch_input *input_at(const batch_input *in, size_t n, const char *path)
{
    struct stat st;
    if (stat(path, &st))
        return NULL;
    batch_input key = {.dev = st.st_dev, .ino = st.st_ino};
    return bsearch(&key, in, n, sizeof *in, by_identity);
}

/* Says that output path (what the batch writes there: owner's what) is
 * input hit; returns 2. */
static int collision(const batch_opts *o, const batch_input *hit, const char *path, const char *owner,
                     const char *what)
{
    char where[PATH_SIZE];
    if (hit->k && !hit->what) {
        /* a folder's knot is its file: the path says where it is */
        snprintf(where, sizeof where, "%s:%d: ", o->src, hit->k->line);
        fprintf(stderr, "tightrope batch: %sthe start %s of %s is the file this batch writes as %s%s%s (%s); "
                        "it would be lost: give another -o, or move the start out of %s\n",
                hit->k->line > 0 ? where : "", hit->path, hit->k->name, owner, owner[0] ? "'s " : "", what, path,
                o->out);
    } else
        fprintf(stderr, "tightrope batch: %s %s is the file this batch writes as %s%s%s (%s); it would be lost: "
                        "give another -o\n", hit->what, hit->path, owner, owner[0] ? "'s " : "", what, path);
    return 2;
}

/* No file the batch writes (for any knot of the manifest, selected or not:
 * its curve, checkpoint, record and start record in OUT and in every
 * OUT/retry-R, the start it makes of a knot by name in OUT/starts, and the
 * table) may be one it reads (a knot's start, the
 * manifest, --compare's table, --merge's files), else the batch would
 * write over it and, worse, go on to tighten and tabulate what it wrote:
 * refused before anything runs, one line naming the start's manifest
 * line. An output that does not exist yet is no input, which exists; one
 * that does is compared by identity (tr_same_file's device and inode),
 * which sees through ./, ../, symbolic and hard links alike. The lock
 * files are left out: opened, never written, they change nothing. Returns
 * -1 to go on, else the exit status. */
static int check_collisions(const batch_opts *o, const tr_batch_list *l, const size_t *sel, size_t nsel)
{
    static const char *exts[] = {"vect", "ckpt", "row.tsv", "start"};
    static const char *what[] = {"curve", "checkpoint", "record", "start record"};
    size_t nmerged = o->merge ? 2 * nsel : 0;
    char **merged = calloc(nmerged + 1, sizeof *merged);
    batch_input *in = malloc((l->count + 2 + nmerged) * sizeof *in);
    int oom = !in || !merged;
    for (size_t s = 0; !oom && s < nmerged; s++) {
        char path[PATH_SIZE];
        knot_path(path, sizeof path, o->merge, l->knots[sel[s / 2]].name, s % 2 ? "row.tsv" : "vect");
        oom = !(merged[s] = strdup(path));
    }
    if (oom) {
        for (size_t s = 0; merged && s < nmerged; s++)
            free(merged[s]);
        free(in);
        free(merged);
        fprintf(stderr, "tightrope batch: out of memory\n");
        return 1;
    }
    size_t n = 0;
    for (size_t i = 0; i < l->count; i++)
        if (l->knots[i].from == TR_BATCH_FROM_FILE)
            add_input(in, &n, l->knots[i].file, &l->knots[i], NULL);
    struct stat st;
    if (stat(o->src, &st) == 0 && !S_ISDIR(st.st_mode))
        add_input(in, &n, o->src, NULL, "the manifest");
    if (o->compare && strcmp(o->compare, TR_BATCH_REF_KNOTINFO))
        add_input(in, &n, o->compare, NULL, "--compare's table");
    for (size_t s = 0; s < nmerged; s++)
        add_input(in, &n, merged[s], &l->knots[sel[s / 2]], "--merge's");
    qsort(in, n, sizeof *in, by_identity);
    int status = -1;
    char path[PATH_SIZE], dir[PATH_SIZE / 2], whatr[64];
    const batch_input *hit;
    for (int t = 0; status < 0 && t < 2; t++) {
        snprintf(path, sizeof path, "%s/%s", o->out, t ? "table.json" : "table.tsv");
        if ((hit = input_at(in, n, path)))
            status = collision(o, hit, path, "", "its table");
    }
    for (long r = 0; status < 0 && r <= o->retry; r++) {
        int w = r == 0 ? snprintf(dir, sizeof dir, "%s", o->out)
                       : snprintf(dir, sizeof dir, "%s/retry-%ld", o->out, r);
        /* a folder's name cut short would be checked in another's place */
        if (w < 0 || (size_t)w >= sizeof dir) {
            fprintf(stderr, "tightrope batch: -o %s: the path is too long\n", o->out);
            status = 2;
            break;
        }
        /* nothing can be in a folder that is not there */
        if (r > 0 && access(dir, F_OK))
            continue;
        for (size_t i = 0; status < 0 && i < l->count; i++)
            for (size_t e = 0; status < 0 && e < sizeof exts / sizeof exts[0]; e++) {
                knot_path(path, sizeof path, dir, l->knots[i].name, exts[e]);
                if (!(hit = input_at(in, n, path)))
                    continue;
                if (r > 0)
                    snprintf(whatr, sizeof whatr, "retry %ld %s", r, what[e]);
                else
                    snprintf(whatr, sizeof whatr, "%s", what[e]);
                status = collision(o, hit, path, l->knots[i].name, whatr);
            }
    }
    /* the starts by name the batch makes, OUT/starts/NAME.vect */
    for (size_t i = 0; status < 0 && i < l->count; i++)
        if (l->knots[i].from != TR_BATCH_FROM_FILE && (hit = input_at(in, n, l->knots[i].file)))
            status = collision(o, hit, l->knots[i].file, l->knots[i].name, "start made by name");
    for (size_t s = 0; s < nmerged; s++)
        free(merged[s]);
    free(in);
    free(merged);
    return status;
}

int tr_cmd_batch(int argc, char **argv)
{
    batch_opts o;
    int status = parse_options(argc, argv, &o);
    if (status >= 0)
        return status;
    if ((status = split_retry_options(&o)) >= 0)
        return status;
    status = -1;
    tr_batch_list l;
    tr_batch_ref ref = {0};
    tr_error err;
    if (tr_batch_read(o.src, &l, &err)) {
        free_retry_options(&o);
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
        return 2;
    }
    if (tr_batch_place_named(&l, o.out ? o.out : "(no -o)")) {
        fprintf(stderr, "tightrope batch: out of memory\n");
        free_retry_options(&o);
        tr_batch_list_free(&l);
        return 1;
    }
    if (o.compare && (strcmp(o.compare, TR_BATCH_REF_KNOTINFO) ? tr_batch_ref_read(o.compare, &ref, &err)
                                                                : tr_batch_ref_knotinfo(&l, &ref, &err))) {
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
        free_retry_options(&o);
        tr_batch_list_free(&l);
        return 2;
    }
    size_t *sel = malloc(l.count * sizeof *sel), nsel = 0;
    for (size_t i = 0; sel && i < l.count; i++)
        if (selected(&o, &l, i)) {
            if (l.knots[i].n > 0 && topts_set_n(&o)) {
                fprintf(stderr, "tightrope batch: %s:%d gives N %ld and the options after -- give --n or "
                                "--refine-to; give one of them\n", o.src, l.knots[i].line, l.knots[i].n);
                status = 2;
                break;
            }
            sel[nsel++] = i;
        }
    if (!sel) {
        fprintf(stderr, "tightrope batch: out of memory\n");
        status = 1;
    } else if (status < 0 && o.only && nsel == 0) {
        fprintf(stderr, "tightrope batch: no knot '%s' in %s (tightrope batch %s --list names them)\n", o.only,
                o.src, o.src);
        status = 2;
    } else if (status < 0 && !o.list && (status = check_collisions(&o, &l, sel, nsel)) >= 0) {
        /* said */
    } else if (status < 0 && (status = check_args(&o, &l, &ref)) >= 0) {
        /* said */
    } else if (status < 0 && o.list) {
        for (size_t s = 0; s < nsel; s++)
            printf("%s\n", l.knots[sel[s]].name);
        status = 0;
    } else if (status < 0 && o.merge && !is_folder(o.merge, "--merge")) {
        status = 2;
    } else if (status < 0 && o.merge && (status = merge_check(&o, &l, sel, nsel)) >= 0) {
        /* said */
    } else if (status < 0 && o.table_only && access(o.out, F_OK)) {
        fprintf(stderr, "tightrope batch: --table-only: no output folder %s: %s\n", o.out, strerror(errno));
        status = 2;
    } else if (status < 0 && mkdir(o.out, 0777) && errno != EEXIST) {
        fprintf(stderr, "tightrope batch: cannot make the output folder %s: %s\n", o.out, strerror(errno));
        status = 2;
    }
    if (status < 0) {
        status = o.table_only ? 0 : o.merge ? merge_all(&o, &l, sel, nsel) : run_all(&o, &l, sel, nsel, &ref);
        size_t rows = 0;
        int ts = write_table(&o, &l, o.compare ? &ref : NULL, &rows);
        if (ts > status)
            status = ts;
        if (!o.quiet)
            fprintf(stderr, "batch: %s/table.tsv holds %zu of the %zu knots of %s\n", o.out, rows, l.count, o.src);
    }
    free(sel);
    free_retry_options(&o);
    tr_batch_ref_free(&ref);
    tr_batch_list_free(&l);
    return status;
}
