/* This file contains the reader and writer of point lists: TSV (three
 * numbers a line, blank lines between components) and KnotPlot lists (one
 * component). */
#include "curve/curve_io.h"
#include "curve/curve_io_formats.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ----------------------------------------------------- TSV and KnotPlot */

/* Line-oriented: three numbers per line, '#' comments, blank lines end a
 * component (TSV) or are ignored (KnotPlot, one component). All closed. */
int tr_point_list_parse(const char *name, const char *text, size_t len, int multi, tr_curve *out,
                       tr_error *err)
{
    double *x = NULL, *xl = NULL; /* coordinates and their low parts (curve.h) */
    int any_lo = 0;
    size_t *vline = NULL, nx = 0, capx = 0;
    size_t *nv = NULL, ncomp = 0, capc = 0;
    size_t compline = 0; /* first line of the current component */
    size_t cur = 0;      /* vertices in the current component */
    int rc = TR_OK;
    char q[64];
    memset(out, 0, sizeof *out);

    size_t pos = 0, line = 0;
    while (pos < len) {
        line++;
        size_t b = pos;
        while (pos < len && text[pos] != '\n')
            pos++;
        size_t e = pos;
        pos++; /* past '\n' (or past the end) */
        const char *h = memchr(text + b, '#', e - b);
        int comment = h != NULL;
        if (h)
            e = (size_t)(h - text);
        const char *w[4];
        size_t wn[4];
        size_t nw = tr_curve_io_split_words(text + b, e - b, w, wn, 4);
        if (nw == 0) {
            /* A blank line ends a component; a comment line does not. */
            if (!comment && multi && cur) {
                if ((rc = tr_curve_io_check_size(1, cur, (int)ncomp - 1, compline, name, err)))
                    goto done;
                cur = 0;
            }
            continue;
        }
        if (nw != 3) {
            rc = tr_curve_io_parse_fail(err, name, line, "expected 3 numbers (x y z), got %zu fields", nw);
            goto done;
        }
        if (nx == capx) {
            size_t cap = capx ? 2 * capx : 256;
            double *g = realloc(x, 3 * cap * sizeof *g);
            if (!g) {
                rc = tr_fail(err, TR_ENOMEM, "out of memory reading %s", name);
                goto done;
            }
            x = g;
            double *gx = realloc(xl, 3 * cap * sizeof *gx);
            if (!gx) {
                rc = tr_fail(err, TR_ENOMEM, "out of memory reading %s", name);
                goto done;
            }
            xl = gx;
            size_t *gl = realloc(vline, cap * sizeof *gl);
            if (!gl) {
                rc = tr_fail(err, TR_ENOMEM, "out of memory reading %s", name);
                goto done;
            }
            vline = gl;
            capx = cap;
        }
        for (int a = 0; a < 3; a++) {
            int r = tr_curve_io_token_split(w[a], wn[a], &x[3 * nx + (size_t)a], &xl[3 * nx + (size_t)a]);
            any_lo |= xl[3 * nx + (size_t)a] != 0.0;
            if (r) {
                rc = tr_curve_io_parse_fail(err, name, line, "%s: '%s'", r == 2 ? "not a finite number" : "not a number",
                                tr_curve_io_quote(q, sizeof q, w[a], wn[a]));
                goto done;
            }
        }
        vline[nx++] = line;
        if (cur == 0) {
            if (ncomp == capc) {
                size_t cap = capc ? 2 * capc : 8;
                size_t *g = realloc(nv, cap * sizeof *g);
                if (!g) {
                    rc = tr_fail(err, TR_ENOMEM, "out of memory reading %s", name);
                    goto done;
                }
                nv = g;
                capc = cap;
            }
            nv[ncomp++] = 0;
            compline = line;
        }
        nv[ncomp - 1]++;
        cur++;
    }
    if (nx == 0) {
        rc = tr_curve_io_parse_fail(err, name, 1, "empty file (no vertices)");
        goto done;
    }
    if (cur && (rc = tr_curve_io_check_size(1, cur, (int)ncomp - 1, compline, name, err)))
        goto done;
    if (ncomp > INT_MAX) {
        rc = tr_curve_io_parse_fail(err, name, line, "too many components");
        goto done;
    }
    if ((rc = tr_curve_alloc(out, (int)ncomp, nv, NULL, err)))
        goto done;
    memcpy(out->x, x, 3 * nx * sizeof *x);
    if (any_lo && (rc = tr_curve_want_lo(out, err)))
        goto done;
    if (any_lo)
        memcpy(out->lo, xl, 3 * nx * sizeof *xl);
    rc = tr_curve_io_check_edges(out, vline, name, err);

done:
    if (rc)
        tr_curve_free(out);
    free(x);
    free(xl);
    free(vline);
    free(nv);
    return rc;
}

/* ----------------------------------------------------------------- writing */

void tr_point_list_format(tr_text *b, const tr_curve *c, const char *comments)
{
    tr_curve_io_comments(b, comments);
    for (int k = 0; k < c->ncomp; k++) {
        if (k)
            tr_text_printf(b, "\n");
        for (size_t i = c->start[k]; i < c->start[k + 1]; i++) {
            tr_curve_io_vertex(b, c, i, "\t");
            tr_text_printf(b, "\n");
        }
    }
}
