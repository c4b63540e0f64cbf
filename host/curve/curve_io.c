/* This file contains the curve files' front door: the format from a name
 * or the content, the dispatch of tr_curve_parse/read/format/write to the
 * formats (VECT in vect.c, TSV and KnotPlot lists in point_list.c) and the
 * helpers they share (curve_io_formats.h). The readers work on a buffer with
 * an explicit length (a file may hold any byte, NUL included) and report the
 * first problem as "FILE:LINE: what is wrong"; the writers build the whole
 * text in memory and hand it to tr_write_file_atomic. */
#include "curve/curve_io.h"
#include "curve/curve_io_formats.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------- shared lexing */

int tr_curve_io_is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || c == '\n'; }

/* Copies a token into buf for a message: at most 24 characters, anything
 * unprintable shown as '?', so an error stays one readable line. */
const char *tr_curve_io_quote(char *buf, size_t bufn, const char *p, size_t n)
{
    size_t m = 0;
    for (size_t i = 0; i < n && m + 4 < bufn && i < 24; i++) {
        unsigned char c = (unsigned char)p[i];
        buf[m++] = (c >= 32 && c < 127) ? (char)c : '?';
    }
    if (n > 24 && m + 4 < bufn) {
        memcpy(buf + m, "...", 3);
        m += 3;
    }
    buf[m] = '\0';
    return buf;
}

/* Parses a whole token as a finite decimal double: 0 ok, 1 not a number,
 * 2 not finite. strtod also reads hexadecimal ("0x1p3"), which no curve
 * file writes: a token with an x in it is not a number here. */
int tr_curve_io_token_double(const char *p, size_t n, double *out)
{
    char buf[128];
    if (n == 0 || n >= sizeof buf)
        return 1;
    memcpy(buf, p, n);
    buf[n] = '\0';
    if (memchr(buf, '\0', n) || strpbrk(buf, "xX"))
        return 1;
    char *end;
    errno = 0;
    double v = strtod(buf, &end);
    if (end != buf + n)
        return 1;
    if (!isfinite(v))
        return 2;
    *out = v;
    return 0;
}

/* The digits of a decimal token's mantissa, leading zeros not counted. */
static int significant_digits(const char *s)
{
    int n = 0, lead = 1;
    for (; *s && *s != 'e' && *s != 'E'; s++) {
        if (*s < '0' || *s > '9')
            continue;
        if (lead && *s == '0')
            continue;
        lead = 0;
        n++;
    }
    return n;
}

int tr_curve_io_token_split(const char *p, size_t n, double *hi, double *lo)
{
    int r = tr_curve_io_token_double(p, n, hi);
    *lo = 0.0;
    if (r)
        return r;
    /* A token of at most 17 digits is the double strtod makes of it, as
     * before low parts existed (every file a double prints); one with
     * more carries the rest in lo (curve.h) */
    char buf[128];
    memcpy(buf, p, n);
    buf[n] = '\0';
    if (significant_digits(buf) <= 17)
        return 0;
    long double v = strtold(buf, NULL);
    if (isfinite(v))
        *lo = (double)(v - (long double)*hi);
    return 0;
}

void tr_curve_io_vertex(tr_text *b, const tr_curve *c, size_t i, const char *sep)
{
    for (int a = 0; a < 3; a++) {
        size_t q = 3 * i + (size_t)a;
        if (a)
            tr_text_printf(b, "%s", sep);
        /* 17 digits hold a double; 21 a long double (x + lo, as wide as
         * this machine's long double keeps it) */
        if (c->lo && c->lo[q] != 0.0)
            tr_text_printf(b, "%.21Lg", (long double)c->x[q] + (long double)c->lo[q]);
        else
            tr_text_printf(b, "%.17g", c->x[q]);
    }
}

int tr_curve_io_parse_fail(tr_error *err, const char *name, size_t line, const char *fmt, ...)
{
    if (err) {
        char what[768];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(what, sizeof what, fmt, ap);
        va_end(ap);
        tr_fail(err, TR_EPARSE, "%.200s:%zu: %s", name, line, what);
    }
    return TR_EPARSE;
}

/* ---------------------------------------------------- shared validation */

/* Where vertices coincide because their coordinates are too large for the
 * curve's size (a curve moved to 1e300 rounds to one point), the message
 * says so: the step between doubles there against the component's extent. */
static void rounding_hint(const tr_curve *c, int k, const double *v, char *buf, size_t n)
{
    buf[0] = '\0';
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2]))), ext = 0.0;
    for (int a = 0; a < 3; a++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = c->start[k]; i < c->start[k + 1]; i++) {
            lo = fmin(lo, c->x[3 * i + a]);
            hi = fmax(hi, c->x[3 * i + a]);
        }
        ext = fmax(ext, hi - lo);
    }
    double step = tr_double_step(m);
    if (m > 0.0 && TR_CURVE_MIN_STEPS * step > ext)
        snprintf(buf, n, " (its coordinates, near %.3g, are stored in steps of %.3g, and the component is only %.3g "
                         "across: the numbers cannot hold its shape there; move it nearer the origin)",
                 m, step, ext);
}

/* Coincident consecutive vertices make a zero-length edge: no tangent, no
 * curvature, so every later stage would divide by zero. Then the numbers
 * must hold the curve's shape at all (curve.h, tr_curve_check_resolution:
 * not a curve far from the origin for its size, nor subnormal). */
int tr_curve_io_check_edges(const tr_curve *c, const size_t *vline, const char *name, tr_error *err)
{
    for (int k = 0; k < c->ncomp; k++) {
        size_t s = c->start[k], n = tr_comp_nv(c, k);
        for (size_t j = 1; j <= n; j++) {
            if (j == n && !c->closed[k])
                break;
            const double *a = c->x + 3 * (s + j - 1), *b = c->x + 3 * (s + j % n);
            if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) {
                char hint[256];
                rounding_hint(c, k, a, hint, sizeof hint);
                if (j == n)
                    return tr_curve_io_parse_fail(err, name, vline[s + n - 1],
                                      "last vertex of closed component %d coincides with its first "
                                      "(a closed component does not repeat its first vertex)%s",
                                      k, hint);
                return tr_curve_io_parse_fail(err, name, vline[s + j],
                                  "vertex %zu of component %d coincides with the previous vertex%s", j, k, hint);
            }
        }
    }
    size_t v;
    tr_error why;
    if (tr_curve_check_resolution(c, &v, &why))
        return tr_curve_io_parse_fail(err, name, v < c->nv ? vline[v] : 1, "%s", why.msg);
    return TR_OK;
}

int tr_curve_io_check_size(int closed, size_t n, int k, size_t line, const char *name, tr_error *err)
{
    if (closed && n < 3)
        return tr_curve_io_parse_fail(err, name, line, "closed component %d has %zu vertices, needs at least 3", k, n);
    if (!closed && n < 2)
        return tr_curve_io_parse_fail(err, name, line, "open component %d has %zu vertices, needs at least 2", k, n);
    return TR_OK;
}

/* Words of a comment, split on blanks (no allocation: pointers into the text). */
size_t tr_curve_io_split_words(const char *p, size_t n, const char **w, size_t *wn, size_t maxw)
{
    size_t k = 0, i = 0;
    while (i < n) {
        while (i < n && tr_curve_io_is_space(p[i]))
            i++;
        if (i >= n)
            break;
        size_t b = i;
        while (i < n && !tr_curve_io_is_space(p[i]))
            i++;
        if (k < maxw) {
            w[k] = p + b;
            wn[k] = i - b;
        }
        k++;
    }
    return k;
}

/* Each line of comments becomes "# line". */
void tr_curve_io_comments(tr_text *b, const char *comments)
{
    if (!comments)
        return;
    const char *p = comments;
    while (*p) {
        const char *e = strchr(p, '\n');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        tr_text_printf(b, n ? "# %.*s\n" : "#\n", (int)n, p);
        p += n;
        if (*p == '\n')
            p++;
    }
}

/* ------------------------------------------------------------- public API */

static int ends_with(const char *s, const char *suf)
{
    size_t n = strlen(s), m = strlen(suf);
    if (m > n)
        return 0;
    for (size_t i = 0; i < m; i++) {
        char a = s[n - m + i];
        if (a >= 'A' && a <= 'Z')
            a = (char)(a - 'A' + 'a');
        if (a != suf[i])
            return 0;
    }
    return 1;
}

tr_format tr_format_from_name(const char *name)
{
    if (!name)
        return TR_FORMAT_AUTO;
    if (ends_with(name, ".vect"))
        return TR_FORMAT_VECT;
    if (ends_with(name, ".tsv"))
        return TR_FORMAT_TSV;
    if (ends_with(name, ".txt") || ends_with(name, ".dat") || ends_with(name, ".knot"))
        return TR_FORMAT_KNOTPLOT;
    return TR_FORMAT_AUTO;
}

int tr_curve_parse(const char *name, const char *text, size_t len, tr_format fmt, tr_curve *out,
                   tr_error *err)
{
    if (!name)
        name = "<input>";
    if (!text)
        text = "", len = 0;
    /* A UTF-8 byte-order mark (a Windows editor's) is no part of the
     * text: skipped, as every reader of the format would. Line numbers
     * are unchanged. */
    if (len >= 3 && !memcmp(text, "\xef\xbb\xbf", 3)) {
        text += 3;
        len -= 3;
    }
    if (fmt == TR_FORMAT_AUTO)
        fmt = tr_format_from_name(name);
    if (fmt == TR_FORMAT_AUTO) {
        /* By content: a VECT file starts (after comments) with the word VECT. */
        fmt = tr_vect_sniff(name, text, len) ? TR_FORMAT_VECT : TR_FORMAT_TSV;
    }
    switch (fmt) {
    case TR_FORMAT_VECT: return tr_vect_parse(name, text, len, out, err);
    case TR_FORMAT_TSV: return tr_point_list_parse(name, text, len, 1, out, err);
    case TR_FORMAT_KNOTPLOT: return tr_point_list_parse(name, text, len, 0, out, err);
    default: break;
    }
    memset(out, 0, sizeof *out);
    return tr_fail(err, TR_EINVAL, "unknown curve format %d", (int)fmt);
}

int tr_curve_read(const char *path, tr_format fmt, tr_curve *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    char *buf;
    size_t n;
    int rc = tr_read_text_file(path, &buf, &n, err);
    if (rc)
        return rc;
    if (fmt == TR_FORMAT_AUTO)
        fmt = tr_format_from_name(path);
    rc = tr_curve_parse(path, buf, n, fmt, out, err);
    free(buf);
    return rc;
}

/* ----------------------------------------------------------------- writing */

/* Whether fmt can hold c: finite coordinates, and for TSV and KnotPlot
 * lists closed components without constraints (one, for KnotPlot). */
static int format_holds(const tr_curve *c, tr_format fmt, tr_error *err)
{
    if (fmt != TR_FORMAT_VECT && fmt != TR_FORMAT_TSV && fmt != TR_FORMAT_KNOTPLOT)
        return tr_fail(err, TR_EINVAL, "no curve format given (vect, tsv or knotplot)");
    for (size_t i = 0; i < 3 * c->nv; i++)
        if (!isfinite(c->x[i]))
            return tr_fail(err, TR_EINVAL, "vertex %zu is not finite", i / 3);
    if (fmt != TR_FORMAT_VECT) {
        const char *what = fmt == TR_FORMAT_TSV ? "tsv" : "knotplot";
        for (int k = 0; k < c->ncomp; k++)
            if (!c->closed[k])
                return tr_fail(err, TR_EINVAL, "%s files hold closed components only; use .vect", what);
        if (c->ncst > 0)
            return tr_fail(err, TR_EINVAL, "only vect files carry constraints; use .vect");
        if (fmt == TR_FORMAT_KNOTPLOT && c->ncomp != 1)
            return tr_fail(err, TR_EINVAL, "a knotplot list holds one component, this curve has %d; use .tsv or .vect",
                           c->ncomp);
    }
    return TR_OK;
}

int tr_curve_format(const tr_curve *c, tr_format fmt, const char *comments, char **text, size_t *len,
                    tr_error *err)
{
    *text = NULL;
    *len = 0;
    int rc = format_holds(c, fmt, err);
    if (rc)
        return rc;
    tr_text b = {0};
    if (fmt == TR_FORMAT_VECT)
        tr_vect_format(&b, c, comments);
    else
        tr_point_list_format(&b, c, comments);
    *text = tr_text_take(&b, len);
    if (!*text)
        return tr_fail(err, TR_ENOMEM, "out of memory formatting a curve of %zu vertices", c->nv);
    return TR_OK;
}

/* The format a writer of path uses: fmt, or by path's extension. */
static int output_format(const char *path, tr_format *fmt, tr_error *err)
{
    if (*fmt == TR_FORMAT_AUTO)
        *fmt = tr_format_from_name(path);
    if (*fmt == TR_FORMAT_AUTO)
        return tr_fail(err, TR_EINVAL, "cannot tell the format of %s (use .vect, .tsv or .txt)", path);
    return TR_OK;
}

int tr_curve_check_output(const char *path, tr_format fmt, const tr_curve *c, tr_error *err)
{
    int rc = output_format(path, &fmt, err);
    if (rc)
        return rc;
    rc = format_holds(c, fmt, err);
    if (rc)
        return tr_fail_wrap(err, rc, "not writing %s", path);
    return tr_check_writable(path, err);
}

int tr_curve_write(const char *path, tr_format fmt, const tr_curve *c, const char *comments, tr_error *err)
{
    int rc = output_format(path, &fmt, err);
    if (rc)
        return rc;
    char *text;
    size_t len;
    rc = tr_curve_format(c, fmt, comments, &text, &len, err);
    if (rc)
        return tr_fail_wrap(err, rc, "not writing %s", path);
    rc = tr_write_file_atomic(path, text, len, err);
    free(text);
    return rc;
}


