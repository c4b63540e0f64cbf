/* This file contains the Newton solver's resumable state: taken from the
 * solver between two steps, set up in a solver again, and written to and
 * read from a file (newton.h tr_newton_state has what it holds and why).
 *
 * The file is binary, in this machine's byte order (a marker says which,
 * and a file of the other order is refused): the state's doubles are the
 * solver's bits, which a text format would have to print in full (%a) for
 * no reader but this one, at a size (N = 200 640: 3 nv positions twice, 2 nv
 * multipliers, some 10^5 strut rows) that a state written every few minutes
 * makes worth keeping small. Layout: the magic, the version and the byte
 * order marker; the sizes (nv, ncomp, nfixed, nstrut, has_best); the
 * scalars; the arrays; the end marker. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "solver/newton_internal.h"
#include "util/text_file.h"

#define STATE_MAGIC "tightrope-newton-state\n"
/* 2: the low parts (has_lo, ylo, best_lo); version 1 is read as well */
#define STATE_VERSION 2u
#define STATE_ORDER 0x01020304u
#define STATE_END 0x454e4421u /* "END!" */

void tr_newton_state_free(tr_newton_state *s)
{
    if (!s)
        return;
    free(s->comp_nv);
    free(s->y);
    free(s->build);
    free(s->lam_e);
    free(s->lam_m);
    free(s->strut_a);
    free(s->strut_b);
    free(s->strut_lam);
    free(s->l0);
    free(s->scale_m);
    free(s->best_y);
    free(s->ylo);
    free(s->best_lo);
    memset(s, 0, sizeof *s);
}

/* ---- from and to the solver ---- */

int tr_newton_i_state_fill(solver *s, const double *y, const tr_newton_loop *lp, long steps, double seconds,
                           tr_error *err)
{
    tr_newton_state *o = &s->out;
    size_t nv = s->nv, n = s->n;
    int nc = s->nc;
    if (!o->y) {
        o->comp_nv = malloc((size_t)nc * sizeof *o->comp_nv);
        o->y = malloc(n * sizeof *o->y);
        o->build = malloc(3 * nv * sizeof *o->build);
        o->lam_e = malloc(nv * sizeof *o->lam_e);
        o->lam_m = malloc(nv * sizeof *o->lam_m);
        o->l0 = malloc((size_t)nc * sizeof *o->l0);
        o->scale_m = malloc((size_t)nc * sizeof *o->scale_m);
        o->best_y = malloc(n * sizeof *o->best_y);
        if (!o->comp_nv || !o->y || !o->build || !o->lam_e || !o->lam_m || !o->l0 || !o->scale_m || !o->best_y) {
            tr_newton_state_free(o);
            return tr_fail(err, TR_ENOMEM, "out of memory (Newton state, %zu vertices)", nv);
        }
    }
    /* only the rows that hold something: the list is rebuilt where it was
     * built (o->build), and a pair without a multiplier starts at 0 there */
    size_t ns = 0;
    for (size_t r = 0; r < s->nsp; r++)
        ns += s->sp[r].lam != 0.0;
    size_t cap = ns ? ns : 1;
    size_t *a = realloc(o->strut_a, cap * sizeof *a);
    if (a)
        o->strut_a = a;
    size_t *b = a ? realloc(o->strut_b, cap * sizeof *b) : NULL;
    if (b)
        o->strut_b = b;
    double *l = b ? realloc(o->strut_lam, cap * sizeof *l) : NULL;
    if (l)
        o->strut_lam = l;
    if (!l) {
        tr_newton_state_free(o);
        return tr_fail(err, TR_ENOMEM, "out of memory (Newton state, %zu strut rows)", ns);
    }
    o->nv = nv;
    o->ncomp = nc;
    for (int k = 0; k < nc; k++)
        o->comp_nv[k] = tr_comp_nv(&s->w, k);
    memcpy(o->y, y, n * sizeof *y);
    o->has_lo = s->ylo != NULL;
    if (o->has_lo) {
        if (!o->ylo)
            o->ylo = malloc(3 * nv * sizeof *o->ylo);
        if (!o->best_lo)
            o->best_lo = calloc(3 * nv, sizeof *o->best_lo);
        if (!o->ylo || !o->best_lo) {
            tr_newton_state_free(o);
            return tr_fail(err, TR_ENOMEM, "out of memory (Newton state, %zu vertices)", nv);
        }
        memcpy(o->ylo, s->ylo, 3 * nv * sizeof *o->ylo);
        if (s->best_lo)
            memcpy(o->best_lo, s->best_lo, 3 * nv * sizeof *o->best_lo);
    }
    memcpy(o->build, s->w.x, 3 * nv * sizeof *o->build);
    memcpy(o->lam_e, s->lam_e, nv * sizeof *o->lam_e);
    memcpy(o->lam_m, s->lam_m, nv * sizeof *o->lam_m);
    o->nstrut = 0;
    for (size_t r = 0; r < s->nsp; r++)
        if (s->sp[r].lam != 0.0) {
            o->strut_a[o->nstrut] = s->sp[r].a;
            o->strut_b[o->nstrut] = s->sp[r].b;
            o->strut_lam[o->nstrut++] = s->sp[r].lam;
        }
    memcpy(o->l0, s->l0, (size_t)nc * sizeof *o->l0);
    memcpy(o->scale_m, s->scale_m, (size_t)nc * sizeof *o->scale_m);
    memcpy(o->fixed, s->fixed, sizeof o->fixed);
    o->nfixed = s->nfixed;
    o->mu = s->mu;
    o->band = s->band;
    o->max_bend = s->max_bend;
    o->guard = s->guard;
    o->bend_cap = s->bend_cap;
    o->warm_residual = s->warm_residual;
    o->viol_tol = lp->viol_tol;
    o->omega = lp->omega;
    o->prev_viol = lp->prev_viol;
    o->lm = lp->lm;
    o->prev_len = lp->prev_len;
    o->iter = lp->iter;
    o->outer = lp->outer;
    o->inner = lp->inner;
    o->settled = lp->settled;
    o->last_full = lp->last_full;
    o->moved = lp->moved;
    o->stuck = lp->stuck;
    o->inner_done = lp->inner_done;
    o->has_best = s->best_y && isfinite(s->best_rl);
    if (o->has_best) {
        memcpy(o->best_y, s->best_y, n * sizeof *o->best_y);
        o->best_rl = s->best_rl;
        o->best_viol_edge = s->best_viol_edge;
        o->best_thickness = s->best_thickness;
        o->best_restored = s->best_restored;
    }
    o->steps = steps;
    o->seconds = seconds;
    return TR_OK;
}

int tr_newton_i_state_apply(solver *s, const tr_newton_state *r, int warm, double *y, tr_newton_loop *lp,
                            tr_error *err)
{
    size_t nv = s->nv;
    int nc = s->nc;
    if (r->nv != nv || r->ncomp != nc)
        return tr_fail(err, TR_EINVAL, "newton: the state is of %zu vertices in %d components, the curve has %zu in %d",
                       r->nv, r->ncomp, nv, nc);
    for (int k = 0; k < nc; k++)
        if (r->comp_nv[k] != tr_comp_nv(&s->w, k))
            return tr_fail(err, TR_EINVAL, "newton: the state's component %d has %zu vertices, the curve's %zu", k + 1,
                           r->comp_nv[k], tr_comp_nv(&s->w, k));
    if (r->nfixed < 0 || r->nfixed > 6)
        return tr_fail(err, TR_EINVAL, "newton: the state holds %d gauge coordinates", r->nfixed);
    for (int k = 0; k < r->nfixed; k++)
        if (r->fixed[k] >= s->n)
            return tr_fail(err, TR_EINVAL, "newton: the state's gauge holds coordinate %zu of %zu", r->fixed[k], s->n);
    /* the scales the stopped run's start fixed, not the resumed iterate's:
     * the rows, the penalty's unit and the exclusion gap are those it had */
    memcpy(s->l0, r->l0, (size_t)nc * sizeof *s->l0);
    memcpy(s->scale_m, r->scale_m, (size_t)nc * sizeof *s->scale_m);
    s->l0min = INFINITY;
    for (int k = 0; k < nc; k++)
        s->l0min = fmin(s->l0min, s->l0[k]);
    tr_newton_i_set_gaps(s);
    memcpy(s->fixed, r->fixed, sizeof s->fixed);
    s->nfixed = r->nfixed;
    s->mu = r->mu;
    s->band = r->band;
    s->max_bend = r->max_bend;
    s->guard = r->guard;
    s->bend_cap = r->bend_cap;
    s->warm_residual = s->start_residual = r->warm_residual;
    memcpy(y, r->y, s->n * sizeof *y);
    /* the low parts with them (minimise keeps them); none from version 1 */
    free(s->ylo);
    s->ylo = NULL;
    if (r->has_lo && r->ylo) {
        if (!(s->ylo = malloc(3 * nv * sizeof *s->ylo)))
            return tr_fail(err, TR_ENOMEM, "out of memory (Newton state, %zu vertices)", nv);
        memcpy(s->ylo, r->ylo, 3 * nv * sizeof *s->ylo);
    }
    /* the list where the stopped run built it: the same pairs, so its
     * multipliers go back pair by pair, and the next rebuild comes when
     * it would have */
    int rc = tr_newton_i_rebuild(s, r->build, &s->first_bound, err);
    if (rc)
        return rc;
    if (warm) {
        /* the multipliers by least squares at the iterate: the edges'
         * tension as at a start (solver_init), the rest the warm start's */
        for (size_t r2 = 0; r2 < s->nsp; r2++)
            s->sp[r2].lam = 0.0;
        if (!(s->p->stop && *s->p->stop) && (rc = tr_newton_i_warm_multipliers(s, y, err)))
            return rc;
    } else {
        memcpy(s->lam_e, r->lam_e, nv * sizeof *s->lam_e);
        memcpy(s->lam_m, r->lam_m, nv * sizeof *s->lam_m);
        tr_strut_pair *from = malloc((r->nstrut ? r->nstrut : 1) * sizeof *from);
        if (!from)
            return tr_fail(err, TR_ENOMEM, "out of memory (Newton state, %zu strut rows)", r->nstrut);
        for (size_t q = 0; q < r->nstrut; q++)
            from[q] = (tr_strut_pair){.a = r->strut_a[q], .b = r->strut_b[q], .lam = r->strut_lam[q]};
        qsort(from, r->nstrut, sizeof *from, tr_strut_pair_cmp);
        tr_strut_pairs_carry(from, r->nstrut, s->sp, s->nsp);
        free(from);
    }
    *lp = (tr_newton_loop){.omega = r->omega, .prev_viol = r->prev_viol, .lm = r->lm, .prev_len = r->prev_len,
                           .viol_tol = r->viol_tol, .iter = r->iter, .outer = r->outer, .inner = r->inner,
                           .settled = r->settled, .last_full = r->last_full, .moved = r->moved, .stuck = r->stuck,
                           .inner_done = r->inner_done};
    return TR_OK;
}

/* ---- the file ---- */

typedef struct buf {
    unsigned char *p;
    size_t n, cap;
    int oom;
} buf;

static void put(buf *b, const void *v, size_t len)
{
    if (b->oom || len == 0)
        return;
    if (b->n + len > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->n + len)
            cap *= 2;
        unsigned char *q = realloc(b->p, cap);
        if (!q) {
            b->oom = 1;
            return;
        }
        b->p = q;
        b->cap = cap;
    }
    memcpy(b->p + b->n, v, len);
    b->n += len;
}

static void put_u64(buf *b, uint64_t v) { put(b, &v, sizeof v); }
static void put_i32(buf *b, int32_t v) { put(b, &v, sizeof v); }
static void put_sizes(buf *b, const size_t *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        put_u64(b, (uint64_t)v[i]);
}

/* The state's scalars in the file's order, named once for the writer
 * and the reader (a field added to one and not the other would shift
 * every field after it): the offsets come from these lists, and each
 * field's type is checked against its list's */
#define STATE_DOUBLE_LIST(X)                                                                                     \
    X(mu) X(band) X(max_bend) X(guard) X(viol_tol) X(warm_residual) X(omega) X(prev_viol) X(lm) X(prev_len)      \
        X(best_rl) X(best_viol_edge) X(best_thickness) X(seconds)
#define STATE_INT_LIST(X)                                                                                        \
    X(bend_cap) X(iter) X(outer) X(inner) X(settled) X(last_full) X(moved) X(stuck) X(inner_done) X(best_restored)
#define STATE_OFFSET(f) offsetof(tr_newton_state, f),
#define STATE_IS_DOUBLE(f) _Static_assert(sizeof(((tr_newton_state *)0)->f) == sizeof(double), #f " is a double");
#define STATE_IS_INT(f) _Static_assert(sizeof(((tr_newton_state *)0)->f) == sizeof(int), #f " is an int");
static const size_t STATE_DOUBLE_FIELDS[] = {STATE_DOUBLE_LIST(STATE_OFFSET)};
static const size_t STATE_INT_FIELDS[] = {STATE_INT_LIST(STATE_OFFSET)};
STATE_DOUBLE_LIST(STATE_IS_DOUBLE)
STATE_INT_LIST(STATE_IS_INT)
#define STATE_DOUBLES (sizeof STATE_DOUBLE_FIELDS / sizeof STATE_DOUBLE_FIELDS[0])
#define STATE_INTS (sizeof STATE_INT_FIELDS / sizeof STATE_INT_FIELDS[0])
_Static_assert(sizeof STATE_DOUBLE_FIELDS / sizeof STATE_DOUBLE_FIELDS[0] == 14 &&
                   sizeof STATE_INT_FIELDS / sizeof STATE_INT_FIELDS[0] == 10,
               "the file's layout: 14 doubles, 10 ints (a change is a new STATE_VERSION)");

int tr_newton_state_write(const char *path, const tr_newton_state *s, tr_error *err)
{
    buf b = {0};
    size_t nv = s->nv, n = 3 * nv + (size_t)s->ncomp;
    put(&b, STATE_MAGIC, strlen(STATE_MAGIC));
    uint32_t head[2] = {STATE_VERSION, STATE_ORDER};
    put(&b, head, sizeof head);
    put_u64(&b, nv);
    put_i32(&b, s->ncomp);
    put_i32(&b, s->nfixed);
    put_u64(&b, s->nstrut);
    put_i32(&b, s->has_best);
    put_i32(&b, s->has_lo);
    for (size_t k = 0; k < STATE_DOUBLES; k++)
        put(&b, (const char *)s + STATE_DOUBLE_FIELDS[k], sizeof(double));
    for (size_t k = 0; k < STATE_INTS; k++) {
        int v;
        memcpy(&v, (const char *)s + STATE_INT_FIELDS[k], sizeof v);
        put_i32(&b, (int32_t)v);
    }
    put_u64(&b, (uint64_t)s->steps);
    put_sizes(&b, s->fixed, 6);
    put_sizes(&b, s->comp_nv, (size_t)s->ncomp);
    put(&b, s->l0, (size_t)s->ncomp * sizeof(double));
    put(&b, s->scale_m, (size_t)s->ncomp * sizeof(double));
    put(&b, s->y, n * sizeof(double));
    put(&b, s->build, 3 * nv * sizeof(double));
    put(&b, s->lam_e, nv * sizeof(double));
    put(&b, s->lam_m, nv * sizeof(double));
    put_sizes(&b, s->strut_a, s->nstrut);
    put_sizes(&b, s->strut_b, s->nstrut);
    put(&b, s->strut_lam, s->nstrut * sizeof(double));
    if (s->has_best)
        put(&b, s->best_y, n * sizeof(double));
    if (s->has_lo) {
        put(&b, s->ylo, 3 * nv * sizeof(double));
        put(&b, s->best_lo, 3 * nv * sizeof(double));
    }
    uint32_t end = STATE_END;
    put(&b, &end, sizeof end);
    if (b.oom) {
        free(b.p);
        return tr_fail(err, TR_ENOMEM, "out of memory (writing %s)", path);
    }
    int rc = tr_write_file_atomic(path, (const char *)b.p, b.n, err);
    free(b.p);
    return rc;
}

int tr_newton_state_is_file(const char *path)
{
    char magic[sizeof STATE_MAGIC - 1];
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    size_t got = fread(magic, 1, sizeof magic, f);
    fclose(f);
    return got == sizeof magic && !memcmp(magic, STATE_MAGIC, sizeof magic);
}

typedef struct reader {
    const unsigned char *p;
    size_t n, at;
    const char *path;
    int bad;
} reader;

static int get(reader *r, void *v, size_t len)
{
    if (r->bad)
        return 0;
    if (len > r->n - r->at) {
        r->bad = 1;
        return 0;
    }
    memcpy(v, r->p + r->at, len);
    r->at += len;
    return 1;
}

static uint64_t get_u64(reader *r)
{
    uint64_t v = 0;
    get(r, &v, sizeof v);
    return v;
}

static int32_t get_i32(reader *r)
{
    int32_t v = 0;
    get(r, &v, sizeof v);
    return v;
}

static void get_sizes(reader *r, size_t *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        v[i] = (size_t)get_u64(r);
}

/* the arrays of a state of this size, none read yet */
static int alloc_state(tr_newton_state *s, size_t nv, int nc, size_t nstrut, int has_best)
{
    size_t n = 3 * nv + (size_t)nc, ns = nstrut ? nstrut : 1;
    s->comp_nv = malloc((size_t)nc * sizeof *s->comp_nv);
    s->l0 = malloc((size_t)nc * sizeof *s->l0);
    s->scale_m = malloc((size_t)nc * sizeof *s->scale_m);
    s->y = malloc(n * sizeof *s->y);
    s->build = malloc(3 * nv * sizeof *s->build);
    s->lam_e = malloc(nv * sizeof *s->lam_e);
    s->lam_m = malloc(nv * sizeof *s->lam_m);
    s->strut_a = malloc(ns * sizeof *s->strut_a);
    s->strut_b = malloc(ns * sizeof *s->strut_b);
    s->strut_lam = malloc(ns * sizeof *s->strut_lam);
    s->best_y = has_best ? malloc(n * sizeof *s->best_y) : NULL;
    return s->comp_nv && s->l0 && s->scale_m && s->y && s->build && s->lam_e && s->lam_m && s->strut_a &&
           s->strut_b && s->strut_lam && (!has_best || s->best_y);
}

int tr_newton_state_read(const char *path, tr_newton_state *s, tr_error *err)
{
    memset(s, 0, sizeof *s);
    FILE *f = fopen(path, "rb");
    if (!f)
        return tr_fail(err, TR_EIO, "cannot open %s", path);
    unsigned char *data = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? 2 * cap : 1 << 20;
            unsigned char *q = realloc(data, cap);
            if (!q) {
                free(data);
                fclose(f);
                return tr_fail(err, TR_ENOMEM, "out of memory (reading %s)", path);
            }
            data = q;
        }
        size_t got = fread(data + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    int ioerr = ferror(f);
    fclose(f);
    if (ioerr) {
        free(data);
        return tr_fail(err, TR_EIO, "cannot read %s", path);
    }
    reader r = {.p = data, .n = n, .path = path};
    int rc = TR_OK;
    char magic[sizeof STATE_MAGIC - 1];
    uint32_t head[2] = {0, 0};
    if (!get(&r, magic, sizeof magic) || memcmp(magic, STATE_MAGIC, sizeof magic)) {
        rc = tr_fail(err, TR_EPARSE, "%s: not a Newton solver state (no \"%.*s\" at byte 0)", path,
                     (int)sizeof magic - 1, STATE_MAGIC);
        goto out;
    }
    get(&r, head, sizeof head);
    if (!r.bad && head[1] != STATE_ORDER) {
        rc = tr_fail(err, TR_EPARSE, "%s: a Newton state of another byte order (byte %zu)", path, r.at - 4);
        goto out;
    }
    if (!r.bad && head[0] != STATE_VERSION && head[0] != 1u) {
        rc = tr_fail(err, TR_EPARSE, "%s: a Newton state of version %u, this build reads 1 and %u (byte %zu)", path,
                     head[0], STATE_VERSION, r.at - 8);
        goto out;
    }
    uint64_t nv = get_u64(&r);
    int32_t nc = get_i32(&r), nfixed = get_i32(&r);
    uint64_t nstrut = get_u64(&r);
    int32_t has_best = get_i32(&r);
    int32_t has_lo = head[0] >= 2u ? get_i32(&r) : 0;
    /* the sizes must be possible, and the file as long as they say,
     * before anything is allocated for them */
    size_t sizes_at = r.at;
    if (r.bad)
        goto cut;
    if (nv == 0 || nv > ((uint64_t)1 << 40) || nc < 1 || (uint64_t)nc > nv || nfixed < 0 || nfixed > 6 ||
        nstrut > ((uint64_t)1 << 40) || (has_best != 0 && has_best != 1) || (has_lo != 0 && has_lo != 1)) {
        rc = tr_fail(err, TR_EPARSE, "%s: impossible sizes before byte %zu (%llu vertices, %d components, %d gauge "
                     "coordinates, %llu strut rows)", path, sizes_at, (unsigned long long)nv, (int)nc, (int)nfixed,
                     (unsigned long long)nstrut);
        goto out;
    }
    {
        uint64_t ny = 3 * nv + (uint64_t)nc;
        uint64_t need = (uint64_t)r.at + STATE_DOUBLES * 8 + STATE_INTS * 4 + 8 + 6 * 8 + (uint64_t)nc * 24 + ny * 8 +
                        5 * nv * 8 + nstrut * 24 + (has_best ? ny * 8 : 0) + (has_lo ? 6 * nv * 8 : 0) + 4;
        if ((uint64_t)r.n < need) {
            rc = tr_fail(err, TR_EPARSE, "%s: cut short at byte %zu (its sizes, %llu vertices and %llu strut rows, "
                         "need %llu bytes)", path, r.n, (unsigned long long)nv, (unsigned long long)nstrut,
                         (unsigned long long)need);
            goto out;
        }
    }
    if (!alloc_state(s, (size_t)nv, nc, (size_t)nstrut, has_best) ||
        (has_lo && (!(s->ylo = malloc(3 * nv * sizeof *s->ylo)) || !(s->best_lo = malloc(3 * nv * sizeof *s->best_lo))))) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (reading %s, %llu vertices)", path, (unsigned long long)nv);
        goto out;
    }
    s->nv = (size_t)nv;
    s->ncomp = nc;
    s->nfixed = nfixed;
    s->nstrut = (size_t)nstrut;
    s->has_best = has_best;
    s->has_lo = has_lo;
    for (size_t k = 0; k < STATE_DOUBLES; k++)
        get(&r, (char *)s + STATE_DOUBLE_FIELDS[k], sizeof(double));
    for (size_t k = 0; k < STATE_INTS; k++) {
        int v = get_i32(&r);
        memcpy((char *)s + STATE_INT_FIELDS[k], &v, sizeof v);
    }
    s->steps = (long)get_u64(&r);
    size_t nvv = (size_t)nv, ny = 3 * nvv + (size_t)nc;
    get_sizes(&r, s->fixed, 6);
    get_sizes(&r, s->comp_nv, (size_t)nc);
    get(&r, s->l0, (size_t)nc * sizeof(double));
    get(&r, s->scale_m, (size_t)nc * sizeof(double));
    get(&r, s->y, ny * sizeof(double));
    get(&r, s->build, 3 * nvv * sizeof(double));
    get(&r, s->lam_e, nvv * sizeof(double));
    get(&r, s->lam_m, nvv * sizeof(double));
    get_sizes(&r, s->strut_a, s->nstrut);
    get_sizes(&r, s->strut_b, s->nstrut);
    get(&r, s->strut_lam, s->nstrut * sizeof(double));
    if (has_best)
        get(&r, s->best_y, ny * sizeof(double));
    if (has_lo) {
        get(&r, s->ylo, 3 * nvv * sizeof(double));
        get(&r, s->best_lo, 3 * nvv * sizeof(double));
    }
    uint32_t end = 0;
    get(&r, &end, sizeof end);
    if (r.bad)
        goto cut;
    if (end != STATE_END || r.at != r.n) {
        rc = tr_fail(err, TR_EPARSE, "%s: no end marker at byte %zu (the sizes and the file disagree)", path,
                     r.at - sizeof end);
        goto out;
    }
    /* what the solver would index with */
    size_t total = 0;
    for (int k = 0; k < nc; k++)
        total += s->comp_nv[k];
    if (total != nvv) {
        rc = tr_fail(err, TR_EPARSE, "%s: components of %zu vertices in all, not %zu", path, total, nvv);
        goto out;
    }
    for (size_t q = 0; q < s->nstrut; q++)
        if (s->strut_a[q] >= nvv || s->strut_b[q] >= nvv) {
            rc = tr_fail(err, TR_EPARSE, "%s: strut row %zu names vertex %zu of %zu", path, q + 1,
                         s->strut_a[q] >= nvv ? s->strut_a[q] : s->strut_b[q], nvv);
            goto out;
        }
    goto out;
cut:
    rc = tr_fail(err, TR_EPARSE, "%s: cut short at byte %zu", path, r.n);
out:
    free(data);
    if (rc)
        tr_newton_state_free(s);
    return rc;
}
