/* tightrope batch SRC -o OUT [options] [-- tighten options]
 *
 * Tightens every knot of a manifest or a folder (batch_manifest.h) with
 * tighten's own code (tr_tighten_command, in this process: the same
 * checks, certificate and output as `tightrope tighten`), one after the
 * other, into OUT: NAME.vect (the tight curve, its certificate in
 * comments), NAME.ckpt while it runs, NAME.row.tsv once it is done
 * (batch_row.h), and the table of every knot done, table.tsv and
 * table.json (batch_table.h). A knot with a record is skipped and one with
 * a checkpoint resumes from it, so a batch killed at any moment is started
 * again with the same command. Scale-out is left to existing engines:
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

#include "cli/batch_manifest.h"
#include "cli/batch_merge.h"
#include "cli/batch_row.h"
#include "cli/batch_table.h"
#include "cli/cli.h"
#include "cli/cli_args.h"
#include "curve/curve.h"
#include "curve/curve_io.h"
#include "util/clock.h"
#include "util/text_file.h"

static void usage(FILE *out)
{
    fprintf(out,
            "usage: tightrope batch SRC -o OUT [options] [-- TIGHTEN-OPTIONS...]\n"
            "  SRC                a folder of curve files (.vect, .tsv, .txt, .dat, .knot; each knot\n"
            "                     named by its file without the extension) or a manifest: lines\n"
            "                     name<TAB>file<TAB>N<TAB>options ('#' comments; file relative to\n"
            "                     the manifest; N the vertices per component of the tight curve,\n"
            "                     tighten --refine-to N, or --n N for a start with more, '-' none;\n"
            "                     options: tighten's, space-separated, for this knot)\n"
            "  -o, --out OUT      output folder: NAME.vect (tight curve and certificate), NAME.ckpt\n"
            "                     (while it runs), NAME.row.tsv (done), table.tsv and table.json\n"
            "  --only NAME        this knot only (GNU parallel: one job per name of --list)\n"
            "  --job I --jobs J   the knots at places I, I+J, I+2J, ... of SRC (0 <= I < J):\n"
            "                     one of J independent jobs (a SLURM array, scripts/slurm_batch.sh)\n"
            "  --list             print the selected knots' names, one a line, and tighten nothing\n"
            "  --table-only       tighten nothing: rebuild the table from the knots done in OUT\n"
            "  --merge OTHER      tighten nothing: take each selected knot's result from OTHER (a batch\n"
            "                     output folder of the same knots, e.g. another --seed) where OUT has\n"
            "                     none or OTHER's is shorter at the same N; then rebuild the table\n"
            "  --compare REF      add a reference table's N and ropelength (a TSV with a header: knot\n"
            "                     name first, a column 'ropelength...'; '.' and '_' match in names)\n"
            "                     and the difference, ours - reference, absolute and in %%\n"
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
            "TIGHTEN-OPTIONS go to every knot (before the manifest's own), e.g. -- --scale --time-limit 120;\n"
            "batch sets -o, --checkpoint, --checkpoint-every, --resume and --json itself.\n"
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
 * continues the road that was interrupted, so --tries and --seed go too. */
static int start_only(char **opts, int j)
{
    if (!strcmp(opts[j], "--scale"))
        return 1;
    return !strcmp(opts[j], "--n") || !strcmp(opts[j], "--tries") || !strcmp(opts[j], "--seed") ? 2 : 0;
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

/* Runs tighten on knot k (or resumes it) into folder dir, with --seed
 * seed and the retry options of recipe (o->ropts) where seed >= 0, and
 * writes its record. Returns tighten's exit
 * status, or 2 when the record cannot be written; *rep says what the run
 * came to. */
static int run_knot(const batch_opts *o, const tr_batch_knot *k, const char *dir, long seed, int recipe,
                    tr_tighten_report *rep)
{
    int own_seed = seed >= 0, has_recipe = own_seed && recipe >= 0 && recipe < o->nrecipes;
    char **ropts = has_recipe ? o->ropts[recipe] : NULL;
    int nropts = has_recipe ? o->nropts[recipe] : 0;
    char vect[PATH_SIZE], ckpt[PATH_SIZE], row[PATH_SIZE], nbuf[32], every[32], sbuf[32];
    knot_path(vect, sizeof vect, dir, k->name, "vect");
    knot_path(ckpt, sizeof ckpt, dir, k->name, "ckpt");
    knot_path(row, sizeof row, dir, k->name, "row.tsv");
    int resume = exists(ckpt);
    char **args = malloc((size_t)(16 + o->ntopts + k->nopts + nropts) * sizeof *args);
    if (!args) {
        fprintf(stderr, "tightrope batch: out of memory\n");
        return 1;
    }
    int na = 0;
    args[na++] = "tighten";
    if (resume) {
        args[na++] = "--resume";
        args[na++] = ckpt;
    } else {
        args[na++] = k->file;
    }
    snprintf(every, sizeof every, "%g", o->ckpt_every);
    char *fixed[] = {"-o", vect, "--checkpoint", ckpt, "--checkpoint-every", every, "--quiet"};
    for (size_t j = 0; j < sizeof fixed / sizeof fixed[0]; j++)
        args[na++] = fixed[j];
    tr_error err;
    int rc = TR_OK;
    if (k->n > 0) {
        const char *opt = n_option(k, resume, &err, &rc);
        if (rc != TR_OK) {
            fprintf(stderr, "tightrope batch: %s: %s\n", k->name, err.msg);
            free(args);
            *rep = (tr_tighten_report){0};
            return rc == TR_ENOMEM ? 1 : 2;
        }
        snprintf(nbuf, sizeof nbuf, "%ld", k->n);
        args[na++] = (char *)opt;
        args[na++] = nbuf;
    }
    /* a retry's own options replace the same options of the batch's and the knot's */
    add_opts(args, &na, o->topts, o->ntopts, resume, own_seed, ropts, nropts);
    add_opts(args, &na, k->opts, k->nopts, resume, own_seed, ropts, nropts);
    if (own_seed)
        add_opts(args, &na, ropts, nropts, resume, own_seed, NULL, 0);
    if (own_seed && !resume) {
        snprintf(sbuf, sizeof sbuf, "%ld", seed);
        args[na++] = "--seed";
        args[na++] = sbuf;
    }
    args[na] = NULL;
    int status = tr_tighten_command(na, args, rep);
    free(args);
    if (!rep->written || rep->interrupted) {
        if (resume && !rep->written)
            fprintf(stderr, "tightrope batch: %s: resuming from %s failed; remove it to start the knot afresh\n",
                    k->name, ckpt);
        return status;
    }
    tr_batch_row r = {.n = rep->n, .ropelength = rep->ropelength, .thickness = rep->thickness,
                      .minrad = rep->minrad, .dcsd = rep->dcsd, .kkt_residual = rep->kkt_residual,
                      .time_s = rep->elapsed, .tries = rep->tries, .steps = rep->steps, .resumed = resume,
                      .seed = rep->seed, .road = rep->road};
    snprintf(r.knot, sizeof r.knot, "%s", k->name);
    snprintf(r.stop, sizeof r.stop, "%s", rep->stop);
    /* the record last: with it the knot is done, and its checkpoint is
     * no longer needed */
    if (tr_batch_row_write(row, &r, &err)) {
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
        return 2;
    }
    unlink(ckpt);
    return status;
}

/* Rebuilds OUT/table.* from the records of the knots of l (in l's order),
 * under an exclusive lock on OUT/.batch.lock, so that of several jobs
 * finishing at once the last to write has read every record. */
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
        if (tr_batch_row_read(row, &rows[n], &err) == TR_OK)
            n++;
        else {
            fprintf(stderr, "tightrope batch: %s\n", err.msg);
            status = 2;
        }
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
static int retry_knot(const batch_opts *o, const tr_batch_knot *k, const tr_batch_ref *ref, batch_progress *p)
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
        if (!exists(rrow)) {
            int recipe = o->nrecipes > 0 ? (int)((r - 1) % o->nrecipes) : -1;
            int at = snprintf(what, sizeof what, "%.6f is above the reference's %.6f: retry %ld of %ld, seed %ld",
                              cur.ropelength, target, r, o->retry, base + r);
            if (recipe >= 0 && at > 0 && (size_t)at < sizeof what)
                snprintf(what + at, sizeof what - (size_t)at, ", %s", o->retry_text[recipe]);
            progress_line(o, p, k->name, "%s", what);
            double t = tr_clock_seconds();
            tr_tighten_report rep;
            int rc = run_knot(o, k, dir, base + r, recipe, &rep);
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
        int mc = tr_batch_merge_knot(o->out, dir, k->name, &how, merged, sizeof merged, &err);
        if (mc != TR_OK) {
            fprintf(stderr, "tightrope batch: %s\n", err.msg);
            return mc == TR_ENOMEM ? 1 : 2;
        }
        snprintf(what, sizeof what, "retry %ld: %s", r, merged);
        progress_line(o, p, k->name, "%s", what);
    }
    return 0;
}

/* Tightens knot k (or resumes it) into OUT, with its progress lines.
 * Returns 0 done (*done = 1), -1 interrupted (the run keeps its
 * checkpoint), or the exit status of a failed run (1 or 2). */
static int tighten_one(const batch_opts *o, const tr_batch_knot *k, batch_progress *p, int *done)
{
    char ckpt[PATH_SIZE], what[160];
    knot_path(ckpt, sizeof ckpt, o->out, k->name, "ckpt");
    progress_line(o, p, k->name, "%s", exists(ckpt) ? "resuming from its checkpoint" : "tightening");
    double t = tr_clock_seconds();
    tr_tighten_report rep;
    int rc = run_knot(o, k, o->out, -1, -1, &rep);
    if (rep.interrupted || tr_tighten_stop_requested()) {
        if (!o->quiet && rep.interrupted)
            fprintf(stderr, "batch: interrupted; %s resumes from its checkpoint when the batch is run again\n",
                    k->name);
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

/* Tightens the selected knots in turn (and retries them: --retry).
 * Returns the exit status. */
static int run_all(const batch_opts *o, const tr_batch_list *l, const size_t *sel, size_t nsel, const tr_batch_ref *ref)
{
    batch_progress p = {.total = nsel, .t0 = tr_clock_seconds()};
    int status = 0;
    for (size_t s = 0; s < nsel; s++) {
        const tr_batch_knot *k = &l->knots[sel[s]];
        char row[PATH_SIZE], ckpt[PATH_SIZE];
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
        int done = exists(row), rc_run;
        if (done) {
            /* a run killed between its record and the checkpoint's removal */
            unlink(ckpt);
            p.skipped++;
            progress_line(o, &p, k->name, "%s", "done before, skipped");
        } else if ((rc_run = tighten_one(o, k, &p, &done)) != 0) {
            close(lock);
            if (rc_run < 0)
                return 1;
            status = rc_run == 2 || status == 2 ? 2 : 1;
            continue;
        }
        /* a knot done here or before: retried while above its reference */
        int rs = done && o->retry > 0 ? retry_knot(o, k, ref, &p) : 0;
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

/* --merge: each selected knot's result from o->merge where it is shorter
 * (batch_merge.h), under the knot's lock. Returns the exit status. */
static int merge_all(const batch_opts *o, const tr_batch_list *l, const size_t *sel, size_t nsel)
{
    if (tr_same_file(o->merge, o->out)) {
        fprintf(stderr, "tightrope batch: --merge %s is the output folder itself\n", o->merge);
        return 2;
    }

    size_t counts[4] = {0};
    for (size_t s = 0; s < nsel; s++) {
        const char *name = l->knots[sel[s]].name;
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
        tr_error err;
        int rc = tr_batch_merge_knot(o->out, o->merge, name, &how, what, sizeof what, &err);
        close(lock);
        if (rc != TR_OK) {
            fprintf(stderr, "tightrope batch: --merge: %s\n", err.msg);
            return rc == TR_ENOMEM ? 1 : 2;
        }
        counts[how]++;
        if (!o->quiet)
            fprintf(stderr, "batch merge [%zu/%zu] %s: %s\n", s + 1, nsel, name, what);
    }
    if (!o->quiet)
        fprintf(stderr, "batch merge: %zu taken, %zu shorter, %zu kept, %zu not in %s\n", counts[TR_MERGE_TAKEN],
                counts[TR_MERGE_SHORTER], counts[TR_MERGE_KEPT], counts[TR_MERGE_ABSENT], o->merge);
    return 0;
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
    if (o.compare && tr_batch_ref_read(o.compare, &ref, &err)) {
        fprintf(stderr, "tightrope batch: %s\n", err.msg);
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
    } else if (status < 0 && o.list) {
        for (size_t s = 0; s < nsel; s++)
            printf("%s\n", l.knots[sel[s]].name);
        status = 0;
    } else if (status < 0 && o.merge && !is_folder(o.merge, "--merge")) {
        status = 2;
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
