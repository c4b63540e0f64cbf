/* Braid words and PD codes from text (knot_notation.h). */
#include "topology/knot_notation.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* The integers of text, in order, into a growing array; TR_EINVAL for a
 * character no notation uses (what == "braid word" or "PD code"). */
static int read_ints(const char *text, const char *what, int allow_x, int **out, int *count, int max, tr_error *err)
{
    *out = NULL;
    *count = 0;
    int cap = 0;
    for (const char *p = text; *p;) {
        unsigned char ch = (unsigned char)*p;
        if (isspace(ch) || strchr("[](){},;", ch)) {
            p++;
            continue;
        }
        /* KnotTheory's X[a, b, c, d]: an X only right before its bracket */
        if (allow_x && (ch == 'X' || ch == 'x') && p[1] == '[') {
            p++;
            continue;
        }
        if (ch == '+' || ch == '-' || isdigit(ch)) {
            char *end;
            errno = 0;
            long v = strtol(p, &end, 10);
            if (end == p) {
                free(*out);
                *out = NULL;
                return tr_fail(err, TR_EINVAL, "%s: '%c' at character %d is not followed by a number", what, ch,
                               (int)(p - text) + 1);
            }
            if (errno == ERANGE || v > INT_MAX / 4 || v < -INT_MAX / 4) {
                free(*out);
                *out = NULL;
                return tr_fail(err, TR_EINVAL, "%s: the number at character %d is too large", what,
                               (int)(p - text) + 1);
            }
            if (*count >= max) {
                free(*out);
                *out = NULL;
                return tr_fail(err, TR_EINVAL, "%s: more than %d numbers (too large for a start curve)", what, max);
            }
            if (*count == cap) {
                cap = cap ? 2 * cap : 64;
                int *g = realloc(*out, (size_t)cap * sizeof *g);
                if (!g) {
                    free(*out);
                    *out = NULL;
                    return tr_fail(err, TR_ENOMEM, "out of memory reading a %s", what);
                }
                *out = g;
            }
            (*out)[(*count)++] = (int)v;
            p = end;
            continue;
        }
        free(*out);
        *out = NULL;
        if (isprint(ch))
            return tr_fail(err, TR_EINVAL, "%s: unexpected '%c' at character %d", what, ch, (int)(p - text) + 1);
        return tr_fail(err, TR_EINVAL, "%s: unexpected byte 0x%02x at character %d", what, ch, (int)(p - text) + 1);
    }
    return 0;
}

int tr_braid_parse(const char *text, tr_braid *b, tr_error *err)
{
    memset(b, 0, sizeof *b);
    int *w = NULL, n = 0;
    int rc = read_ints(text, "braid word", 0, &w, &n, TR_NOTATION_MAX_CROSSINGS, err);
    if (rc)
        return rc;
    if (n == 0) {
        free(w);
        return tr_fail(err, TR_EINVAL, "braid word: empty (no generator; e.g. \"1,1,1\" is the trefoil)");
    }
    int strands = 2;
    for (int k = 0; k < n; k++) {
        if (w[k] == 0) {
            free(w);
            return tr_fail(err, TR_EINVAL, "braid word: generator %d is 0 (generators are 1..s-1, -i the inverse)",
                           k + 1);
        }
        int a = abs(w[k]);
        if (a + 1 > strands)
            strands = a + 1;
    }
    if (strands > 64) {
        free(w);
        return tr_fail(err, TR_EINVAL, "braid word: %d strands, more than the 64 a start curve takes", strands);
    }
    b->strands = strands;
    b->len = n;
    b->word = w;
    return 0;
}

void tr_braid_free(tr_braid *b)
{
    if (b)
        free(b->word);
    if (b)
        memset(b, 0, sizeof *b);
}

int tr_braid_components(const tr_braid *b, int *comp_of)
{
    /* perm[p]: where the strand starting at position p ends */
    int perm[64], seen[64];
    for (int p = 0; p < b->strands; p++) {
        int q = p;
        for (int k = 0; k < b->len; k++) {
            int i = abs(b->word[k]) - 1; /* swaps positions i and i+1 */
            if (q == i)
                q = i + 1;
            else if (q == i + 1)
                q = i;
        }
        perm[p] = q;
        seen[p] = -1;
    }
    int nc = 0;
    for (int p = 0; p < b->strands; p++) {
        if (seen[p] >= 0)
            continue;
        for (int q = p; seen[q] < 0; q = perm[q])
            seen[q] = nc;
        nc++;
    }
    if (comp_of)
        memcpy(comp_of, seen, (size_t)b->strands * sizeof *comp_of);
    return nc;
}

int tr_pd_parse(const char *text, tr_pd *p, tr_error *err)
{
    memset(p, 0, sizeof *p);
    int *v = NULL, n = 0;
    int rc = read_ints(text, "PD code", 1, &v, &n, 4 * TR_NOTATION_MAX_CROSSINGS, err);
    if (rc)
        return rc;
    if (n == 0) {
        free(v);
        return tr_fail(err, TR_EINVAL, "PD code: empty (no crossing; e.g. \"[[1,5,2,4],[3,1,4,6],[5,3,6,2]]\" is the "
                       "trefoil)");
    }
    if (n % 4) {
        free(v);
        return tr_fail(err, TR_EINVAL, "PD code: %d numbers, not 4 per crossing", n);
    }
    int nc = n / 4, ne = 2 * nc;
    int *use = calloc((size_t)ne + 1, sizeof *use);
    if (!use) {
        free(v);
        return tr_fail(err, TR_ENOMEM, "out of memory reading a PD code");
    }
    for (int c = 0; c < nc && !rc; c++)
        for (int k = 0; k < 4; k++) {
            int e = v[4 * c + k];
            if (e < 1 || e > ne) {
                rc = tr_fail(err, TR_EINVAL, "PD code: crossing %d has label %d, outside 1..%d (%d crossings have %d "
                             "edges)", c + 1, e, ne, nc, ne);
                break;
            }
            use[e]++;
        }
    for (int e = 1; e <= ne && !rc; e++)
        if (use[e] != 2)
            rc = tr_fail(err, TR_EINVAL, "PD code: label %d appears %d time%s, not twice (each edge joins two "
                         "crossing ends)", e, use[e], use[e] == 1 ? "" : "s");
    for (int c = 0; c < nc && !rc; c++) {
        int a = v[4 * c], b = v[4 * c + 1], cc = v[4 * c + 2], d = v[4 * c + 3];
        if (cc != a % ne + 1)
            rc = tr_fail(err, TR_EINVAL, "PD code: crossing %d [%d,%d,%d,%d]: the under strand runs %d -> %d, not "
                         "%d -> %d (a knot's edges are numbered along it)", c + 1, a, b, cc, d, a, cc, a, a % ne + 1);
        else if (b != d % ne + 1 && d != b % ne + 1)
            rc = tr_fail(err, TR_EINVAL, "PD code: crossing %d [%d,%d,%d,%d]: the over strand's edges %d and %d are "
                         "not consecutive", c + 1, a, b, cc, d, b, d);
    }
    free(use);
    if (rc) {
        free(v);
        return rc;
    }
    p->n = nc;
    p->x = (int(*)[4])v;
    return 0;
}

void tr_pd_free(tr_pd *p)
{
    if (p)
        free(p->x);
    if (p)
        memset(p, 0, sizeof *p);
}
