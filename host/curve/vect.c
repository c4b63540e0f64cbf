/* This file contains the VECT reader and writer: Geomview's VECT with
 * plCurve's constraint comments ("# Constraint k Kind ...", "# Cst: k"). */
#include "curve/curve_io.h"
#include "curve/curve_io_formats.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/vec3.h"

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

static item lex_next(lexer *lx)
{
    while (lx->pos < lx->len && tr_curve_io_is_space(lx->s[lx->pos])) {
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
    while (lx->pos < lx->len && !tr_curve_io_is_space(lx->s[lx->pos]) && lx->s[lx->pos] != '#')
        lx->pos++;
    it.kind = IT_TOKEN;
    it.p = lx->s + b;
    it.n = lx->pos - b;
    return it;
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

/* ------------------------------------------------------------------- VECT */

typedef struct cst_def {
    tr_constraint c;
    size_t line;
} cst_def;

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
    size_t nw = tr_curve_io_split_words(it->p, it->n, w, wn, 12);
    if (nw < 2 || !word_is(w[0], wn[0], "constraint"))
        return 0;
    long id = 0;
    if (token_long(w[1], wn[1], &id))
        return 0; /* "# Constraint violation ..." is prose, not a definition */
    char q[64];
    if (id < 1 || id > INT_MAX)
        return tr_curve_io_parse_fail(err, name, it->line, "constraint number %ld out of range (must be >= 1)", id);
    if (nw < 3)
        return tr_curve_io_parse_fail(err, name, it->line, "constraint %ld has no kind (Fixed, Line or Plane)", id);
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
        return tr_curve_io_parse_fail(err, name, it->line, "unknown constraint kind '%s' (Fixed, Line or Plane)",
                          tr_curve_io_quote(q, sizeof q, w[2], wn[2]));
    }
    if (nw != 3 + want)
        return tr_curve_io_parse_fail(err, name, it->line, "constraint %ld (%s) needs %zu numbers, got %zu", id,
                          tr_curve_io_quote(q, sizeof q, w[2], wn[2]), want, nw - 3);
    double v[6];
    for (size_t i = 0; i < want; i++) {
        int r = tr_curve_io_token_double(w[3 + i], wn[3 + i], &v[i]);
        if (r)
            return tr_curve_io_parse_fail(err, name, it->line, "constraint %ld: %s '%s'", id,
                              r == 2 ? "not a finite number" : "not a number",
                              tr_curve_io_quote(q, sizeof q, w[3 + i], wn[3 + i]));
    }
    switch (def->c.kind) {
    case TR_CST_FIXED:
        memcpy(def->c.p, v, sizeof def->c.p);
        break;
    case TR_CST_LINE:
        memcpy(def->c.u, v, sizeof def->c.u);
        memcpy(def->c.p, v + 3, sizeof def->c.p);
        if (normalize_dir(def->c.u, NULL))
            return tr_curve_io_parse_fail(err, name, it->line, "constraint %ld: line direction is zero", id);
        break;
    case TR_CST_PLANE:
        memcpy(def->c.u, v, sizeof def->c.u);
        def->c.d = v[3];
        if (normalize_dir(def->c.u, &def->c.d))
            return tr_curve_io_parse_fail(err, name, it->line, "constraint %ld: plane normal is zero", id);
        break;
    }
    return 1;
}

/* "# Cst: k" after a vertex: 1 and *id if it is one, 0 if not, or TR_EPARSE. */
static int parse_cst_comment(const item *it, const char *name, long *id, tr_error *err)
{
    const char *w[4];
    size_t wn[4];
    size_t nw = tr_curve_io_split_words(it->p, it->n, w, wn, 4);
    if (nw < 1)
        return 0;
    char q[64];
    if (word_is(w[0], wn[0], "cst:")) {
        if (nw < 2 || token_long(w[1], wn[1], id) || *id < 1 || *id > INT_MAX)
            return tr_curve_io_parse_fail(err, name, it->line, "'# cst:' needs a constraint number >= 1, got '%s'",
                              nw < 2 ? "" : tr_curve_io_quote(q, sizeof q, w[1], wn[1]));
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
            return tr_curve_io_parse_fail(st->err, st->lx.name, d->line, "constraint %d defined twice (first on line %zu)",
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
                return tr_curve_io_parse_fail(st->err, st->lx.name, it.line, "'# cst:' comment not after a vertex");
            if (*cst)
                return tr_curve_io_parse_fail(st->err, st->lx.name, it.line, "a second '# cst:' comment for one vertex");
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
        return tr_curve_io_parse_fail(st->err, st->lx.name, it.line, "file ends where %s was expected", what);
    if (token_long(it.p, it.n, v) || *v < lo || *v > INT_MAX || *v < -(long)INT_MAX)
        return tr_curve_io_parse_fail(st->err, st->lx.name, it.line, "bad %s '%s' (an integer >= %ld)", what,
                          tr_curve_io_quote(q, sizeof q, it.p, it.n), lo);
    return TR_OK;
}

/* what is "vertex" or "colour", index its number (named only in a message). */
static int vect_double(vect_state *st, const char *what, size_t index, double *v, double *vlo, size_t *line,
                       long *cst, size_t *cstline)
{
    item it;
    int rc = vect_token(st, &it, cst, cstline);
    if (rc)
        return rc;
    *line = it.line;
    char q[64];
    if (it.kind == IT_END)
        return tr_curve_io_parse_fail(st->err, st->lx.name, it.line, "file ends where %s %zu was expected", what, index);
    double lo_dummy;
    int r = tr_curve_io_token_split(it.p, it.n, v, vlo ? vlo : &lo_dummy);
    if (r)
        return tr_curve_io_parse_fail(st->err, st->lx.name, it.line, "%s in %s %zu: '%s'",
                          r == 2 ? "not a finite number" : "not a number", what, index,
                          tr_curve_io_quote(q, sizeof q, it.p, it.n));
    return TR_OK;
}

/* A vertex held by a constraint must lie on it: rounding puts it off by
 * a few ulp, and a file from another code printed to a few digits by a
 * few parts in 10^6 of its size, which tighten's first projection takes
 * up unseen. A vertex further off than half its shorter edge is not on its
 * plane (line, point) at all: projecting it would make another curve
 * (a clasp's end 45 units above its plane became one edge 45 long, and
 * tighten called the curve too coarse). */
static int check_on_constraint(const tr_curve *c, size_t i, const cst_def *def, size_t line, const char *name,
                               tr_error *err)
{
    int k = tr_curve_comp_of(c, i);
    size_t s = c->start[k], n = tr_comp_nv(c, k), j = i - s;
    /* the edges as the projection would leave them: the offence does not
     * lengthen its own yardstick */
    double on[3] = {c->x[3 * i], c->x[3 * i + 1], c->x[3 * i + 2]}, edge = INFINITY;
    tr_constraint_project(&def->c, on);
    if (c->closed[k] || j > 0)
        edge = fmin(edge, sqrt(v3_dist2(on, c->x + 3 * (s + (j + n - 1) % n))));
    if (c->closed[k] || j + 1 < n)
        edge = fmin(edge, sqrt(v3_dist2(on, c->x + 3 * (s + (j + 1) % n))));
    double off = sqrt(v3_dist2(on, c->x + 3 * i));
    if (!(off > 0.5 * edge))
        return TR_OK;
    static const char *const what[] = {"", "the point", "the line", "the plane"};
    return tr_curve_io_parse_fail(err, name, line,
                                  "vertex %zu of component %d is %.6g off %s of its constraint %d (line %zu): the "
                                  "curve does not lie on its own constraint (allowed: up to half its edge, %.3g); "
                                  "put the vertex on %s or change the constraint",
                                  j, k, off, what[def->c.kind], def->c.id, def->line, 0.5 * edge, what[def->c.kind]);
}

int tr_vect_parse(const char *name, const char *text, size_t len, tr_curve *out, tr_error *err)
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
        rc = tr_curve_io_parse_fail(err, name, 1, "empty file");
        goto done;
    }
    if (!(it.n == 4 && !memcmp(it.p, "VECT", 4))) {
        rc = tr_curve_io_parse_fail(err, name, it.line, "expected the VECT header, got '%s'", tr_curve_io_quote(q, sizeof q, it.p, it.n));
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
        rc = tr_curve_io_parse_fail(err, name, hline, "header counts (%ld components, %ld vertices, %ld colours) "
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
        if ((rc = tr_curve_io_check_size(closed[k], nv[k], (int)k, line, name, err)))
            goto done;
        sum += nv[k];
        if (sum > (size_t)nverts) {
            rc = tr_curve_io_parse_fail(err, name, line, "vertex counts add up to more than the %ld in the header", nverts);
            goto done;
        }
    }
    if (sum != (size_t)nverts) {
        rc = tr_curve_io_parse_fail(err, name, nvline, "vertex counts add up to %zu, the header says %ld", sum, nverts);
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
            rc = tr_curve_io_parse_fail(err, name, line, "component %ld has %ld colours for %zu vertices", k, v, nv[k]);
            goto done;
        }
        csum += (size_t)v;
    }
    if (csum != (size_t)ncolors) {
        rc = tr_curve_io_parse_fail(err, name, ncline, "colour counts add up to %zu, the header says %ld", csum, ncolors);
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
            double lo;
            if ((rc = vect_double(&st, "vertex", i, &out->x[3 * i + a], &lo, &cl[a], a == 0 ? pending : NULL,
                                  pending_line)))
                goto done;
            if (lo != 0.0 && (rc = tr_curve_want_lo(out, err)))
                goto done;
            if (out->lo)
                out->lo[3 * i + a] = lo;
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
                rc = tr_curve_io_parse_fail(err, name, cl[0], "more than 3 numbers on the line of vertex %zu (the vertices "
                                "stand one to a line)", i - 1);
            else
                rc = tr_curve_io_parse_fail(err, name, cl[0], "%d number%s on the line of vertex %zu, which needs 3 (the "
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
            if ((rc = vect_double(&st, "colour", (size_t)j, &v, NULL, &line, (j == 0 && a == 0) ? pending : NULL, pending_line)))
                goto done;
        }
    }
    rc = vect_token(&st, &it, ncolors == 0 ? pending : NULL, pending_line);
    if (rc)
        goto done;
    if (it.kind != IT_END) {
        rc = tr_curve_io_parse_fail(err, name, it.line, "unexpected text after the last %s: '%s'",
                        ncolors ? "colour" : "vertex", tr_curve_io_quote(q, sizeof q, it.p, it.n));
        goto done;
    }
    if ((rc = tr_curve_io_check_edges(out, vline, name, err)))
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
                rc = tr_curve_io_parse_fail(err, name, cline[i], "vertex %zu refers to undefined constraint %ld", i, vfid[i]);
                goto done;
            }
            out->vcst[i] = (int)d;
            if ((rc = check_on_constraint(out, i, &st.defs[d], vline[i], name, err)))
                goto done;
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

int tr_vect_sniff(const char *name, const char *text, size_t len)
{
    lexer lx = {name, text, len, 0, 1, 0};
    item it;
    do
        it = lex_next(&lx);
    while (it.kind == IT_COMMENT);
    return it.kind == IT_TOKEN && it.n == 4 && !memcmp(it.p, "VECT", 4);
}

/* ----------------------------------------------------------------- writing */

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

void tr_vect_format(tr_text *b, const tr_curve *c, const char *comments)
{
    tr_text_printf(b, "VECT\n");
    tr_curve_io_comments(b, comments);
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
            tr_curve_io_vertex(b, c, i, " ");
            if (c->vcst && c->vcst[i] >= 0)
                tr_text_printf(b, " # Cst: %d\n", cst_number(c, c->vcst[i], keep));
            else
                tr_text_printf(b, "\n");
        }
    }
}
