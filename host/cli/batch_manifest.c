/* The batch's list of knots: a manifest's lines or a folder's curve files
 * (batch_manifest.h). */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/batch_manifest.h"
#include "cli/cli_args.h"
#include "topology/knot_table.h"
#include "util/text_file.h"

const char *tr_batch_reserved_option(const char *opt)
{
    /* batch names the output, the checkpoint and what goes to stdout of
     * every run; an option of its own would contradict or duplicate them */
    static const char *reserved[] = {"-o", "--output", "--checkpoint", "--checkpoint-every", "--resume", "--json"};
    for (size_t i = 0; i < sizeof reserved / sizeof reserved[0]; i++)
        if (!strcmp(opt, reserved[i]))
            return "batch sets it for every knot (the output folder, checkpoints: see tightrope batch --help)";
    return NULL;
}

int tr_batch_name_ok(const char *name)
{
    size_t len = strlen(name);
    if (len == 0 || len > TR_BATCH_NAME_MAX || name[0] == '.' || name[0] == '-')
        return 0;
    for (size_t i = 0; i < len; i++)
        if (!isalnum((unsigned char)name[i]) && !strchr("._+-", name[i]))
            return 0;
    return 1;
}

void tr_batch_list_free(tr_batch_list *l)
{
    for (size_t i = 0; i < l->count; i++) {
        tr_batch_knot *k = &l->knots[i];
        free(k->name);
        free(k->file);
        free(k->source);
        free(k->notation);
        for (int j = 0; j < k->nopts; j++)
            free(k->opts[j]);
        free(k->opts);
    }
    free(l->knots);
    *l = (tr_batch_list){0};
}

/* Appends a zeroed knot to l; NULL when out of memory. */
static tr_batch_knot *add_knot(tr_batch_list *l)
{
    tr_batch_knot *k = realloc(l->knots, (l->count + 1) * sizeof *k);
    if (!k)
        return NULL;
    l->knots = k;
    k = &l->knots[l->count++];
    *k = (tr_batch_knot){0};
    return k;
}

/* The index of the knot called name among the first `count` of l, or -1. */
static long find_name(const tr_batch_list *l, size_t count, const char *name)
{
    for (size_t i = 0; i < count; i++)
        if (!strcmp(l->knots[i].name, name))
            return (long)i;
    return -1;
}

int tr_batch_split_options(char *field, char ***opts, int *nopts)
{
    char *save = NULL;
    for (char *tok = strtok_r(field, " \t", &save); tok; tok = strtok_r(NULL, " \t", &save)) {
        char **o = realloc(*opts, (size_t)(*nopts + 1) * sizeof *o);
        if (!o)
            return -1;
        *opts = o;
        if (!((*opts)[*nopts] = strdup(tok)))
            return -1;
        (*nopts)++;
    }
    return 0;
}

/* The start's path as the manifest gives it, relative to the manifest's
 * folder, so that a manifest and its curves move together. */
static char *start_path(const char *manifest, const char *file)
{
    const char *slash = strrchr(manifest, '/');
    if (file[0] == '/' || !slash) {
        return strdup(file);
    }
    size_t dl = (size_t)(slash - manifest) + 1, fl = strlen(file);
    char *p = malloc(dl + fl + 1);
    if (p) {
        memcpy(p, manifest, dl);
        memcpy(p + dl, file, fl + 1);
    }
    return p;
}

/* Checks one knot of a manifest line: its N against its options, its
 * options against batch's own, its start against the file system. */
static int check_knot(const char *src, const tr_batch_knot *k, tr_error *err)
{
    for (int j = 0; j < k->nopts; j++) {
        const char *why = tr_batch_reserved_option(k->opts[j]);
        if (why)
            return tr_fail(err, TR_EPARSE, "%s:%d: option %s: %s", src, k->line, k->opts[j], why);
        if (k->n > 0 && (!strcmp(k->opts[j], "--n") || !strcmp(k->opts[j], "--refine-to")))
            return tr_fail(err, TR_EPARSE, "%s:%d: N is %ld and the options give %s too; give one of them",
                           src, k->line, k->n, k->opts[j]);
    }
    if (k->from == TR_BATCH_FROM_FILE && access(k->file, R_OK) != 0)
        return tr_fail(err, TR_EPARSE, "%s:%d: start %s: %s", src, k->line, k->file, strerror(errno));
    return TR_OK;
}

/* The embedded knot table, loaded when a manifest's first start by name
 * is read (a manifest of files never parses it). */
typedef struct named_table {
    tr_knot_table t;
    int loaded;
} named_table;

/* Which start a file field names: TR_BATCH_FROM_KNOT or _LINK with *name
 * pointing at the name (after `knot ` or `knot:`; may be empty), or
 * TR_BATCH_FROM_FILE. A bare `knot` or `link` is a start by name without
 * one (refused by the caller), never a file so called: ./knot is. */
static tr_batch_start_kind start_kind(char *field, char **name)
{
    static const char *words[] = {"knot", "link"};
    for (int w = 0; w < 2; w++) {
        size_t len = strlen(words[w]);
        if (strncmp(field, words[w], len) || (field[len] && field[len] != ' ' && field[len] != ':'))
            continue;
        char *p = field + len;
        if (*p == ':')
            p++;
        while (*p == ' ')
            p++;
        size_t n = strlen(p);
        while (n > 0 && p[n - 1] == ' ')
            p[--n] = '\0';
        *name = p;
        return w ? TR_BATCH_FROM_LINK : TR_BATCH_FROM_KNOT;
    }
    return TR_BATCH_FROM_FILE;
}

/* Looks a start by name up in the table: k->source and k->notation from
 * its entry, or the line's error (no name, an unknown one with the nearest,
 * a link's name given as a knot's or the other way round). */
static int name_start(const char *src, int lineno, tr_batch_knot *k, const char *name, named_table *nt,
                      tr_error *err)
{
    int is_link = k->from == TR_BATCH_FROM_LINK;
    const char *kind = is_link ? "link" : "knot";
    if (!name[0])
        return tr_fail(err, TR_EPARSE, "%s:%d: '%s' names no %s (%s NAME, e.g. %s; a file so called: ./%s)", src,
                       lineno, kind, kind, kind, is_link ? "link L2a1" : "knot 3_1", kind);
    if (!nt->loaded) {
        tr_error sub;
        if (tr_knot_table_load(&nt->t, &sub))
            return tr_fail(err, TR_EPARSE, "the embedded knot table: %s", sub.msg);
        nt->loaded = 1;
    }
    const tr_table_entry *e = tr_knot_table_find(&nt->t, name, is_link);
    if (!e) {
        const tr_table_entry *other = tr_knot_table_find(&nt->t, name, !is_link);
        if (other)
            return tr_fail(err, TR_EPARSE, "%s:%d: %s is a %s, not a %s (%s %s)", src, lineno, other->name,
                           is_link ? "knot" : "link", kind, is_link ? "knot" : "link", other->name);
        char near[256];
        tr_knot_table_suggest(&nt->t, name, is_link, near, sizeof near);
        return tr_fail(err, TR_EPARSE, "%s:%d: no %s named '%s' in %s; nearest: %s", src, lineno, kind, name,
                       is_link ? "LinkInfo's table (prime links to 9 crossings, L2a1 ... L9n28)"
                               : "KnotInfo's table (prime knots to 12 crossings, 0_1, 3_1 ... 10_165, 11a_1 ... "
                                 "12n_888)",
                       near);
    }
    /* the identity of the start is what it is made from: the name and its
     * braid word, the same on every machine and for every build */
    tr_text t = {0};
    tr_text_printf(&t, "braid on %d strands:", e->braid.strands);
    for (int j = 0; j < e->braid.len; j++)
        tr_text_printf(&t, "%s%d", j ? "," : " ", e->braid.word[j]);
    if (e->braid.len == 0)
        tr_text_printf(&t, " none (the unknot: a circle)");
    size_t sl = strlen(kind) + strlen(e->name) + 2;
    if (!(k->notation = tr_text_take(&t, NULL)) || !(k->source = malloc(sl)))
        return tr_fail(err, TR_ENOMEM, "out of memory");
    snprintf(k->source, sl, "%s:%s", kind, e->name);
    return TR_OK;
}

/* Parses manifest line `line` (text, tabs) into a new knot of l. */
static int parse_line(const char *src, int lineno, char *line, tr_batch_list *l, named_table *nt, tr_error *err)
{
    char *field[5] = {0};
    int nf = 0;
    for (char *p = line; nf < 5;) {
        field[nf++] = p;
        char *tab = strchr(p, '\t');
        if (!tab)
            break;
        *tab = '\0';
        p = tab + 1;
    }
    if (nf > 4)
        return tr_fail(err, TR_EPARSE, "%s:%d: more than 4 tab-separated fields (name, file, N, options)", src,
                       lineno);
    if (nf < 2 || !field[1][0])
        return tr_fail(err, TR_EPARSE, "%s:%d: expected name<TAB>file[<TAB>N[<TAB>options]]", src, lineno);
    if (!tr_batch_name_ok(field[0]))
        return tr_fail(err, TR_EPARSE,
                       "%s:%d: bad name '%s' (letters, digits and ._+- only, not first . or -, at most %d)", src,
                       lineno, field[0], TR_BATCH_NAME_MAX);
    long prev = find_name(l, l->count, field[0]);
    if (prev >= 0)
        return tr_fail(err, TR_EPARSE, "%s:%d: name '%s' already given on line %d", src, lineno, field[0],
                       l->knots[prev].line);
    long n = 0;
    if (nf > 2 && field[2][0] && strcmp(field[2], "-") && tr_arg_long(field[2], 4, 100000000, &n))
        return tr_fail(err, TR_EPARSE, "%s:%d: bad N '%s' (an integer >= 4, vertices per component, or -)", src,
                       lineno, field[2]);
    char *named = NULL;
    tr_batch_start_kind from = start_kind(field[1], &named);
    tr_batch_knot *k = add_knot(l);
    if (!k || !(k->name = strdup(field[0])) ||
        (from == TR_BATCH_FROM_FILE && !(k->file = start_path(src, field[1]))) ||
        (nf > 3 && tr_batch_split_options(field[3], &k->opts, &k->nopts)))
        return tr_fail(err, TR_ENOMEM, "out of memory");
    k->from = from;
    k->n = n;
    k->line = lineno;
    int rc = from == TR_BATCH_FROM_FILE ? TR_OK : name_start(src, lineno, k, named, nt, err);
    return rc ? rc : check_knot(src, k, err);
}

static int read_manifest(const char *src, tr_batch_list *l, tr_error *err)
{
    char *text;
    int rc = tr_read_text_file(src, &text, NULL, err);
    if (rc != TR_OK)
        return rc;
    int lineno = 0, seen = 0;
    named_table nt = {0};
    /* a UTF-8 byte-order mark (a Windows editor's) is no part of the first name */
    char *first = !strncmp(text, "\xef\xbb\xbf", 3) ? text + 3 : text;
    for (char *line = first, *next; rc == TR_OK && line; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = '\0';
        lineno++;
        size_t len = strlen(line);
        while (len > 0 && (line[len - 1] == '\r' || line[len - 1] == ' '))
            line[--len] = '\0';
        if (len == 0 || line[0] == '#')
            continue;
        /* a header names its first column "name" */
        if (!seen++ && !strncmp(line, "name\t", 5))
            continue;
        rc = parse_line(src, lineno, line, l, &nt, err);
    }
    free(text);
    if (nt.loaded)
        tr_knot_table_free(&nt.t);
    if (rc == TR_OK && l->count == 0)
        rc = tr_fail(err, TR_EPARSE, "%s: no knots (lines name<TAB>file[<TAB>N[<TAB>options]])", src);
    return rc;
}

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* The extension of a curve file tighten reads by name, or NULL. */
static const char *curve_ext(const char *name)
{
    static const char *exts[] = {".vect", ".tsv", ".txt", ".dat", ".knot"};
    const char *dot = strrchr(name, '.');
    for (size_t i = 0; dot && i < sizeof exts / sizeof exts[0]; i++)
        if (!strcmp(dot, exts[i]))
            return dot;
    return NULL;
}

/* The sorted names of the curve files in dir (regular files only). */
static int list_dir(const char *dir, char ***names, size_t *count, tr_error *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return tr_fail(err, TR_EIO, "%s: %s", dir, strerror(errno));
    int rc = TR_OK;
    *names = NULL;
    *count = 0;
    for (struct dirent *de; rc == TR_OK && (de = readdir(d));) {
        if (de->d_name[0] == '.' || !curve_ext(de->d_name))
            continue;
        char path[4096];
        struct stat st;
        if (snprintf(path, sizeof path, "%s/%s", dir, de->d_name) >= (int)sizeof path || stat(path, &st) ||
            !S_ISREG(st.st_mode))
            continue;
        char **nn = realloc(*names, (*count + 1) * sizeof *nn);
        if (!nn || !(nn[*count] = strdup(de->d_name))) {
            if (nn)
                *names = nn;
            rc = tr_fail(err, TR_ENOMEM, "out of memory");
            break;
        }
        *names = nn;
        (*count)++;
    }
    closedir(d);
    if (rc == TR_OK && *count > 1)
        qsort(*names, *count, sizeof **names, by_name);
    return rc;
}

static int read_dir(const char *dir, tr_batch_list *l, tr_error *err)
{
    char **names;
    size_t count;
    int rc = list_dir(dir, &names, &count, err);
    for (size_t i = 0; rc == TR_OK && i < count; i++) {
        size_t stem = (size_t)(curve_ext(names[i]) - names[i]);
        tr_batch_knot *k = add_knot(l);
        if (!k || !(k->name = strndup(names[i], stem)) || !(k->file = malloc(strlen(dir) + strlen(names[i]) + 2))) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory");
            break;
        }
        sprintf(k->file, "%s/%s", dir, names[i]);
        long prev = find_name(l, l->count - 1, k->name);
        if (prev >= 0)
            rc = tr_fail(err, TR_EINVAL, "%s: %s and %s both name the knot '%s'; rename one or use a manifest",
                         dir, l->knots[prev].file, k->file, k->name);
        else if (!tr_batch_name_ok(k->name))
            rc = tr_fail(err, TR_EINVAL,
                         "%s: the file name %s is no knot name (letters, digits and ._+- only); use a manifest",
                         dir, names[i]);
    }
    for (size_t i = 0; i < count; i++)
        free(names[i]);
    free(names);
    if (rc == TR_OK && l->count == 0)
        rc = tr_fail(err, TR_EINVAL, "%s: no curve files (.vect, .tsv, .txt, .dat, .knot)", dir);
    return rc;
}

int tr_batch_place_named(tr_batch_list *l, const char *out)
{
    for (size_t i = 0; i < l->count; i++) {
        tr_batch_knot *k = &l->knots[i];
        if (k->from == TR_BATCH_FROM_FILE)
            continue;
        size_t len = strlen(out) + strlen(TR_BATCH_STARTS_DIR) + strlen(k->name) + 8;
        char *p = malloc(len);
        if (!p)
            return -1;
        snprintf(p, len, "%s/%s/%s.vect", out, TR_BATCH_STARTS_DIR, k->name);
        free(k->file);
        k->file = p;
    }
    return 0;
}

int tr_batch_read(const char *src, tr_batch_list *out, tr_error *err)
{
    *out = (tr_batch_list){0};
    struct stat st;
    if (stat(src, &st))
        return tr_fail(err, TR_EIO, "%s: %s", src, strerror(errno));
    int rc = S_ISDIR(st.st_mode) ? read_dir(src, out, err) : read_manifest(src, out, err);
    if (rc != TR_OK)
        tr_batch_list_free(out);
    return rc;
}
