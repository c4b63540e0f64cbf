/* The public API's curves: the handle, its arrays, the start curves and the
 * curve files (tightrope.h). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "api/api_internal.h"
#include "curve/curve_io.h"
#include "curve/generate.h"
#include "tighten/knot_notation_start.h"

/* The public status codes are the internal ones (error.h), so a status
 * passes through unchanged. */
_Static_assert((int)TIGHTROPE_EIO == (int)TR_EIO &&
                   (int)TIGHTROPE_EPARSE == (int)TR_EPARSE &&
                   (int)TIGHTROPE_EINVAL == (int)TR_EINVAL &&
                   (int)TIGHTROPE_ENOMEM == (int)TR_ENOMEM &&
                   (int)TIGHTROPE_EGEOMETRY == (int)TR_EGEOMETRY &&
                   (int)TIGHTROPE_EOPENCL == (int)TR_EOPENCL &&
                   (int)TIGHTROPE_ETOPOLOGY == (int)TR_ETOPOLOGY &&
                   (int)TIGHTROPE_EINTERRUPTED == (int)TR_EINTERRUPTED &&
                   (int)TIGHTROPE_EUNSUPPORTED == (int)TR_EUNSUPPORTED,
               "public and internal status codes differ");

int tr_api_fail(tightrope_error *out, int status, const tr_error *err)
{
    if (out) {
        out->status = status;
        snprintf(out->message, sizeof out->message, "%s", err && err->msg[0] ? err->msg : tr_strerror(status));
    }
    return status;
}

int tr_api_wrap(tr_curve *c, tightrope_curve **out, tightrope_error *err)
{
    tightrope_curve *h = malloc(sizeof *h);
    if (!h) {
        tr_curve_free(c);
        tr_error e;
        return tr_api_fail(err, tr_fail(&e, TR_ENOMEM, "out of memory"), &e);
    }
    h->c = *c;
    memset(c, 0, sizeof *c);
    *out = h;
    return TIGHTROPE_OK;
}

const char *tightrope_strerror(int status) { return tr_strerror(status); }

const char *tightrope_version(void) { return TIGHTROPE_VERSION; }

/* The checks a curve file's reader makes (curve_io.c), on arrays: sizes,
 * finite coordinates, no zero-length edge, numbers that hold the shape. */
static int check_arrays(const tr_curve *c, tr_error *e)
{
    for (int k = 0; k < c->ncomp; k++) {
        size_t n = tr_comp_nv(c, k);
        if (c->closed[k] && n < 3)
            return tr_fail(e, TR_EINVAL, "closed component %d has %zu vertices, needs at least 3", k, n);
        if (!c->closed[k] && n < 2)
            return tr_fail(e, TR_EINVAL, "open component %d has %zu vertices, needs at least 2", k, n);
        for (size_t j = 0; j < n; j++) {
            const double *a = c->x + 3 * (c->start[k] + j);
            if (!isfinite(a[0]) || !isfinite(a[1]) || !isfinite(a[2]))
                return tr_fail(e, TR_EINVAL, "vertex %zu of component %d is not finite (%g, %g, %g)", j, k, a[0],
                               a[1], a[2]);
        }
        for (size_t j = 1; j <= n; j++) {
            if (j == n && !c->closed[k])
                break;
            const double *a = c->x + 3 * (c->start[k] + j - 1), *b = c->x + 3 * (c->start[k] + j % n);
            if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
                return j == n ? tr_fail(e, TR_EINVAL,
                                        "last vertex of closed component %d coincides with its first (a closed "
                                        "component does not repeat its first vertex)", k)
                              : tr_fail(e, TR_EINVAL, "vertex %zu of component %d coincides with the previous vertex",
                                        j, k);
        }
    }
    size_t v;
    int rc = tr_curve_check_resolution(c, &v, e);
    return rc ? TR_EINVAL : TR_OK;
}

int tightrope_curve_new(int ncomp, const size_t *offsets, const int *closed, const double *xyz,
                        tightrope_curve **out, tightrope_error *err)
{
    tr_error e = {{0}};
    if (!out || ncomp < 1 || !offsets || !xyz)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "a curve needs at least one component, offsets and "
                                                        "coordinates"), &e);
    *out = NULL;
    if (offsets[0] != 0)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "offsets[0] is %zu, not 0", offsets[0]), &e);
    size_t *nv = malloc((size_t)ncomp * sizeof *nv);
    unsigned char *cl = malloc((size_t)ncomp);
    if (!nv || !cl) {
        free(nv);
        free(cl);
        return tr_api_fail(err, tr_fail(&e, TR_ENOMEM, "out of memory"), &e);
    }
    int rc = TR_OK;
    for (int k = 0; k < ncomp && rc == TR_OK; k++) {
        if (offsets[k + 1] < offsets[k] || offsets[k + 1] > SIZE_MAX / 24)
            rc = tr_fail(&e, TR_EINVAL, "offsets[%d] = %zu is below offsets[%d] = %zu", k + 1, offsets[k + 1], k,
                         offsets[k]);
        nv[k] = offsets[k + 1] - offsets[k];
        cl[k] = closed ? closed[k] != 0 : 1;
    }
    tr_curve c = {0};
    if (rc == TR_OK && (rc = tr_curve_alloc(&c, ncomp, nv, cl, &e)) == TR_OK) {
        memcpy(c.x, xyz, 3 * c.nv * sizeof *c.x);
        if ((rc = check_arrays(&c, &e)) != TR_OK)
            tr_curve_free(&c);
    }
    free(nv);
    free(cl);
    if (rc != TR_OK)
        return tr_api_fail(err, rc, &e);
    return tr_api_wrap(&c, out, err);
}

int tightrope_curve_copy(const tightrope_curve *h, tightrope_curve **out, tightrope_error *err)
{
    tr_error e = {{0}};
    tr_curve c;
    int rc = tr_curve_copy(&c, &h->c, &e);
    return rc ? tr_api_fail(err, rc, &e) : tr_api_wrap(&c, out, err);
}

void tightrope_curve_free(tightrope_curve *h)
{
    if (!h)
        return;
    tr_curve_free(&h->c);
    free(h);
}

size_t tightrope_curve_vertices(const tightrope_curve *h) { return h->c.nv; }
int tightrope_curve_components(const tightrope_curve *h) { return h->c.ncomp; }
size_t tightrope_curve_offset(const tightrope_curve *h, int k)
{
    return k >= 0 && k <= h->c.ncomp ? h->c.start[k] : 0;
}
int tightrope_curve_closed(const tightrope_curve *h, int k)
{
    return k >= 0 && k < h->c.ncomp ? h->c.closed[k] : 0;
}
int tightrope_curve_constraints(const tightrope_curve *h)
{
    int n = 0;
    for (size_t i = 0; h->c.vcst && i < h->c.nv; i++)
        n += h->c.vcst[i] >= 0;
    return n;
}
const double *tightrope_curve_xyz(const tightrope_curve *h) { return h->c.x; }

/* A whole word as a number: 0 ok, else not one. */
static int word_double(const char *w, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(w, &end);
    return end == w || *end || errno || !isfinite(*v);
}

static int word_int(const char *w, int *v)
{
    char *end;
    errno = 0;
    long l = strtol(w, &end, 10);
    if (end == w || *end || errno || l < INT_MIN || l > INT_MAX)
        return -1;
    *v = (int)l;
    return 0;
}

/* Splits spec on blanks into at most max words (in buf); the count, or
 * max + 1 when there are more. */
static int split_words(const char *spec, char *buf, size_t bufn, char **w, int max)
{
    snprintf(buf, bufn, "%s", spec);
    int n = 0;
    char *save = NULL; /* strtok_r: strtok's hidden state is global */
    for (char *p = strtok_r(buf, " \t\n", &save); p; p = strtok_r(NULL, " \t\n", &save)) {
        if (n == max)
            return max + 1;
        w[n++] = p;
    }
    return n;
}

/* a start by a table's name (want_link -1: a knot's or a link's) */
static int start_named(const char *name, int want_link, size_t n, tr_curve *c, tr_error *e)
{
    tr_knot_made made;
    tr_knot_notation nt = {.name = name, .want_link = want_link, .n = n};
    return tr_knot_start_make(&nt, c, &made, e);
}

int tightrope_make(const char *spec, size_t n, tightrope_curve **out, tightrope_error *err)
{
    tr_error e = {{0}};
    char buf[256], *w[4];
    /* notation, any length: "braid 1,-2,1,-2" or "pd [[1,5,2,4],...]" */
    const char *rest = spec ? spec + strspn(spec, " \t") : NULL;
    if (out && rest && (!strncmp(rest, "braid ", 6) || !strncmp(rest, "pd ", 3))) {
        *out = NULL;
        tr_curve nc;
        tr_knot_made made;
        int braid = rest[0] == 'b';
        tr_knot_notation nt = {.braid = braid ? rest + 6 : NULL, .pd = braid ? NULL : rest + 3, .want_link = -1, .n = n};
        int nrc = tr_knot_start_make(&nt, &nc, &made, &e);
        return nrc ? tr_api_fail(err, nrc, &e) : tr_api_wrap(&nc, out, err);
    }
    if (!spec || !out || strlen(spec) >= sizeof buf)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "no curve named (torus P Q, trefoil, circle, hopf, clasp)"),
                           &e);
    *out = NULL;
    int nw = split_words(spec, buf, sizeof buf, w, 3);
    if (nw == 0)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "no curve named (torus P Q, trefoil, circle, hopf, clasp)"),
                           &e);
    if (n && n < 3)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "%zu vertices: a curve needs at least 3", n), &e);
    tr_curve c = {0};
    int rc;
    const char *kind = w[0];
    double v = 0.0;
    if (!strcmp(kind, "torus") || !strcmp(kind, "trefoil")) {
        int p = 2, q = 3;
        int is_torus = !strcmp(kind, "torus");
        if (is_torus ? nw != 3 || word_int(w[1], &p) || word_int(w[2], &q) : nw != 1)
            return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "bad torus knot '%s' (\"torus P Q\", two integers)",
                                            spec), &e);
        rc = tr_make_torus(&c, p, q, n ? n : 200, &e);
    } else if (!strcmp(kind, "circle") || !strcmp(kind, "hopf") || !strcmp(kind, "clasp")) {
        int takes = strcmp(kind, "hopf") != 0;
        if (nw > 1 + takes || (nw == 2 && word_double(w[1], &v)))
            return tr_api_fail(err, tr_fail(&e, TR_EINVAL, takes ? "bad '%s' (\"%s\" or \"%s NUMBER\")"
                                                                 : "bad '%s' (\"%s\" takes no argument)",
                                            spec, kind, kind), &e);
        if (!strcmp(kind, "circle"))
            rc = tr_make_circle(&c, nw == 2 ? v : 3.0, n ? n : 64, &e);
        else if (!strcmp(kind, "hopf"))
            rc = tr_make_hopf(&c, n ? n : 64, &e);
        else
            rc = tr_make_clasp(&c, n ? n : 100, nw == 2 ? v : 5.0, &e);
    } else if ((!strcmp(kind, "knot") || !strcmp(kind, "link")) && nw == 2) {
        /* by name, from KnotInfo's and LinkInfo's tables, the type checked */
        rc = start_named(w[1], !strcmp(kind, "link"), n, &c, &e);
    } else if (nw == 1 && strcmp(kind, "knot") && strcmp(kind, "link")) {
        /* a bare name: a knot's or a link's */
        rc = start_named(kind, -1, n, &c, &e);
    } else {
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "unknown curve '%s' (knot NAME, link NAME, a name such as "
                                                        "7_4, torus P Q, trefoil, circle [R], hopf, clasp [H])", spec),
                           &e);
    }
    return rc ? tr_api_fail(err, rc, &e) : tr_api_wrap(&c, out, err);
}

int tightrope_read(const char *path, tightrope_curve **out, tightrope_error *err)
{
    tr_error e = {{0}};
    if (!path || !out)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "no file named"), &e);
    *out = NULL;
    tr_curve c;
    int rc = tr_curve_read(path, TR_FORMAT_AUTO, &c, &e);
    return rc ? tr_api_fail(err, rc, &e) : tr_api_wrap(&c, out, err);
}

int tightrope_parse(const char *name, const char *text, size_t len, tightrope_curve **out, tightrope_error *err)
{
    tr_error e = {{0}};
    if (!text || !out)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "no text to parse"), &e);
    *out = NULL;
    tr_curve c;
    int rc = tr_curve_parse(name ? name : "text", text, len, TR_FORMAT_AUTO, &c, &e);
    return rc ? tr_api_fail(err, rc, &e) : tr_api_wrap(&c, out, err);
}

int tightrope_write(const char *path, const tightrope_curve *h, const char *comments, tightrope_error *err)
{
    tr_error e = {{0}};
    if (!path || !h)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "no file or curve"), &e);
    int rc = tr_curve_write(path, TR_FORMAT_AUTO, &h->c, comments, &e);
    return rc ? tr_api_fail(err, rc, &e) : TIGHTROPE_OK;
}
