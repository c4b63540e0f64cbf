/* Curve files: VECT with plCurve's constraint comments, TSV and plain
 * KnotPlot lists. The readers work on a buffer with an explicit length (a
 * file may hold any byte, NUL included) and report the first problem as
 * "FILE:LINE: what is wrong"; the writers build the whole text in memory and
 * hand it to tr_write_file_atomic. */
#include "curve/curve_io.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* ------------------------------------------------------------------ lexing */

typedef struct lexer {
    const char *name;
    const char *s;
    size_t len, pos;
    size_t line;      /* line of the character at pos */
    size_t last_line; /* line of the last item returned (where an early end is reported) */
} lexer;

/* One item of a VECT file: a token (number or word) or a '#' comment. */
typedef struct item {
    enum { IT_END, IT_TOKEN, IT_COMMENT } kind;
    const char *p; /* for a comment: the text after '#' */
    size_t n;
    size_t line;
} item;

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || c == '\n'; }

static item lex_next(lexer *lx)
{
    while (lx->pos < lx->len && is_space(lx->s[lx->pos])) {
        if (lx->s[lx->pos] == '\n')
            lx->line++;
        lx->pos++;
    }
    item it = {IT_END, lx->s + lx->pos, 0, lx->line};
    if (lx->pos >= lx->len) {
        it.line = lx->last_line ? lx->last_line : 1;
        return it;
    }
    lx->last_line = lx->line;
    if (lx->s[lx->pos] == '#') {
        size_t b = ++lx->pos;
        while (lx->pos < lx->len && lx->s[lx->pos] != '\n')
            lx->pos++;
        it.kind = IT_COMMENT;
        it.p = lx->s + b;
        it.n = lx->pos - b;
        return it;
    }
    size_t b = lx->pos;
    while (lx->pos < lx->len && !is_space(lx->s[lx->pos]) && lx->s[lx->pos] != '#')
        lx->pos++;
    it.kind = IT_TOKEN;
    it.p = lx->s + b;
    it.n = lx->pos - b;
    return it;
}

/* Copies a token into buf for a message: at most 24 characters, anything
 * unprintable shown as '?', so an error stays one readable line. */
static const char *quote(char *buf, size_t bufn, const char *p, size_t n)
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
static int token_double(const char *p, size_t n, double *out)
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

static int token_long(const char *p, size_t n, long *out)
{
    char buf[32];
    if (n == 0 || n >= sizeof buf)
        return 1;
    memcpy(buf, p, n);
    buf[n] = '\0';
    if (memchr(buf, '\0', n))
        return 1;
    char *end;
    errno = 0;
    long v = strtol(buf, &end, 10);
    if (end != buf + n || errno == ERANGE)
        return 1;
    *out = v;
    return 0;
}

static int parse_fail(tr_error *err, const char *name, size_t line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static int parse_fail(tr_error *err, const char *name, size_t line, const char *fmt, ...)
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

/* Coincident consecutive vertices make a zero-length edge: no tangent, no
 * curvature, so every later stage would divide by zero. */
static int check_edges(const tr_curve *c, const size_t *vline, const char *name, tr_error *err)
{
    for (int k = 0; k < c->ncomp; k++) {
        size_t s = c->start[k], n = tr_comp_nv(c, k);
        for (size_t j = 1; j <= n; j++) {
            if (j == n && !c->closed[k])
                break;
            const double *a = c->x + 3 * (s + j - 1), *b = c->x + 3 * (s + j % n);
            if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) {
                if (j == n)
                    return parse_fail(err, name, vline[s + n - 1],
                                      "last vertex of closed component %d coincides with its first "
                                      "(a closed component does not repeat its first vertex)",
                                      k);
                return parse_fail(err, name, vline[s + j],
                                  "vertex %zu of component %d coincides with the previous vertex", j, k);
            }
        }
    }
    return TR_OK;
}

static int check_size(int closed, size_t n, int k, size_t line, const char *name, tr_error *err)
{
    if (closed && n < 3)
        return parse_fail(err, name, line, "closed component %d has %zu vertices, needs at least 3", k, n);
    if (!closed && n < 2)
        return parse_fail(err, name, line, "open component %d has %zu vertices, needs at least 2", k, n);
    return TR_OK;
}

/* ------------------------------------------------------------------- VECT */

typedef struct cst_def {
    tr_constraint c;
    size_t line;
} cst_def;

/* Words of a comment, split on blanks (no allocation: pointers into the text). */
static size_t split_words(const char *p, size_t n, const char **w, size_t *wn, size_t maxw)
{
    size_t k = 0, i = 0;
    while (i < n) {
        while (i < n && is_space(p[i]))
            i++;
        if (i >= n)
            break;
        size_t b = i;
        while (i < n && !is_space(p[i]))
            i++;
        if (k < maxw) {
            w[k] = p + b;
            wn[k] = i - b;
        }
        k++;
    }
    return k;
}

static int word_is(const char *w, size_t n, const char *lit)
{
    size_t m = strlen(lit);
    if (n != m)
        return 0;
    for (size_t i = 0; i < n; i++) {
        char a = w[i], b = lit[i];
        if (a >= 'A' && a <= 'Z')
            a = (char)(a - 'A' + 'a');
        if (b >= 'A' && b <= 'Z')
            b = (char)(b - 'A' + 'a');
        if (a != b)
            return 0;
    }
    return 1;
}

/* Makes a direction unit length. One that is already unit to a few ulp is
 * left alone, so a file we wrote reads back bit for bit. */
static int normalize_dir(double *u, double *d)
{
    double nrm = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(nrm > 1e-300) || !isfinite(nrm))
        return -1;
    if (fabs(nrm - 1.0) > 8 * 2.220446049250313e-16) {
        for (int a = 0; a < 3; a++)
            u[a] /= nrm;
        if (d)
            *d /= nrm;
    }
    return 0;
}

/* "# Constraint k Kind numbers..." as plCurve writes it: Fixed x y z,
 * Line tx ty tz px py pz (direction first, then a point), Plane nx ny nz d.
 * Returns 1 if the comment is a constraint definition (parsed into *def),
 * 0 if it is an ordinary comment, or TR_EPARSE. */
static int parse_constraint_comment(const item *it, const char *name, cst_def *def, tr_error *err)
{
    const char *w[12];
    size_t wn[12];
    size_t nw = split_words(it->p, it->n, w, wn, 12);
    if (nw < 2 || !word_is(w[0], wn[0], "constraint"))
        return 0;
    long id = 0;
    if (token_long(w[1], wn[1], &id))
        return 0; /* "# Constraint violation ..." is prose, not a definition */
    char q[64];
    if (id < 1 || id > INT_MAX)
        return parse_fail(err, name, it->line, "constraint number %ld out of range (must be >= 1)", id);
    if (nw < 3)
        return parse_fail(err, name, it->line, "constraint %ld has no kind (Fixed, Line or Plane)", id);
    memset(def, 0, sizeof *def);
    def->c.id = (int)id;
    def->line = it->line;
    size_t want;
    if (word_is(w[2], wn[2], "fixed")) {
        def->c.kind = TR_CST_FIXED;
        want = 3;
    } else if (word_is(w[2], wn[2], "line")) {
        def->c.kind = TR_CST_LINE;
        want = 6;
    } else if (word_is(w[2], wn[2], "plane")) {
        def->c.kind = TR_CST_PLANE;
        want = 4;
    } else {
        return parse_fail(err, name, it->line, "unknown constraint kind '%s' (Fixed, Line or Plane)",
                          quote(q, sizeof q, w[2], wn[2]));
    }
    if (nw != 3 + want)
        return parse_fail(err, name, it->line, "constraint %ld (%s) needs %zu numbers, got %zu", id,
                          quote(q, sizeof q, w[2], wn[2]), want, nw - 3);
    double v[6];
    for (size_t i = 0; i < want; i++) {
        int r = token_double(w[3 + i], wn[3 + i], &v[i]);
        if (r)
            return parse_fail(err, name, it->line, "constraint %ld: %s '%s'", id,
                              r == 2 ? "not a finite number" : "not a number",
                              quote(q, sizeof q, w[3 + i], wn[3 + i]));
    }
    switch (def->c.kind) {
    case TR_CST_FIXED:
        memcpy(def->c.p, v, sizeof def->c.p);
        break;
    case TR_CST_LINE:
        memcpy(def->c.u, v, sizeof def->c.u);
        memcpy(def->c.p, v + 3, sizeof def->c.p);
        if (normalize_dir(def->c.u, NULL))
            return parse_fail(err, name, it->line, "constraint %ld: line direction is zero", id);
        break;
    case TR_CST_PLANE:
        memcpy(def->c.u, v, sizeof def->c.u);
        def->c.d = v[3];
        if (normalize_dir(def->c.u, &def->c.d))
            return parse_fail(err, name, it->line, "constraint %ld: plane normal is zero", id);
        break;
    }
    return 1;
}

/* "# Cst: k" after a vertex: 1 and *id if it is one, 0 if not, or TR_EPARSE. */
static int parse_cst_comment(const item *it, const char *name, long *id, tr_error *err)
{
    const char *w[4];
    size_t wn[4];
    size_t nw = split_words(it->p, it->n, w, wn, 4);
    if (nw < 1)
        return 0;
    char q[64];
    if (word_is(w[0], wn[0], "cst:")) {
        if (nw < 2 || token_long(w[1], wn[1], id) || *id < 1 || *id > INT_MAX)
            return parse_fail(err, name, it->line, "'# cst:' needs a constraint number >= 1, got '%s'",
                              nw < 2 ? "" : quote(q, sizeof q, w[1], wn[1]));
        return 1;
    }
    return 0;
}

typedef struct vect_state {
    lexer lx;
    cst_def *defs;
    size_t ndefs, capdefs;
    tr_error *err;
} vect_state;

static int add_def(vect_state *st, const cst_def *d)
{
    for (size_t i = 0; i < st->ndefs; i++)
        if (st->defs[i].c.id == d->c.id)
            return parse_fail(st->err, st->lx.name, d->line, "constraint %d defined twice (first on line %zu)",
                              d->c.id, st->defs[i].line);
    if (st->ndefs == st->capdefs) {
        size_t cap = st->capdefs ? 2 * st->capdefs : 8;
        cst_def *g = realloc(st->defs, cap * sizeof *g);
        if (!g)
            return tr_fail(st->err, TR_ENOMEM, "out of memory reading constraints");
        st->defs = g;
        st->capdefs = cap;
    }
    st->defs[st->ndefs++] = *d;
    return TR_OK;
}

/* Next token; comments on the way are checked for constraint definitions.
 * *cst receives the number of a "# Cst: k" comment seen on the way (if cst
 * is non-NULL), with its line in *cstline. */
static int vect_token(vect_state *st, item *out, long *cst, size_t *cstline)
{
    for (;;) {
        item it = lex_next(&st->lx);
        if (it.kind != IT_COMMENT) {
            *out = it;
            return TR_OK;
        }
        cst_def d;
        int r = parse_constraint_comment(&it, st->lx.name, &d, st->err);
        if (r < 0)
            return r;
        if (r == 1) {
            int rc = add_def(st, &d);
            if (rc)
                return rc;
            continue;
        }
        long id = 0;
        r = parse_cst_comment(&it, st->lx.name, &id, st->err);
        if (r < 0)
            return r;
        if (r == 1) {
            if (!cst)
                return parse_fail(st->err, st->lx.name, it.line, "'# cst:' comment not after a vertex");
            if (*cst)
                return parse_fail(st->err, st->lx.name, it.line, "a second '# cst:' comment for one vertex");
            *cst = id;
            *cstline = it.line;
        }
    }
}

static int vect_int(vect_state *st, const char *what, long lo, long *v, size_t *line)
{
    item it;
    int rc = vect_token(st, &it, NULL, NULL);
    if (rc)
        return rc;
    *line = it.line;
    char q[64];
    if (it.kind == IT_END)
        return parse_fail(st->err, st->lx.name, it.line, "file ends where %s was expected", what);
    if (token_long(it.p, it.n, v) || *v < lo || *v > INT_MAX || *v < -(long)INT_MAX)
        return parse_fail(st->err, st->lx.name, it.line, "bad %s '%s' (an integer >= %ld)", what,
                          quote(q, sizeof q, it.p, it.n), lo);
    return TR_OK;
}

/* what is "vertex" or "colour", index its number (named only in a message). */
static int vect_double(vect_state *st, const char *what, size_t index, double *v, size_t *line, long *cst,
                       size_t *cstline)
{
    item it;
    int rc = vect_token(st, &it, cst, cstline);
    if (rc)
        return rc;
    *line = it.line;
    char q[64];
    if (it.kind == IT_END)
        return parse_fail(st->err, st->lx.name, it.line, "file ends where %s %zu was expected", what, index);
    int r = token_double(it.p, it.n, v);
    if (r)
        return parse_fail(st->err, st->lx.name, it.line, "%s in %s %zu: '%s'",
                          r == 2 ? "not a finite number" : "not a number", what, index,
                          quote(q, sizeof q, it.p, it.n));
    return TR_OK;
}

static int parse_vect(const char *name, const char *text, size_t len, tr_curve *out, tr_error *err)
{
    vect_state st = {{name, text, len, 0, 1, 0}, NULL, 0, 0, err};
    size_t *nv = NULL, *vline = NULL, *cline = NULL;
    unsigned char *closed = NULL;
    long *vfid = NULL;
    int rc = TR_OK;
    char q[64];
    memset(out, 0, sizeof *out);

    item it;
    rc = vect_token(&st, &it, NULL, NULL);
    if (rc)
        goto done;
    if (it.kind == IT_END) {
        rc = parse_fail(err, name, 1, "empty file");
        goto done;
    }
    if (!(it.n == 4 && !memcmp(it.p, "VECT", 4))) {
        rc = parse_fail(err, name, it.line, "expected the VECT header, got '%s'", quote(q, sizeof q, it.p, it.n));
        goto done;
    }
    long ncomp, nverts, ncolors;
    size_t hline, l2;
    if ((rc = vect_int(&st, "number of components", 1, &ncomp, &hline)) ||
        (rc = vect_int(&st, "number of vertices", 1, &nverts, &l2)) ||
        (rc = vect_int(&st, "number of colours", 0, &ncolors, &l2)))
        goto done;
    /* Every count needs at least two bytes of file, so a header that promises
     * more than the file can hold is refused before anything is allocated. */
    if ((size_t)ncomp > len / 2 || (size_t)nverts > len / 6 || (size_t)ncolors > len / 8) {
        rc = parse_fail(err, name, hline, "header counts (%ld components, %ld vertices, %ld colours) "
                        "exceed what a %zu-byte file can hold", ncomp, nverts, ncolors, len);
        goto done;
    }
    nv = malloc((size_t)ncomp * sizeof *nv);
    closed = malloc((size_t)ncomp);
    if (!nv || !closed) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory reading %s", name);
        goto done;
    }
    size_t sum = 0, nvline = 0;
    for (long k = 0; k < ncomp; k++) {
        long v;
        size_t line;
        if ((rc = vect_int(&st, "vertex count", -(long)INT_MAX, &v, &line)))
            goto done;
        if (k == 0)
            nvline = line;
        closed[k] = v < 0;
        nv[k] = (size_t)labs(v);
        if ((rc = check_size(closed[k], nv[k], (int)k, line, name, err)))
            goto done;
        sum += nv[k];
        if (sum > (size_t)nverts) {
            rc = parse_fail(err, name, line, "vertex counts add up to more than the %ld in the header", nverts);
            goto done;
        }
    }
    if (sum != (size_t)nverts) {
        rc = parse_fail(err, name, nvline, "vertex counts add up to %zu, the header says %ld", sum, nverts);
        goto done;
    }
    size_t csum = 0, ncline = 0;
    for (long k = 0; k < ncomp; k++) {
        long v;
        size_t line;
        if ((rc = vect_int(&st, "colour count", 0, &v, &line)))
            goto done;
        if (k == 0)
            ncline = line;
        if ((size_t)v > nv[k]) {
            rc = parse_fail(err, name, line, "component %ld has %ld colours for %zu vertices", k, v, nv[k]);
            goto done;
        }
        csum += (size_t)v;
    }
    if (csum != (size_t)ncolors) {
        rc = parse_fail(err, name, ncline, "colour counts add up to %zu, the header says %ld", csum, ncolors);
        goto done;
    }

    if ((rc = tr_curve_alloc(out, (int)ncomp, nv, closed, err)))
        goto done;
    vline = malloc(out->nv * sizeof *vline);
    cline = malloc(out->nv * sizeof *cline);
    vfid = calloc(out->nv, sizeof *vfid);
    if (!vline || !cline || !vfid) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory reading %s", name);
        goto done;
    }
    long *pending = NULL; /* where a "# Cst:" comment goes: the last vertex read */
    size_t *pending_line = NULL;
    /* VECT is a stream of numbers, so a number missing from (or added to)
     * one line shifts every later one and the count only fails at the end.
     * When the first two vertices stand one to a line, as plCurve and every
     * writer we know put them, every vertex must: the line that breaks the
     * layout is the one reported. */
    int one_per_line = 0;
    for (size_t i = 0; i < out->nv; i++) {
        size_t cl[3];
        for (int a = 0; a < 3; a++) {
            if ((rc = vect_double(&st, "vertex", i, &out->x[3 * i + a], &cl[a], a == 0 ? pending : NULL,
                                  pending_line)))
                goto done;
            if (a == 0)
                vline[i] = cl[0];
        }
        int own_line = cl[1] == cl[0] && cl[2] == cl[0] && (i == 0 || cl[0] > vline[i - 1]);
        if (i == 1)
            one_per_line = own_line && cl[0] > vline[0];
        if (i == 0 && !own_line)
            one_per_line = 0;
        if (i >= 2 && one_per_line && !own_line) {
            if (cl[0] == vline[i - 1])
                rc = parse_fail(err, name, cl[0], "more than 3 numbers on the line of vertex %zu (the vertices "
                                "stand one to a line)", i - 1);
            else
                rc = parse_fail(err, name, cl[0], "%d number%s on the line of vertex %zu, which needs 3 (the "
                                "vertices stand one to a line)", cl[1] == cl[0] ? 2 : 1, cl[1] == cl[0] ? "s" : "", i);
            goto done;
        }
        pending = &vfid[i];
        pending_line = &cline[i];
    }
    for (long j = 0; j < ncolors; j++) {
        for (int a = 0; a < 4; a++) {
            double v;
            size_t line;
            if ((rc = vect_double(&st, "colour", (size_t)j, &v, &line, (j == 0 && a == 0) ? pending : NULL, pending_line)))
                goto done;
        }
    }
    rc = vect_token(&st, &it, ncolors == 0 ? pending : NULL, pending_line);
    if (rc)
        goto done;
    if (it.kind != IT_END) {
        rc = parse_fail(err, name, it.line, "unexpected text after the last %s: '%s'",
                        ncolors ? "colour" : "vertex", quote(q, sizeof q, it.p, it.n));
        goto done;
    }
    if ((rc = check_edges(out, vline, name, err)))
        goto done;

    /* Resolve "# Cst: k" against the definitions; every definition is kept
     * (in file order) so that a file round-trips even with unused ones. */
    int any = 0;
    for (size_t i = 0; i < out->nv; i++)
        any |= vfid[i] != 0;
    if (any || st.ndefs) {
        for (size_t d = 0; d < st.ndefs; d++) {
            int r = tr_curve_add_constraint(out, &st.defs[d].c, err);
            if (r < 0) {
                rc = r;
                goto done;
            }
        }
        if (!out->vcst) {
            out->vcst = malloc(out->nv * sizeof *out->vcst);
            if (!out->vcst) {
                rc = tr_fail(err, TR_ENOMEM, "out of memory reading constraints");
                goto done;
            }
        }
        for (size_t i = 0; i < out->nv; i++) {
            out->vcst[i] = -1;
            if (!vfid[i])
                continue;
            size_t d = 0;
            while (d < st.ndefs && st.defs[d].c.id != vfid[i])
                d++;
            if (d == st.ndefs) {
                rc = parse_fail(err, name, cline[i], "vertex %zu refers to undefined constraint %ld", i, vfid[i]);
                goto done;
            }
            out->vcst[i] = (int)d;
        }
    }

done:
    if (rc)
        tr_curve_free(out);
    free(nv);
    free(closed);
    free(vline);
    free(cline);
    free(vfid);
    free(st.defs);
    return rc;
}

/* ----------------------------------------------------- TSV and KnotPlot */

/* Line-oriented: three numbers per line, '#' comments, blank lines end a
 * component (TSV) or are ignored (KnotPlot, one component). All closed. */
static int parse_lines(const char *name, const char *text, size_t len, int multi, tr_curve *out,
                       tr_error *err)
{
    double *x = NULL;
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
        size_t nw = split_words(text + b, e - b, w, wn, 4);
        if (nw == 0) {
            /* A blank line ends a component; a comment line does not. */
            if (!comment && multi && cur) {
                if ((rc = check_size(1, cur, (int)ncomp - 1, compline, name, err)))
                    goto done;
                cur = 0;
            }
            continue;
        }
        if (nw != 3) {
            rc = parse_fail(err, name, line, "expected 3 numbers (x y z), got %zu fields", nw);
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
            size_t *gl = realloc(vline, cap * sizeof *gl);
            if (!gl) {
                rc = tr_fail(err, TR_ENOMEM, "out of memory reading %s", name);
                goto done;
            }
            vline = gl;
            capx = cap;
        }
        for (int a = 0; a < 3; a++) {
            int r = token_double(w[a], wn[a], &x[3 * nx + (size_t)a]);
            if (r) {
                rc = parse_fail(err, name, line, "%s: '%s'", r == 2 ? "not a finite number" : "not a number",
                                quote(q, sizeof q, w[a], wn[a]));
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
        rc = parse_fail(err, name, 1, "empty file (no vertices)");
        goto done;
    }
    if (cur && (rc = check_size(1, cur, (int)ncomp - 1, compline, name, err)))
        goto done;
    if (ncomp > INT_MAX) {
        rc = parse_fail(err, name, line, "too many components");
        goto done;
    }
    if ((rc = tr_curve_alloc(out, (int)ncomp, nv, NULL, err)))
        goto done;
    memcpy(out->x, x, 3 * nx * sizeof *x);
    rc = check_edges(out, vline, name, err);

done:
    if (rc)
        tr_curve_free(out);
    free(x);
    free(vline);
    free(nv);
    return rc;
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
    if (fmt == TR_FORMAT_AUTO)
        fmt = tr_format_from_name(name);
    if (fmt == TR_FORMAT_AUTO) {
        /* By content: a VECT file starts (after comments) with the word VECT. */
        lexer lx = {name, text, len, 0, 1, 0};
        item it;
        do
            it = lex_next(&lx);
        while (it.kind == IT_COMMENT);
        fmt = (it.kind == IT_TOKEN && it.n == 4 && !memcmp(it.p, "VECT", 4)) ? TR_FORMAT_VECT : TR_FORMAT_TSV;
    }
    switch (fmt) {
    case TR_FORMAT_VECT: return parse_vect(name, text, len, out, err);
    case TR_FORMAT_TSV: return parse_lines(name, text, len, 1, out, err);
    case TR_FORMAT_KNOTPLOT: return parse_lines(name, text, len, 0, out, err);
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

/* Each line of comments becomes "# line". */
static void sb_comments(tr_text *b, const char *comments)
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

/* The number a constraint is written under: its own id when the ids are
 * distinct and positive (so files round-trip), otherwise its index + 1. */
static int cst_number(const tr_curve *c, int k, int keep_ids) { return keep_ids ? c->cst[k].id : k + 1; }

static int ids_usable(const tr_curve *c)
{
    for (int k = 0; k < c->ncst; k++) {
        if (c->cst[k].id < 1)
            return 0;
        for (int j = 0; j < k; j++)
            if (c->cst[j].id == c->cst[k].id)
                return 0;
    }
    return 1;
}

static void write_vect(tr_text *b, const tr_curve *c, const char *comments)
{
    tr_text_printf(b, "VECT\n");
    sb_comments(b, comments);
    tr_text_printf(b, "%d %zu 0 # components vertices colours\n", c->ncomp, c->nv);
    for (int k = 0; k < c->ncomp; k++)
        tr_text_printf(b, k ? " %s%zu" : "%s%zu", c->closed[k] ? "-" : "", tr_comp_nv(c, k));
    tr_text_printf(b, " # vertices per component (negative: closed)\n");
    for (int k = 0; k < c->ncomp; k++)
        tr_text_printf(b, k ? " 0" : "0");
    tr_text_printf(b, " # colours per component\n");
    int keep = ids_usable(c);
    for (int k = 0; k < c->ncst; k++) {
        const tr_constraint *q = &c->cst[k];
        int id = cst_number(c, k, keep);
        switch (q->kind) {
        case TR_CST_FIXED:
            tr_text_printf(b, "# Constraint %d Fixed %.17g %.17g %.17g\n", id, q->p[0], q->p[1], q->p[2]);
            break;
        case TR_CST_LINE:
            tr_text_printf(b, "# Constraint %d Line %.17g %.17g %.17g %.17g %.17g %.17g\n", id, q->u[0], q->u[1],
                      q->u[2], q->p[0], q->p[1], q->p[2]);
            break;
        case TR_CST_PLANE:
            tr_text_printf(b, "# Constraint %d Plane %.17g %.17g %.17g %.17g\n", id, q->u[0], q->u[1], q->u[2], q->d);
            break;
        }
    }
    for (int k = 0; k < c->ncomp; k++) {
        tr_text_printf(b, "# component %d\n", k);
        for (size_t i = c->start[k]; i < c->start[k + 1]; i++) {
            const double *v = c->x + 3 * i;
            if (c->vcst && c->vcst[i] >= 0)
                tr_text_printf(b, "%.17g %.17g %.17g # Cst: %d\n", v[0], v[1], v[2], cst_number(c, c->vcst[i], keep));
            else
                tr_text_printf(b, "%.17g %.17g %.17g\n", v[0], v[1], v[2]);
        }
    }
}

static void write_lines(tr_text *b, const tr_curve *c, const char *comments)
{
    sb_comments(b, comments);
    for (int k = 0; k < c->ncomp; k++) {
        if (k)
            tr_text_printf(b, "\n");
        for (size_t i = c->start[k]; i < c->start[k + 1]; i++) {
            const double *v = c->x + 3 * i;
            tr_text_printf(b, "%.17g\t%.17g\t%.17g\n", v[0], v[1], v[2]);
        }
    }
}

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
        write_vect(&b, c, comments);
    else
        write_lines(&b, c, comments);
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

