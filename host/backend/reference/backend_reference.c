/* This file contains the serial reference backend's frame: open, destroy,
 * upload, download, save, restore, measure (reference_state.h has the
 * operations' files). The backend is plain C, written to follow the
 * specification in backend.h line by line (same sums in the same order), so
 * the OpenCL backend can be held against it. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/backend.h"
#include "backend/reference/reference_state.h"
#include "geometry/neighbour_search.h"
#include "segment_distance.h"
#include "util/vec3.h"

static void ref_destroy(void *sp)
{
    ref_state *s = sp;
    if (!s)
        return;
    void *ptrs[] = {s->start, s->closed, s->comp, s->next, s->prev, s->ne, s->x, s->xs, s->ebar,
                    s->ebar_s, s->pj, s->pu, s->vcst, s->cst, s->pa, s->pb, s->adj_start, s->adj,
                    s->F, s->G, s->H, s->dx, s->debar, s->rC, s->rgrad, s->rs, s->rt, s->ract,
                    s->y, s->r, s->p, s->q, s->b, s->cgq, s->cdeb, s->pd, s->z, s->po,
                    s->tri_w, s->tri_ib, s->tri_uu, s->act, s->aadj_start, s->aadj,
                    s->sr_d, s->sr_g, s->sr_h, s->sr_sel};
    for (size_t i = 0; i < sizeof ptrs / sizeof ptrs[0]; i++)
        free(ptrs[i]);
    if (s->ns_built)
        tr_nsearch_free(&s->ns);
    free(s);
}

void rb_snap(const ref_state *s, size_t i)
{
    if (s->pj[i] != PJ_NONE)
        tr_constraint_project(&s->cst[s->vcst[i]], s->x + 3 * i);
}

void rb_project_motion(const ref_state *s, size_t i, double *v)
{
    const double *u = s->pu + 3 * i;
    switch (s->pj[i]) {
    case PJ_PLANE: {
        double d = v3_dot(v, u);
        v3_axpy(v, -d, u);
        break;
    }
    case PJ_LINE: {
        double d = v3_dot(v, u);
        v3_scale(v, d, u);
        break;
    }
    case PJ_FIXED:
        v[0] = v[1] = v[2] = 0.0;
        break;
    default:
        break;
    }
}

static void reset_ebar(ref_state *s)
{
    for (int k = 0; k < s->ncomp; k++) {
        double sum = 0.0;
        size_t ne = 0;
        for (size_t a = s->start[k]; a < s->start[k + 1]; a++) {
            if (s->next[a] < 0)
                continue;
            sum += sqrt(v3_dist2(s->x + 3 * a, s->x + 3 * (size_t)s->next[a]));
            ne++;
        }
        s->ebar[k] = ne ? sum / (double)ne : 0.0;
    }
}

static int ref_upload(void *sp, const double *x, const double *ebar, tr_error *err)
{
    (void)err;
    ref_state *s = sp;
    memcpy(s->x, x, 3 * s->nv * sizeof *x);
    if (ebar)
        memcpy(s->ebar, ebar, (size_t)s->ncomp * sizeof *ebar);
    else
        reset_ebar(s);
    s->np = 0;
    s->saved = 0;
    return TR_OK;
}

static int ref_download(void *sp, double *x, double *ebar, tr_error *err)
{
    (void)err;
    ref_state *s = sp;
    memcpy(x, s->x, 3 * s->nv * sizeof *x);
    if (ebar)
        memcpy(ebar, s->ebar, (size_t)s->ncomp * sizeof *ebar);
    return TR_OK;
}

static int ref_save(void *sp, tr_error *err)
{
    (void)err;
    ref_state *s = sp;
    memcpy(s->xs, s->x, 3 * s->nv * sizeof *s->x);
    memcpy(s->ebar_s, s->ebar, (size_t)s->ncomp * sizeof *s->ebar);
    s->saved = 1;
    return TR_OK;
}

static int ref_restore(void *sp, tr_error *err)
{
    ref_state *s = sp;
    if (!s->saved)
        return tr_fail(err, TR_EINVAL, "restore without a saved state");
    memcpy(s->x, s->xs, 3 * s->nv * sizeof *s->x);
    memcpy(s->ebar, s->ebar_s, (size_t)s->ncomp * sizeof *s->ebar);
    return TR_OK;
}

int rb_ensure_rows(ref_state *s, tr_error *err)
{
    size_t need = 2 * s->nv + s->np;
    if (need <= s->rcap)
        return TR_OK;
    size_t nc = need + need / 2 + 64;
    double **arrs[] = {&s->rC, &s->y, &s->r, &s->p, &s->q, &s->b, &s->pd, &s->z};
    for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++) {
        double *n = realloc(*arrs[i], nc * sizeof *n);
        if (!n)
            return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
        *arrs[i] = n;
    }
    double *g = realloc(s->rgrad, 3 * nc * sizeof *g);
    if (!g)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
    s->rgrad = g;
    unsigned char *act = realloc(s->ract, nc);
    if (!act)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
    s->ract = act;
    size_t npc = nc - 2 * s->nv;
    double *rs = realloc(s->rs, npc * sizeof *rs), *rt;
    if (!rs)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
    s->rs = rs;
    rt = realloc(s->rt, npc * sizeof *rt);
    if (!rt)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
    s->rt = rt;
    s->rcap = nc;
    return TR_OK;
}

/* ---- reductions ---- */

static int ref_measure(void *sp, tr_measure *out, double *comp_length, double *comp_ebar, tr_error *err)
{
    (void)err;
    ref_state *s = sp;
    tr_measure m = {0};
    m.min_strut = INFINITY;
    m.min_minrad = INFINITY;
    for (int k = 0; k < s->ncomp; k++) {
        double len = 0.0;
        for (size_t a = s->start[k]; a < s->start[k + 1]; a++) {
            if (s->next[a] < 0)
                continue;
            double l = sqrt(v3_dist2(s->x + 3 * a, s->x + 3 * (size_t)s->next[a]));
            len += l;
            double dev = fabs(l - s->ebar[k]) / s->ebar[k];
            if (dev > m.edge_dev)
                m.edge_dev = dev;
        }
        m.length += len;
        if (comp_length)
            comp_length[k] = len;
        if (comp_ebar)
            comp_ebar[k] = s->ebar[k];
    }
    for (size_t p = 0; p < s->np; p++) {
        size_t a = s->pa[p], b = s->pb[p];
        double ss, tt;
        double d = tr_segment_distance(s->x + 3 * a, s->x + 3 * (size_t)s->next[a], s->x + 3 * b,
                                       s->x + 3 * (size_t)s->next[b], &ss, &tt);
        if (d < m.min_strut)
            m.min_strut = d;
    }
    for (size_t i = 0; i < s->nv; i++) {
        if (s->prev[i] < 0 || s->next[i] < 0)
            continue;
        double a[3], b[3], c[3];
        v3_sub(a, s->x + 3 * i, s->x + 3 * (size_t)s->prev[i]);
        v3_sub(b, s->x + 3 * (size_t)s->next[i], s->x + 3 * i);
        v3_cross(c, a, b);
        double cn = v3_norm(c);
        if (cn == 0.0)
            continue;
        double la = v3_norm(a), lb = v3_norm(b);
        double mr = fmin(la, lb) * (la * lb + v3_dot(a, b)) / (2.0 * cn);
        if (mr < m.min_minrad)
            m.min_minrad = mr;
    }
    if (s->saved)
        for (size_t i = 0; i < s->nv; i++) {
            double d = sqrt(v3_dist2(s->x + 3 * i, s->xs + 3 * i));
            if (d > m.max_disp)
                m.max_disp = d;
        }
    *out = m;
    return TR_OK;
}

static const tr_backend_ops reference_ops = {
    .name = "reference",
    .serial = 1,
    .destroy = ref_destroy,
    .upload = ref_upload,
    .download = ref_download,
    .save = ref_save,
    .restore = ref_restore,
    .find_contacts = rb_find_contacts,
    .tension_step = rb_tension_step,
    .correct = rb_correct,
    .strut_rows = rb_strut_rows,
    .measure = ref_measure,
};

int tr_backend_reference_open(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err)
{
    if (spec && *spec && strcmp(spec, "reference") != 0)
        return tr_fail(err, TR_EUNSUPPORTED, "the serial reference is selected by 'reference'");
    memset(out, 0, sizeof *out);
    if (c->nv == 0 || c->ncomp <= 0)
        return tr_fail(err, TR_EINVAL, "empty curve");
    ref_state *s = calloc(1, sizeof *s);
    if (!s)
        return tr_fail(err, TR_ENOMEM, "out of memory opening the reference backend");
    size_t nv = c->nv;
    s->nv = nv;
    s->ncomp = c->ncomp;
    s->start = malloc((size_t)(c->ncomp + 1) * sizeof *s->start);
    s->closed = malloc((size_t)c->ncomp);
    s->ne = malloc((size_t)c->ncomp * sizeof *s->ne);
    s->comp = malloc(nv * sizeof *s->comp);
    s->next = malloc(nv * sizeof *s->next);
    s->prev = malloc(nv * sizeof *s->prev);
    s->x = malloc(3 * nv * sizeof *s->x);
    s->xs = malloc(3 * nv * sizeof *s->xs);
    s->ebar = malloc((size_t)c->ncomp * sizeof *s->ebar);
    s->ebar_s = malloc((size_t)c->ncomp * sizeof *s->ebar_s);
    s->debar = malloc((size_t)c->ncomp * sizeof *s->debar);
    s->pj = calloc(nv, 1);
    s->pu = calloc(3 * nv, sizeof *s->pu);
    s->vcst = malloc(nv * sizeof *s->vcst);
    s->cst = malloc((size_t)(c->ncst > 0 ? c->ncst : 1) * sizeof *s->cst);
    s->adj_start = calloc(nv + 1, sizeof *s->adj_start);
    s->F = malloc(3 * nv * sizeof *s->F);
    s->G = malloc(3 * nv * sizeof *s->G);
    s->H = malloc(3 * nv * sizeof *s->H);
    s->dx = malloc(3 * nv * sizeof *s->dx);
    s->cgq = malloc(3 * nv * sizeof *s->cgq);
    s->cdeb = malloc(nv * sizeof *s->cdeb);
    s->po = calloc(nv, sizeof *s->po);
    s->tri_w = calloc(nv, sizeof *s->tri_w);
    s->tri_ib = calloc(nv, sizeof *s->tri_ib);
    s->tri_uu = calloc(nv, sizeof *s->tri_uu);
    if (!s->start || !s->closed || !s->ne || !s->comp || !s->next || !s->prev || !s->x || !s->xs ||
        !s->ebar || !s->ebar_s || !s->debar || !s->pj || !s->pu || !s->vcst || !s->cst ||
        !s->adj_start || !s->F || !s->G || !s->H || !s->dx || !s->cgq || !s->cdeb || !s->po || !s->tri_w ||
        !s->tri_ib || !s->tri_uu) {
        ref_destroy(s);
        return tr_fail(err, TR_ENOMEM, "out of memory opening the reference backend (%zu vertices)", nv);
    }
    memcpy(s->start, c->start, (size_t)(c->ncomp + 1) * sizeof *s->start);
    memcpy(s->closed, c->closed, (size_t)c->ncomp);
    for (int k = 0; k < c->ncomp; k++) {
        size_t a = c->start[k], e = c->start[k + 1], n = e - a;
        if (n < (c->closed[k] ? 3u : 2u)) {
            ref_destroy(s);
            return tr_fail(err, TR_EGEOMETRY, "component %d has only %zu vertices", k, n);
        }
        s->ne[k] = tr_comp_ne(c, k);
        for (size_t i = a; i < e; i++) {
            s->comp[i] = k;
            s->next[i] = i + 1 < e ? (ptrdiff_t)(i + 1) : (c->closed[k] ? (ptrdiff_t)a : -1);
            s->prev[i] = i > a ? (ptrdiff_t)(i - 1) : (c->closed[k] ? (ptrdiff_t)(e - 1) : -1);
        }
    }
    if (c->ncst > 0)
        memcpy(s->cst, c->cst, (size_t)c->ncst * sizeof *s->cst);
    for (size_t i = 0; i < nv; i++) {
        s->vcst[i] = c->vcst && c->ncst > 0 ? c->vcst[i] : -1;
        if (s->vcst[i] < 0 || s->vcst[i] >= c->ncst) {
            s->vcst[i] = -1;
            continue;
        }
        const tr_constraint *k = &c->cst[s->vcst[i]];
        s->pj[i] = k->kind == TR_CST_PLANE ? PJ_PLANE : k->kind == TR_CST_LINE ? PJ_LINE : PJ_FIXED;
        memcpy(s->pu + 3 * i, k->u, 3 * sizeof(double));
    }
    memcpy(s->x, c->x, 3 * nv * sizeof *s->x);
    for (size_t i = 0; i < nv; i++)
        rb_snap(s, i);
    reset_ebar(s);
    tr_error e2;
    if (rb_ensure_rows(s, &e2) != TR_OK) {
        ref_destroy(s);
        return tr_fail(err, TR_ENOMEM, "%s", e2.msg);
    }
    out->ops = &reference_ops;
    out->state = s;
    snprintf(out->description, sizeof out->description, "serial reference (CPU, double precision)");
    return TR_OK;
}
