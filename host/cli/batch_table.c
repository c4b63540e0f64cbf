/* The batch table and the reference it is compared with (batch_table.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/batch_table.h"
#include "cli/cli_args.h"
#include "util/json.h"
#include "util/text_file.h"

void tr_batch_ref_free(tr_batch_ref *ref)
{
    for (size_t i = 0; i < ref->count; i++)
        free(ref->names[i]);
    free(ref->names);
    free(ref->ropelength);
    free(ref->n);
    *ref = (tr_batch_ref){0};
}

/* Cuts line at tabs into at most max fields; returns how many. */
static int split_tabs(char *line, char **f, int max)
{
    int nf = 0;
    for (char *p = line; nf < max;) {
        f[nf++] = p;
        char *tab = strchr(p, '\t');
        if (!tab)
            break;
        *tab = '\0';
        p = tab + 1;
    }
    return nf;
}

/* Finds the header's ropelength and N columns. */
static int header_columns(const char *path, char *line, int *col_rl, int *col_n, tr_error *err)
{
    char *f[64];
    int nf = split_tabs(line, f, 64);
    *col_rl = *col_n = -1;
    for (int i = 1; i < nf; i++) {
        if (*col_rl < 0 && !strncmp(f[i], "ropelength", 10))
            *col_rl = i;
        if (*col_n < 0 && !strcmp(f[i], "N"))
            *col_n = i;
    }
    if (*col_rl < 0)
        return tr_fail(err, TR_EPARSE, "%s:1: the header names no ropelength column (knot<TAB>...ropelength...)",
                       path);
    return TR_OK;
}

int tr_batch_ref_add(tr_batch_ref *ref, const char *name, double rl, long n)
{
    size_t c = ref->count + 1;
    char **nm = realloc(ref->names, c * sizeof *nm);
    if (nm)
        ref->names = nm;
    double *r = realloc(ref->ropelength, c * sizeof *r);
    if (r)
        ref->ropelength = r;
    long *nn = realloc(ref->n, c * sizeof *nn);
    if (nn)
        ref->n = nn;
    if (!nm || !r || !nn || !(nm[ref->count] = strdup(name)))
        return -1;
    r[ref->count] = rl;
    nn[ref->count] = n;
    ref->count = c;
    return 0;
}

int tr_batch_ref_read(const char *path, tr_batch_ref *ref, tr_error *err)
{
    *ref = (tr_batch_ref){0};
    char *text;
    int rc = tr_read_text_file(path, &text, NULL, err);
    if (rc != TR_OK)
        return rc;
    int col_rl = -1, col_n = -1, lineno = 0;
    for (char *line = text, *next; rc == TR_OK && line && *line; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = '\0';
        lineno++;
        size_t len = strlen(line);
        if (len > 0 && line[len - 1] == '\r')
            line[--len] = '\0';
        if (len == 0 || line[0] == '#')
            continue;
        if (col_rl < 0) {
            rc = header_columns(path, line, &col_rl, &col_n, err);
            continue;
        }
        char *f[64];
        int nf = split_tabs(line, f, 64);
        double rl;
        long n = 0;
        if (nf <= col_rl || tr_arg_double(f[col_rl], 0, HUGE_VAL, &rl) ||
            (col_n >= 0 && (nf <= col_n || tr_arg_long(f[col_n], 0, 1000000000, &n))))
            rc = tr_fail(err, TR_EPARSE, "%s:%d: expected a knot name, a ropelength%s in the header's columns",
                         path, lineno, col_n >= 0 ? " and an N" : "");
        else if (tr_batch_ref_add(ref, f[0], rl, n))
            rc = tr_fail(err, TR_ENOMEM, "out of memory");
    }
    free(text);
    if (rc == TR_OK && col_rl < 0)
        rc = tr_fail(err, TR_EPARSE, "%s: empty (no header line)", path);
    if (rc != TR_OK)
        tr_batch_ref_free(ref);
    return rc;
}

/* Names equal with '.' and '_' as one character. */
static int same_knot(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        int da = *a == '.' ? '_' : *a, db = *b == '.' ? '_' : *b;
        if (da != db)
            return 0;
    }
    return *a == *b;
}

long tr_batch_ref_find(const tr_batch_ref *ref, const char *knot)
{
    for (size_t i = 0; i < ref->count; i++)
        if (same_knot(ref->names[i], knot))
            return (long)i;
    return -1;
}

/* The comparison's columns of row r: the reference's N and ropelength, the
 * difference and the difference in percent ('-' where the reference has
 * no such knot). */
static void compare_tsv(tr_text *t, const tr_batch_ref *ref, const tr_batch_row *r)
{
    long i = tr_batch_ref_find(ref, r->knot);
    if (i < 0) {
        tr_text_printf(t, "\t-\t-\t-\t-");
        return;
    }
    double d = r->ropelength - ref->ropelength[i];
    if (ref->n[i] > 0)
        tr_text_printf(t, "\t%ld", ref->n[i]);
    else
        tr_text_printf(t, "\t-");
    tr_text_printf(t, "\t%.10f\t", ref->ropelength[i]);
    if (isfinite(d))
        tr_text_printf(t, "%+.10f\t%+.4f", d, 100 * d / ref->ropelength[i]);
    else
        tr_text_printf(t, "-\t-");
}

static void compare_json(tr_text *t, const tr_batch_ref *ref, const tr_batch_row *r)
{
    long i = tr_batch_ref_find(ref, r->knot);
    double rl = i < 0 ? NAN : ref->ropelength[i], d = r->ropelength - rl;
    tr_text_printf(t, ", \"ref_N\": ");
    tr_json_number(t, "%.0f", i < 0 || ref->n[i] <= 0 ? NAN : (double)ref->n[i]);
    tr_text_printf(t, ", \"ref_ropelength\": ");
    tr_json_number(t, "%.10f", rl);
    tr_text_printf(t, ", \"diff\": ");
    tr_json_number(t, "%.10f", d);
    tr_text_printf(t, ", \"diff_pct\": ");
    tr_json_number(t, "%.4f", 100 * d / rl);
}

/* The path dir/name in buf; -1 if it does not fit. */
static int join(char *buf, size_t size, const char *dir, const char *name)
{
    return snprintf(buf, size, "%s/%s", dir, name) < (int)size ? 0 : -1;
}

int tr_batch_table_write(const char *dir, const tr_batch_row *rows, size_t count, const tr_batch_ref *ref,
                         tr_error *err)
{
    char path[4096];
    tr_text t = {0};
    tr_text_printf(&t, "%s%s\n", tr_batch_row_header(), ref ? "\tref_N\tref_ropelength\tdiff\tdiff_pct" : "");
    for (size_t i = 0; i < count; i++) {
        tr_batch_row_format(&t, &rows[i]);
        if (ref)
            compare_tsv(&t, ref, &rows[i]);
        tr_text_printf(&t, "\n");
    }
    if (join(path, sizeof path, dir, "table.tsv"))
        return tr_fail(err, TR_EINVAL, "%s: path too long", dir);
    int rc = tr_text_write_atomic(&t, path, err);
    if (rc != TR_OK)
        return rc;
    tr_text j = {0};
    tr_text_printf(&j, "{\"knots\": [");
    for (size_t i = 0; i < count; i++) {
        tr_text_printf(&j, "%s\n  {", i ? "," : "");
        tr_batch_row_json_fields(&j, &rows[i]);
        if (ref)
            compare_json(&j, ref, &rows[i]);
        tr_text_printf(&j, "}");
    }
    tr_text_printf(&j, "\n]}\n");
    if (join(path, sizeof path, dir, "table.json"))
        return tr_fail(err, TR_EINVAL, "%s: path too long", dir);
    return tr_text_write_atomic(&j, path, err);
}
