/* The embedded knot and link tables (knot_table.h). */
#include "topology/knot_table.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* generated from data/knots/knotinfo_knots.tsv and linkinfo_links.tsv by cmake/EmbedText.cmake */
extern const char tr_knotinfo_knots[];
extern const unsigned long tr_knotinfo_knots_size;
extern const char tr_linkinfo_links[];
extern const unsigned long tr_linkinfo_links_size;

#define MAX_FIELDS 12

void tr_knot_name_normalise(const char *name, char *buf, size_t bufsize)
{
    char tmp[64];
    size_t k = 0;
    for (const char *p = name; *p && k + 1 < sizeof tmp; p++) {
        unsigned char ch = (unsigned char)*p;
        if (isspace(ch))
            continue;
        tmp[k++] = (ch == '.' || ch == '-') ? '_' : (char)tolower(ch);
    }
    tmp[k] = 0;
    const char *s = tmp;
    /* "k3_1": a knot named with a leading K */
    if (s[0] == 'k' && isdigit((unsigned char)s[1]))
        s++;
    /* "11a1" -> "11a_1" (KnotInfo's 11- and 12-crossing names) */
    size_t i = 0;
    while (isdigit((unsigned char)s[i]))
        i++;
    if (i > 0 && (s[i] == 'a' || s[i] == 'n') && isdigit((unsigned char)s[i + 1]))
        snprintf(buf, bufsize, "%.*s_%s", (int)(i + 1), s, s + i + 1);
    else
        snprintf(buf, bufsize, "%s", s);
}

static int parse_row(tr_table_entry *e, char **f, int nf, int is_link, tr_error *err)
{
    memset(e, 0, sizeof *e);
    e->ropelength = NAN;
    e->is_link = is_link;
    tr_error sub;
    if ((int)strlen(f[0]) >= (int)sizeof e->name)
        return tr_fail(err, TR_EPARSE, "name too long");
    strcpy(e->name, f[0]);
    if (!is_link) {
        if (nf != 8)
            return tr_fail(err, TR_EPARSE, "%d fields, not 8", nf);
        strcpy(e->unoriented, f[0]);
        e->components = 1;
        e->crossings = atoi(f[1]);
        if (f[2][0] && tr_braid_parse(f[2], &e->braid, &sub))
            return tr_fail(err, TR_EPARSE, "%s", sub.msg);
        if (f[3][0] && tr_pd_parse(f[3], &e->pd, &sub))
            return tr_fail(err, TR_EPARSE, "%s", sub.msg);
        /* the Alexander polynomial as listed; its symmetry and Delta(1) = 1
         * are the extraction script's checks, repeated by the tests */
        int span = -1;
        for (char *p = f[4]; *p;) {
            char *end;
            long long v = strtoll(p, &end, 10);
            if (end == p || span + 1 > TR_ALEXANDER_MAX_CROSSINGS)
                return tr_fail(err, TR_EPARSE, "bad Alexander polynomial '%s'", f[4]);
            e->alexander.coef[++span] = v;
            p = *end == ',' ? end + 1 : end;
            if (*end && *end != ',')
                return tr_fail(err, TR_EPARSE, "bad Alexander polynomial '%s'", f[4]);
        }
        if (span < 0 || span % 2)
            return tr_fail(err, TR_EPARSE, "bad Alexander polynomial '%s'", f[4]);
        e->alexander.span = span;
        e->determinant = e->alexander.determinant = atoll(f[5]);
        if (f[6][0]) {
            e->has_signature = 1;
            e->signature = atoi(f[6]);
        }
        if (f[7][0])
            e->ropelength = strtod(f[7], NULL);
        return 0;
    }
    if (nf != 10)
        return tr_fail(err, TR_EPARSE, "%d fields, not 10", nf);
    if (strlen(f[1]) >= sizeof e->unoriented || strlen(f[2]) >= sizeof e->rolfsen)
        return tr_fail(err, TR_EPARSE, "name too long");
    strcpy(e->unoriented, f[1]);
    strcpy(e->rolfsen, f[2]);
    e->components = atoi(f[3]);
    e->crossings = atoi(f[4]);
    if (tr_braid_parse(f[6], &e->braid, &sub))
        return tr_fail(err, TR_EPARSE, "%s", sub.msg);
    /* the braid's own strand count: a generator-free last strand is still
     * a strand of the closure */
    int strands = atoi(f[5]);
    if (strands < e->braid.strands)
        return tr_fail(err, TR_EPARSE, "%d strands for a braid on %d", strands, e->braid.strands);
    e->braid.strands = strands;
    e->determinant = atoll(f[8]);
    int np = 0;
    for (char *p = f[9]; *p;) {
        char *end;
        long v = strtol(p, &end, 10);
        if (end == p || np >= TR_TABLE_MAX_PAIRS)
            return tr_fail(err, TR_EPARSE, "bad linking numbers '%s'", f[9]);
        e->linking[np++] = (int)v;
        p = *end == ',' ? end + 1 : end;
    }
    e->npairs = np;
    if (np != e->components * (e->components - 1) / 2)
        return tr_fail(err, TR_EPARSE, "%d linking numbers for %d components", np, e->components);
    return 0;
}

static int load_text(tr_knot_table *t, const char *text, unsigned long size, int is_link, const char *file,
                     tr_error *err)
{
    char *copy = malloc(size + 1);
    if (!copy)
        return tr_fail(err, TR_ENOMEM, "out of memory loading the knot table");
    memcpy(copy, text, size);
    copy[size] = 0;
    int rows = 0;
    for (unsigned long i = 0; i < size; i++)
        rows += copy[i] == '\n';
    tr_table_entry *e = realloc(t->e, ((size_t)t->n + (size_t)rows + 1) * sizeof *e);
    if (!e) {
        free(copy);
        return tr_fail(err, TR_ENOMEM, "out of memory loading the knot table");
    }
    t->e = e;
    int line = 0, rc = 0, header = 0;
    for (char *p = copy, *next; *p && !rc; p = next) {
        char *nl = strchr(p, '\n');
        next = nl ? nl + 1 : p + strlen(p);
        if (nl)
            *nl = 0;
        line++;
        if (p[0] == '#' || p[0] == 0)
            continue;
        if (!header) {
            header = 1; /* the column names */
            continue;
        }
        char *f[MAX_FIELDS] = {0}; /* all set up to nf; the rest NULL, never read */
        int nf = 0;
        for (char *q = p;;) {
            if (nf == MAX_FIELDS) {
                nf++;
                break;
            }
            f[nf++] = q;
            char *tab = strchr(q, '\t');
            if (!tab)
                break;
            *tab = 0;
            q = tab + 1;
        }
        tr_error sub;
        if (nf > MAX_FIELDS || parse_row(&t->e[t->n], f, nf, is_link, &sub)) {
            tr_braid_free(&t->e[t->n].braid);
            tr_pd_free(&t->e[t->n].pd);
            rc = tr_fail(err, TR_EPARSE, "%s:%d: %s", file, line, nf > MAX_FIELDS ? "too many fields" : sub.msg);
        } else {
            t->n++;
        }
    }
    free(copy);
    return rc;
}

int tr_knot_table_load(tr_knot_table *t, tr_error *err)
{
    memset(t, 0, sizeof *t);
    int rc = load_text(t, tr_knotinfo_knots, tr_knotinfo_knots_size, 0, "data/knots/knotinfo_knots.tsv", err);
    if (!rc)
        rc = load_text(t, tr_linkinfo_links, tr_linkinfo_links_size, 1, "data/knots/linkinfo_links.tsv", err);
    if (rc)
        tr_knot_table_free(t);
    return rc;
}

void tr_knot_table_free(tr_knot_table *t)
{
    for (int i = 0; i < t->n; i++) {
        tr_braid_free(&t->e[i].braid);
        tr_pd_free(&t->e[i].pd);
    }
    free(t->e);
    memset(t, 0, sizeof *t);
}

static int kind_ok(const tr_table_entry *e, int want_link) { return want_link < 0 || e->is_link == want_link; }

const tr_table_entry *tr_knot_table_find(const tr_knot_table *t, const char *name, int want_link)
{
    char key[64], cand[64];
    tr_knot_name_normalise(name, key, sizeof key);
    /* the exact (oriented) name first, then an unoriented or Rolfsen name:
     * its first orientation */
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < t->n; i++) {
            const tr_table_entry *e = &t->e[i];
            if (!kind_ok(e, want_link))
                continue;
            tr_knot_name_normalise(pass ? e->unoriented : e->name, cand, sizeof cand);
            if (!strcmp(key, cand))
                return e;
            if (pass && e->rolfsen[0]) {
                tr_knot_name_normalise(e->rolfsen, cand, sizeof cand);
                if (!strcmp(key, cand))
                    return e;
            }
        }
    return NULL;
}

static int edit_distance(const char *a, const char *b)
{
    int la = (int)strlen(a), lb = (int)strlen(b);
    if (la > 63 || lb > 63)
        return 1000;
    int row[64];
    for (int j = 0; j <= lb; j++)
        row[j] = j;
    for (int i = 1; i <= la; i++) {
        int diag = row[0];
        row[0] = i;
        for (int j = 1; j <= lb; j++) {
            int up = row[j];
            int sub = diag + (a[i - 1] != b[j - 1]);
            int best = sub < up + 1 ? sub : up + 1;
            row[j] = best < row[j - 1] + 1 ? best : row[j - 1] + 1;
            diag = up;
        }
    }
    return row[lb];
}

void tr_knot_table_suggest(const tr_knot_table *t, const char *name, int want_link, char *buf, size_t bufsize)
{
    enum { MAXS = 4 };
    char key[64], cand[64];
    tr_knot_name_normalise(name, key, sizeof key);
    const char *best[MAXS] = {0};
    int dist[MAXS];
    for (int k = 0; k < MAXS; k++)
        dist[k] = 1 << 30;
    for (int i = 0; i < t->n; i++) {
        const tr_table_entry *e = &t->e[i];
        if (!kind_ok(e, want_link))
            continue;
        /* links by their unoriented names, once each */
        if (e->is_link && i > 0 && !strcmp(t->e[i - 1].unoriented, e->unoriented))
            continue;
        tr_knot_name_normalise(e->unoriented, cand, sizeof cand);
        int d = edit_distance(key, cand);
        for (int k = 0; k < MAXS; k++)
            if (d < dist[k]) {
                for (int m = MAXS - 1; m > k; m--) {
                    dist[m] = dist[m - 1];
                    best[m] = best[m - 1];
                }
                dist[k] = d;
                best[k] = e->unoriented;
                break;
            }
    }
    size_t used = 0;
    buf[0] = 0;
    for (int k = 0; k < MAXS && best[k] && used < bufsize; k++)
        used += (size_t)snprintf(buf + used, bufsize - used, "%s%s", k ? ", " : "", best[k]);
}
