/* The batch table's line of one knot and its record file (batch_row.h). */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/batch_row.h"
#include "cli/cli_args.h"
#include "util/json.h"

#define NCOLS 17
/* the records of before: without source and type_check (15), without the
 * start (14), without seed and road (12) */
static const int NCOLS_OLD[] = {15, 14, 12};

static const char header[] = "knot\tN\tropelength\tthickness\tMinRad\tdcsd\tkkt_residual\ttime_s\ttries\tsteps\tstop"
                             "\tresumed\tseed\troad\tstart\tsource\ttype_check";

/* The type_check column's words, by tr_batch_row.type_checked + 1. */
static const char *const type_words[] = {"-", "unchecked", "kept"};

const char *tr_batch_row_header(void) { return header; }

/* A number of the table: the format's digits, or '-' where there is none. */
static void num(tr_text *t, const char *fmt, double v)
{
    if (isfinite(v))
        tr_text_printf(t, fmt, v);
    else
        tr_text_printf(t, "-");
}

/* A count known from least on, else the text for unknown. */
static void known(tr_text *t, long v, long least, const char *unknown)
{
    if (v >= least)
        tr_text_printf(t, "%ld", v);
    else
        tr_text_printf(t, "%s", unknown);
}

void tr_batch_row_format(tr_text *t, const tr_batch_row *r)
{
    /* ropelength to 10 decimals, as the TightKnot table; the record is read
     * back from this text, so the table shows what the record holds */
    tr_text_printf(t, "%s\t%zu\t", r->knot, r->n);
    num(t, "%.10f", r->ropelength);
    tr_text_printf(t, "\t");
    num(t, "%.12f", r->thickness);
    tr_text_printf(t, "\t");
    num(t, "%.12f", r->minrad);
    tr_text_printf(t, "\t");
    num(t, "%.12f", r->dcsd);
    tr_text_printf(t, "\t");
    num(t, "%.3e", r->kkt_residual);
    tr_text_printf(t, "\t");
    num(t, "%.2f", r->time_s);
    tr_text_printf(t, "\t%d\t%ld\t%s\t%d\t", r->tries, r->steps, r->stop, r->resumed);
    known(t, r->seed, 0, "-");
    tr_text_printf(t, "\t");
    known(t, r->road, 1, "-");
    tr_text_printf(t, "\t%s", r->start[0] ? r->start : "-");
    tr_text_printf(t, "\t%s\t%s", r->source[0] ? r->source : "-", type_words[r->type_checked + 1]);
}

void tr_batch_row_json_fields(tr_text *t, const tr_batch_row *r)
{
    tr_text_printf(t, "\"knot\": ");
    tr_json_string(t, r->knot);
    tr_text_printf(t, ", \"N\": %zu, \"ropelength\": ", r->n);
    tr_json_number(t, "%.10f", r->ropelength);
    tr_text_printf(t, ", \"thickness\": ");
    tr_json_number(t, "%.12f", r->thickness);
    tr_text_printf(t, ", \"MinRad\": ");
    tr_json_number(t, "%.12f", r->minrad);
    tr_text_printf(t, ", \"dcsd\": ");
    tr_json_number(t, "%.12f", r->dcsd);
    tr_text_printf(t, ", \"kkt_residual\": ");
    tr_json_number(t, "%.3e", r->kkt_residual);
    tr_text_printf(t, ", \"time_s\": ");
    tr_json_number(t, "%.2f", r->time_s);
    tr_text_printf(t, ", \"tries\": %d, \"steps\": %ld, \"stop\": ", r->tries, r->steps);
    tr_json_string(t, r->stop);
    tr_text_printf(t, ", \"resumed\": %s, \"seed\": ", r->resumed ? "true" : "false");
    known(t, r->seed, 0, "null");
    tr_text_printf(t, ", \"road\": ");
    known(t, r->road, 1, "null");
    tr_text_printf(t, ", \"start\": ");
    if (r->start[0])
        tr_json_string(t, r->start);
    else
        tr_text_printf(t, "null");
    tr_text_printf(t, ", \"source\": ");
    if (r->source[0])
        tr_json_string(t, r->source);
    else
        tr_text_printf(t, "null");
    tr_text_printf(t, ", \"type_check\": ");
    if (r->type_checked >= 0)
        tr_json_string(t, type_words[r->type_checked + 1]);
    else
        tr_text_printf(t, "null");
}

int tr_batch_row_write(const char *path, const tr_batch_row *r, tr_error *err)
{
    tr_text t = {0};
    tr_text_printf(&t, "%s\n", header);
    tr_batch_row_format(&t, r);
    tr_text_printf(&t, "\n");
    return tr_text_write_atomic(&t, path, err);
}

/* A number field: '-' is NAN. */
static int field_double(const char *s, double *v)
{
    if (!strcmp(s, "-")) {
        *v = NAN;
        return 0;
    }
    return tr_arg_double(s, -HUGE_VAL, HUGE_VAL, v);
}

/* An optional count: '-' is unknown (-1). */
static int field_long(const char *s, long max, long *v)
{
    if (!strcmp(s, "-")) {
        *v = -1;
        return 0;
    }
    return tr_arg_long(s, 0, max, v);
}

/* Whether s is an identity (tr_batch_start_id): 16 lower-case hex digits. */
static int id_ok(const char *s)
{
    size_t i = 0;
    while (i < 16 && ((s[i] >= '0' && s[i] <= '9') || (s[i] >= 'a' && s[i] <= 'f')))
        i++;
    return i == 16 && s[16] == '\0';
}

/* Whether s is a source (tr_batch_row): "file", "-", or "knot:" or
 * "link:" and a name of the table's characters. */
static int source_ok(const char *s)
{
    if (!strcmp(s, "file") || !strcmp(s, "-"))
        return 1;
    if (strncmp(s, "knot:", 5) && strncmp(s, "link:", 5))
        return 0;
    if (!s[5])
        return 0;
    for (const char *p = s + 5; *p; p++)
        if (!isalnum((unsigned char)*p) && !strchr("_{},", *p))
            return 0;
    return 1;
}

/* Parses the record's second line (tabs cut into NUL-separated fields),
 * ncols of them. */
static int parse_fields(char *line, int ncols, tr_batch_row *r)
{
    char *f[NCOLS];
    int nf = 0;
    for (char *p = line;;) {
        if (nf == ncols)
            return -1; /* more fields than columns */
        f[nf++] = p;
        char *tab = strchr(p, '\t');
        if (!tab)
            break;
        *tab = '\0';
        p = tab + 1;
    }
    long n, tries, resumed, seed = -1, road = 0;
    if (nf != ncols || strlen(f[0]) > TR_BATCH_NAME_MAX || strlen(f[10]) >= sizeof r->stop ||
        tr_arg_long(f[1], 0, 1000000000, &n) || field_double(f[2], &r->ropelength) ||
        field_double(f[3], &r->thickness) || field_double(f[4], &r->minrad) || field_double(f[5], &r->dcsd) ||
        field_double(f[6], &r->kkt_residual) || field_double(f[7], &r->time_s) ||
        tr_arg_long(f[8], 0, 1000000, &tries) || tr_arg_long(f[9], 0, LONG_MAX, &r->steps) ||
        tr_arg_long(f[11], 0, 1, &resumed) ||
        (ncols >= 14 && (field_long(f[12], LONG_MAX, &seed) || field_long(f[13], 1000000, &road))) ||
        (ncols >= 15 && strcmp(f[14], "-") && !id_ok(f[14])) ||
        (ncols >= 17 && (strlen(f[15]) >= sizeof r->source || !source_ok(f[15]))))
        return -1;
    if (ncols >= 15 && strcmp(f[14], "-"))
        strcpy(r->start, f[14]);
    r->type_checked = -1;
    if (ncols >= 17) {
        if (strcmp(f[15], "-"))
            strcpy(r->source, f[15]);
        int w = 0;
        while (w < 3 && strcmp(f[16], type_words[w]))
            w++;
        if (w == 3)
            return -1;
        r->type_checked = w - 1;
    }
    strcpy(r->knot, f[0]);
    strcpy(r->stop, f[10]);
    r->n = (size_t)n;
    r->tries = (int)tries;
    r->resumed = (int)resumed;
    r->seed = seed;
    r->road = road > 0 ? (int)road : 0;
    return 0;
}

int tr_batch_row_read(const char *path, tr_batch_row *r, tr_error *err)
{
    char *text;
    int rc = tr_read_text_file(path, &text, NULL, err);
    if (rc != TR_OK)
        return rc;
    /* a header of before is this one's first columns */
    size_t hl = strlen(header);
    int ncols = NCOLS;
    for (size_t v = 0; v < sizeof NCOLS_OLD / sizeof NCOLS_OLD[0]; v++) {
        size_t hl_old = 0;
        for (int c = 0; c < NCOLS_OLD[v]; c++)
            hl_old += strcspn(header + hl_old, "\t") + (c + 1 < NCOLS_OLD[v]);
        if (!strncmp(text, header, hl_old) && text[hl_old] == '\n') {
            ncols = NCOLS_OLD[v];
            hl = hl_old;
        }
    }
    char *line = text + hl + 1;
    if (strncmp(text, header, hl) || text[hl] != '\n')
        rc = tr_fail(err, TR_EPARSE, "%s:1: not a batch record (expected the header '%s')", path, header);
    else {
        char *nl = strchr(line, '\n');
        if (!nl || nl[1] != '\0')
            rc = tr_fail(err, TR_EPARSE, "%s:2: expected one line after the header", path);
        else {
            *nl = '\0';
            *r = (tr_batch_row){0};
            if (parse_fields(line, ncols, r))
                rc = tr_fail(err, TR_EPARSE, "%s:2: expected %d tab-separated fields as the header names", path,
                             ncols);
        }
    }
    free(text);
    return rc;
}

/* FNV-1a: one multiply a byte, no table; 64 bits leave a chance
 * collision at 2^-64, and the identity guards against mix-ups, not
 * against an adversary */
#define FNV_BASIS 14695981039346656037u
static uint64_t fnv1a(uint64_t h, const unsigned char *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211u;
    return h;
}

int tr_batch_knot_start_id(const tr_batch_knot *k, char id[TR_BATCH_ID_SIZE], tr_error *err)
{
    if (k->from == TR_BATCH_FROM_FILE)
        return tr_batch_start_id(k->file, id, err);
    /* the tag says what kind of identity this is (a start file would have
     * to begin with these very bytes to share it); a change to how a start
     * by name is made that should make it another start is a new tag */
    static const char tag[] = "tightrope start by name 1\n";
    uint64_t h = fnv1a(FNV_BASIS, (const unsigned char *)tag, sizeof tag - 1);
    h = fnv1a(h, (const unsigned char *)k->source, strlen(k->source));
    h = fnv1a(h, (const unsigned char *)"\n", 1);
    h = fnv1a(h, (const unsigned char *)k->notation, strlen(k->notation));
    snprintf(id, TR_BATCH_ID_SIZE, "%016llx", (unsigned long long)h);
    return TR_OK;
}

int tr_batch_start_id(const char *path, char id[TR_BATCH_ID_SIZE], tr_error *err)
{
    id[0] = '\0';
    struct stat st;
    if (stat(path, &st))
        return tr_fail(err, TR_EIO, "%s: %s", path, strerror(errno));
    if (!S_ISREG(st.st_mode))
        return TR_OK;
    FILE *f = fopen(path, "rb");
    if (!f)
        return tr_fail(err, TR_EIO, "%s: %s", path, strerror(errno));
    uint64_t h = FNV_BASIS;
    unsigned char buf[65536];
    size_t got;
    while ((got = fread(buf, 1, sizeof buf, f)) > 0)
        h = fnv1a(h, buf, got);
    int bad = ferror(f);
    fclose(f);
    if (bad)
        return tr_fail(err, TR_EIO, "%s: a read failed", path);
    snprintf(id, TR_BATCH_ID_SIZE, "%016llx", (unsigned long long)h);
    return TR_OK;
}

int tr_batch_start_write(const char *path, const char *id, tr_error *err)
{
    tr_text t = {0};
    tr_text_printf(&t, "%s\n", id[0] ? id : "-");
    return tr_text_write_atomic(&t, path, err);
}

int tr_batch_start_read(const char *path, char id[TR_BATCH_ID_SIZE], tr_error *err)
{
    id[0] = '\0';
    struct stat st;
    if (stat(path, &st) && errno == ENOENT)
        return 1;
    char *text;
    size_t len;
    int rc = tr_read_text_file(path, &text, &len, err);
    if (rc != TR_OK)
        return rc;
    if (len > 0 && text[len - 1] == '\n')
        text[--len] = '\0';
    if (id_ok(text))
        strcpy(id, text);
    else if (strcmp(text, "-"))
        rc = tr_fail(err, TR_EPARSE, "%s:1: expected the start's identity (16 hex digits)", path);
    free(text);
    return rc;
}
