/* This file contains the OpenCL backend's frame: open and close, upload,
 * download, save, restore, measure, and the launch helpers the operations'
 * files share (opencl_state.h). Every operation of backend.h runs as kernels
 * over device buffers, following the reference's order of operations (see
 * the kernels' comments). Per step the host reads back only the few scalars
 * each op reports; coordinates cross the bus only in upload and download. */
#include "backend/opencl/backend_opencl.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/opencl_state.h"
#include "util/device_spec.h"
#include "util/vec3.h"

const char *const clb_kernel_names[K_COUNT] = {KERNELS(NAME)};

void clb_release(cl_mem *m)
{
    if (*m)
        clReleaseMemObject(*m);
    *m = NULL;
}

static void cl_destroy(void *sp)
{
    cl_state *s = sp;
    if (!s)
        return;
    cl_mem *m[] = {&s->start, &s->ne,   &s->cidx, &s->cst,  &s->gap,  &s->x,    &s->x_saved,   &s->ebar,
                   &s->ebar_saved, &s->debar, &s->force,  &s->field,    &s->field_tmp,    &s->dx,   &s->vterm_a,
                   &s->vterm_b,    &s->vterm_c,   &s->sc,   &s->upper_count,   &s->upper_first, &s->pair_off,
                   &s->pair_a,    &s->pair_b,   &s->part, &s->rzp, &s->row_c,   &s->row_grad,
                   &s->row_active,  &s->row_s,   &s->row_t,   &s->y,    &s->r,    &s->p,
                   &s->q,     &s->b,    &s->cgq,  &s->cdeb, &s->changed,
                   &s->pdiag, &s->z,    &s->edge_off,   &s->edge_work,   &s->closed, &s->pcr_set0,
                   &s->pcr_p,    &s->pcr_q,   &s->pcr_uu,  &s->ebar_part, &s->curv, &s->tmid,
                   &s->tends, &s->aadj, &s->aadjn, &s->act, &s->actc,
                   &s->aaoff, &s->acoef, &s->agrad, &s->sab, &s->sw, &s->dist, &s->nbr, &s->blkf};
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
        clb_release(m[i]);
    clb_rows_free(&s->rows);
    for (int i = 0; i < K_COUNT; i++)
        if (s->k[i])
            clReleaseKernel(s->k[i]);
    if (s->tree_ready)
        tr_cl_tree_free(&s->tree);
    tr_cl_reduce_free(&s->red);
    tr_cl_topology_free(&s->topo);
    if (s->prog)
        clReleaseProgram(s->prog);
    tr_cl_ctx_close(&s->ctx);
    tr_curve_free(&s->shape);
    free(s->h_start);
    free(s->h_ne);
    free(s);
}

int clb_buffer(cl_state *s, cl_mem *m, size_t bytes, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    clb_release(m);
    TR_CL_CHECK((*m = clCreateBuffer(s->ctx.context, CL_MEM_READ_WRITE, bytes ? bytes : 8, NULL, &e), e));
cleanup:
    return rc;
}

/* Sets kernel id's arguments 0, 1, ... from ap (TR_CL_A pairs up to TR_CL_END). */
static int set_args(cl_state *s, int id, va_list ap, tr_error *err)
{
    return tr_cl_vargs(err, __FILE__, __LINE__, s->k[id], 0, ap);
}

/* Launches kernel id over global items in groups of local. With profiling
 * on, waits for the launch and adds its device time. */
static int enqueue(cl_state *s, int id, size_t g, size_t l, tr_error *err)
{
    int rc = tr_cl_launch(&s->ctx, s->k[id], g, l, err);
    if (rc != TR_OK)
        tr_fail_wrap(err, rc, "%s", clb_kernel_names[id]);
    return rc;
}

/* Sets the arguments and launches kernel id over its n indices (a TR_ITEMS
 * kernel: tr_cl_launch_items). */
int clb_run(cl_state *s, int id, size_t n, tr_error *err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = set_args(s, id, ap, err);
    va_end(ap);
    if (rc == TR_OK && (rc = tr_cl_launch_items(&s->ctx, s->k[id], n, err)) != TR_OK)
        tr_fail_wrap(err, rc, "%s", clb_kernel_names[id]);
    return rc;
}

/* Launches with explicit work-groups (one per component, or a single one). */
int clb_run_groups(cl_state *s, int id, size_t groups, tr_error *err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = set_args(s, id, ap, err);
    va_end(ap);
    size_t l = groups ? TR_LOCAL_SIZE : 1, g = groups ? groups * TR_LOCAL_SIZE : 1;
    return rc != TR_OK ? rc : enqueue(s, id, g, l, err);
}

/* Launches n items, each its own work-group (a CPU device runs
 * work-groups, not items, on different cores). */
int clb_run_items(cl_state *s, int id, size_t n, tr_error *err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = set_args(s, id, ap, err);
    va_end(ap);
    return rc != TR_OK ? rc : enqueue(s, id, n, 1, err);
}

/* Launches one work-group of local items. */
int clb_run_one_group(cl_state *s, int id, size_t local, tr_error *err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = set_args(s, id, ap, err);
    va_end(ap);
    return rc != TR_OK ? rc : enqueue(s, id, local, local, err);
}



int clb_read_scalars(cl_state *s, int first, int count, double *out, tr_error *err)
{
    int rc = TR_OK;
    TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->sc, CL_TRUE, (size_t)first * sizeof(double),
                                    (size_t)count * sizeof(double), out, 0, NULL, NULL));
cleanup:
    return rc;
}

/* The reference's ebar: mean edge length per component, summed in order. */
static void host_ebar(const tr_curve *c, const double *x, double *ebar)
{
    for (int k = 0; k < c->ncomp; k++) {
        size_t s = c->start[k], e = c->start[k + 1], ne = 0;
        double sum = 0.0;
        for (size_t a = s; a < e; a++) {
            size_t nx = a + 1 < e ? a + 1 : s;
            if (a + 1 == e && !c->closed[k])
                continue;
            sum += sqrt(v3_dist2(x + 3 * a, x + 3 * nx));
            ne++;
        }
        ebar[k] = ne ? sum / (double)ne : 0.0;
    }
}

static int cl_upload(void *sp, const double *x, const double *ebar, tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    double *eb = NULL;
    size_t nv = (size_t)s->nv, nc = (size_t)s->ncomp;
    if (!ebar) {
        eb = malloc(nc * sizeof *eb);
        if (!eb)
            return tr_fail(err, TR_ENOMEM, "out of memory uploading");
        host_ebar(&s->shape, x, eb);
        ebar = eb;
    }
    TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, s->x, CL_TRUE, 0, 3 * nv * sizeof(double), x, 0,
                                     NULL, NULL));
    TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, s->ebar, CL_TRUE, 0, nc * sizeof(double), ebar, 0,
                                     NULL, NULL));
    s->np = 0; /* the contact list is emptied */
    s->saved = 0;
cleanup:
    free(eb);
    return rc;
}

static int cl_download(void *sp, double *x, double *ebar, tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->x, CL_TRUE, 0, 3 * (size_t)s->nv * sizeof(double),
                                    x, 0, NULL, NULL));
    if (ebar)
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->ebar, CL_TRUE, 0,
                                        (size_t)s->ncomp * sizeof(double), ebar, 0, NULL, NULL));
cleanup:
    return rc;
}

static int cl_save(void *sp, tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->x, s->x_saved, 0, 0, 3 * (size_t)s->nv * sizeof(double),
                                    0, NULL, NULL));
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->ebar, s->ebar_saved, 0, 0,
                                    (size_t)s->ncomp * sizeof(double), 0, NULL, NULL));
    s->saved = 1;
cleanup:
    return rc;
}

static int cl_restore(void *sp, tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    if (!s->saved)
        return tr_fail(err, TR_EINVAL, "restore without a saved state");
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->x_saved, s->x, 0, 0, 3 * (size_t)s->nv * sizeof(double),
                                    0, NULL, NULL));
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->ebar_saved, s->ebar, 0, 0,
                                    (size_t)s->ncomp * sizeof(double), 0, NULL, NULL));
cleanup:
    return rc;
}

/* Row buffers for 2 nv + np rows. */
int clb_ensure_rows(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int need = 2 * s->nv + s->np;
    if (need <= s->rcap)
        return TR_OK;
    int cap = need + need / 2 + 64;
    size_t n = (size_t)cap, d = sizeof(double);
    s->rcap = 0; /* until every buffer of the group is there */
    TR_TRY(clb_buffer(s, &s->row_c, n * d, err));
    TR_TRY(clb_buffer(s, &s->row_grad, 3 * n * d, err));
    TR_TRY(clb_buffer(s, &s->row_active, n * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->row_s, n * d, err));
    TR_TRY(clb_buffer(s, &s->row_t, n * d, err));
    TR_TRY(clb_buffer(s, &s->pdiag, n * d, err));
    TR_TRY(tr_cl_reduce_reserve(&s->red, &s->ctx, n, err));
    s->rcap = cap;
cleanup:
    return rc;
}

/* Room for n partial results (part), and a reduction over them. On a GPU
 * each folding kernel's partials are its padded global size, so the chain
 * rows' and strut rows' together can outnumber the rows (a few dozen
 * vertices, a few dozen pairs). */
int clb_partials(cl_state *s, size_t n, tr_error *err)
{
    int rc = tr_cl_reduce_reserve(&s->red, &s->ctx, n, err);
    if (rc != TR_OK || (n <= s->partcap && s->part && (s->rzp || !s->tri_twist)))
        return rc;
    size_t c = n + n / 2 + 64;
    s->partcap = 0;
    rc = clb_buffer(s, &s->part, c * sizeof(double), err);
    if (rc == TR_OK && s->tri_twist)
        rc = clb_buffer(s, &s->rzp, (c + (size_t)s->ncomp) * sizeof(double), err);
    s->partcap = rc == TR_OK ? c : 0;
    return rc;
}

/* ---- reductions ---- */

static int cl_measure(void *sp, tr_measure *out, double *comp_length, double *comp_ebar,
                      tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    int nv = s->nv, np = s->np, slot = SC_COMP;
    double *cl = NULL;
    tr_measure m = {0};
    m.min_strut = INFINITY;
    TR_TRY(clb_run(s, K_measure_edges, (size_t)nv, err, A(s->x), A(s->topo.next), A(s->topo.comp),
               A(s->ebar), A(nv), A(s->vterm_a), A(s->vterm_b), END));
    TR_TRY(clb_run_groups(s, K_comp_sum, (size_t)s->ncomp, err, A(s->vterm_a), A(s->start), A(s->sc), A(slot),
                      END));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->vterm_b, nv, s->sc, SC_DEV, err));
    TR_TRY(clb_run(s, K_measure_minrad, (size_t)nv, err, A(s->x), A(s->topo.next), A(s->topo.prev), A(nv),
               A(s->vterm_c), END));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->vterm_c, nv, s->sc, SC_MINRAD, err));
    if (np > 0) {
        TR_TRY(clb_closest_pair(s, err));
    }
    if (s->saved) {
        TR_TRY(clb_run(s, K_measure_disp, (size_t)nv, err, A(s->x), A(s->x_saved), A(nv), A(s->vterm_a), END));
        TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->vterm_a, nv, s->sc, SC_DISP, err));
    }
    cl = malloc((size_t)(SC_COMP + s->ncomp) * sizeof *cl);
    if (!cl) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory measuring");
        goto cleanup;
    }
    TR_TRY(clb_read_scalars(s, 0, SC_COMP + s->ncomp, cl, err));
    for (int k = 0; k < s->ncomp; k++) {
        m.length += cl[SC_COMP + k];
        if (comp_length)
            comp_length[k] = cl[SC_COMP + k];
    }
    m.edge_dev = cl[SC_DEV + 1] > 0.0 ? cl[SC_DEV + 1] : 0.0;
    m.min_minrad = cl[SC_MINRAD];
    if (np > 0)
        m.min_strut = cl[SC_STRUT];
    if (s->saved)
        m.max_disp = cl[SC_DISP + 1];
    if (comp_ebar)
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->ebar, CL_TRUE, 0,
                                        (size_t)s->ncomp * sizeof(double), comp_ebar, 0, NULL, NULL));
    *out = m;
cleanup:
    free(cl);
    return rc;
}

static void cl_describe(void *sp, char *out, size_t size);
static int cl_profile(void *sp, tr_kernel_time *out, int max);

static const tr_backend_ops opencl_ops = {
    .name = "opencl",
    .serial = 0,
    .destroy = cl_destroy,
    .upload = cl_upload,
    .download = cl_download,
    .save = cl_save,
    .restore = cl_restore,
    .find_contacts = clb_find_contacts,
    .tension_step = clb_tension_step,
    .correct = clb_correct,
    .strut_rows = clb_strut_rows,
    .measure = cl_measure,
    .describe = cl_describe,
    .profile = cl_profile,
};

/* Threshold for the one-work-group PCR: below it a single launch with
 * global-memory barriers beats a launch per level (launch overhead); above
 * it one work-group is too few items for the rows. */
#define TR_TRI_GROUP_MAX_ROWS 4096

/* Which edge-block solver: TIGHTROPE_CL_TRIDIAG=thomas|twisted|pcr chooses
 * (pcr-group and pcr-levels force one of PCR's two launch plans; the tests
 * run each on any device); by default PCR on GPUs and accelerators, where a
 * sequential sweep is the slowest kernel of the step, and the twisted
 * factorisation on CPU devices: O(N) like Thomas (PCR is O(N log N)) but two
 * chains per component, so two cores work where Thomas keeps one. "thomas"
 * is the reference's arithmetic bit for bit. Allocates what the choice
 * needs. */
static int tridiag_choose(cl_state *s, const tr_cl_device_info *dev, tr_error *err)
{
    int rc = TR_OK;
    const char *v = getenv("TIGHTROPE_CL_TRIDIAG");
    int plan = 0; /* 1: one work-group, 2: a launch per level, 0: by size */
    if (v && *v) {
        if (strcmp(v, "pcr") && strcmp(v, "thomas") && strcmp(v, "twisted") &&
            strcmp(v, "pcr-group") && strcmp(v, "pcr-levels"))
            return tr_fail(err, TR_EINVAL,
                           "TIGHTROPE_CL_TRIDIAG='%s': use thomas, twisted, pcr, pcr-group or pcr-levels", v);
        s->tri_twist = !strcmp(v, "twisted");
        s->tri_pcr = !s->tri_twist && strcmp(v, "thomas") != 0;
        plan = !strcmp(v, "pcr-group") ? 1 : !strcmp(v, "pcr-levels") ? 2 : 0;
    } else {
        s->tri_pcr = !(dev->type & CL_DEVICE_TYPE_CPU);
        s->tri_twist = !s->tri_pcr;
    }
    size_t nv = (size_t)s->nv, d = sizeof(double);
    for (int k = 0; k < s->ncomp; k++)
        s->any_closed |= s->shape.closed[k] && s->h_ne[k] >= 3;
    if (s->tri_twist) {
        TR_TRY(clb_buffer(s, &s->tmid, 2 * (size_t)s->ncomp * d, err));
        TR_TRY(clb_buffer(s, &s->tends, 7 * (size_t)s->ncomp * d, err));
    }
    if (!s->tri_pcr)
        return TR_OK;
    int maxne = 1;
    for (int k = 0; k < s->ncomp; k++)
        maxne = s->h_ne[k] > maxne ? s->h_ne[k] : maxne;
    s->tri_levels = 0;
    while ((1L << s->tri_levels) < maxne)
        s->tri_levels++;
    s->tri_group = 0;
    if (plan == 1 || (plan == 0 && nv <= TR_TRI_GROUP_MAX_ROWS)) {
        size_t wg = 0;
        TR_CL_CHECK(clGetKernelWorkGroupInfo(s->k[K_tridiag_group], dev->did,
                                             CL_KERNEL_WORK_GROUP_SIZE, sizeof wg, &wg, NULL));
        s->tri_group = wg < 1024 ? wg : 1024;
    }
    TR_TRY(clb_buffer(s, &s->pcr_set0, 4 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->pcr_p, 4 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->pcr_q, 4 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->pcr_uu, nv * d, err));
cleanup:
    return rc;
}

static int open_on(const tr_device_choice *dev, const tr_curve *c, int profiling, tr_backend *out,
                   tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    double *x = NULL, *eb = NULL, *cst = NULL;
    int *cidx = NULL;
    if (c->nv == 0 || c->ncomp <= 0)
        return tr_fail(err, TR_EINVAL, "empty curve");
    if (c->nv >= (size_t)1 << 28)
        return tr_fail(err, TR_EINVAL, "%zu vertices: the opencl backend takes fewer than 2^28", c->nv);
    for (int k = 0; k < c->ncomp; k++)
        if (tr_comp_nv(c, k) < (c->closed[k] ? 3u : 2u))
            return tr_fail(err, TR_EGEOMETRY, "component %d has only %zu vertices", k,
                           tr_comp_nv(c, k));
    cl_state *s = calloc(1, sizeof *s);
    if (!s)
        return tr_fail(err, TR_ENOMEM, "out of memory opening the opencl backend");
    s->nv = (int)c->nv;
    s->ncomp = c->ncomp;
    size_t nv = c->nv, nc = (size_t)c->ncomp, d = sizeof(double);
    TR_TRY(tr_curve_copy(&s->shape, c, err));
    TR_TRY(tr_cl_ctx_open(&s->ctx, &dev->cl, profiling, err));
    TR_TRY(tr_cl_build_all(&s->ctx, &s->prog, err));
    for (int i = 0; i < K_COUNT; i++) {
        s->k[i] = clCreateKernel(s->prog, clb_kernel_names[i], &e);
        if (e != CL_SUCCESS) {
            tr_cl_fail(err, e, "clCreateKernel", __FILE__, __LINE__);
            rc = tr_fail_wrap(err, TR_EOPENCL, "kernel %s", clb_kernel_names[i]);
            goto cleanup;
        }
    }
    TR_TRY(tr_cl_reduce_init(&s->red, &s->ctx, s->prog, 3 * nv + 64, err));
    TR_TRY(tr_cl_tree_init(&s->tree, &s->ctx, s->prog, c, 16, err));
    s->tree_ready = 1;
    TR_TRY(tr_cl_topology_upload(&s->ctx, c, &s->topo, err));

    s->h_start = malloc((nc + 1) * sizeof(int));
    s->h_ne = malloc(nc * sizeof(int));
    x = malloc(3 * nv * d);
    eb = malloc(nc * d);
    /* one record per constraint of the curve (at least one: no empty buffers) */
    size_t ncst = c->vcst && c->ncst > 0 ? (size_t)c->ncst : 0, nrec = ncst > 0 ? ncst : 1;
    cst = calloc(TR_CST_STRIDE * nrec, d);
    cidx = malloc(nv * sizeof *cidx);
    if (!s->h_start || !s->h_ne || !x || !eb || !cst || !cidx) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory opening the opencl backend");
        goto cleanup;
    }
    for (size_t k = 0; k <= nc; k++)
        s->h_start[k] = (int)c->start[k];
    for (size_t k = 0; k < nc; k++)
        s->h_ne[k] = (int)tr_comp_ne(c, (int)k);
    /* as the reference: snap constrained vertices, then ebar from the snapped positions */
    memcpy(x, c->x, 3 * nv * d);
    for (size_t k = 0; k < ncst; k++) {
        const tr_constraint *kc = &c->cst[k];
        double *r = cst + TR_CST_STRIDE * k;
        memcpy(r + TR_CST_U, kc->u, 3 * d);
        memcpy(r + TR_CST_P, kc->p, 3 * d);
        r[TR_CST_D] = kc->d;
        r[TR_CST_KIND] = kc->kind == TR_CST_PLANE  ? TR_CST_REC_PLANE
                         : kc->kind == TR_CST_LINE ? TR_CST_REC_LINE
                                                   : TR_CST_REC_FIXED;
    }
    for (size_t i = 0; i < nv; i++) {
        int ci = ncst > 0 ? c->vcst[i] : -1;
        if (ci < 0 || ci >= (int)ncst) {
            cidx[i] = -1;
            continue;
        }
        cidx[i] = ci;
        tr_constraint_project(&c->cst[ci], x + 3 * i);
    }
    host_ebar(c, x, eb);

    TR_TRY(clb_buffer(s, &s->start, (nc + 1) * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->ne, nc * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->gap, nc * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->cidx, nv * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->cst, TR_CST_STRIDE * nrec * d, err));
    TR_TRY(clb_buffer(s, &s->x, 3 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->x_saved, 3 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->ebar, nc * d, err));
    TR_TRY(clb_buffer(s, &s->ebar_saved, nc * d, err));
    TR_TRY(clb_buffer(s, &s->debar, nc * d, err));
    TR_TRY(clb_buffer(s, &s->curv, 2 * nc * d, err));
    TR_TRY(clb_buffer(s, &s->force, 3 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->field, 3 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->field_tmp, 3 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->dx, 3 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->cgq, 3 * nv * d, err));
    TR_TRY(clb_buffer(s, &s->cdeb, nv * d, err));
    TR_TRY(clb_buffer(s, &s->blkf, nv / 4 + 1, err));
    TR_TRY(clb_buffer(s, &s->changed, sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->edge_off, nv * d, err));
    TR_TRY(clb_buffer(s, &s->edge_work, 4 * nv * d, err));
    TR_TRY(tridiag_choose(s, &dev->cl, err));
    {
        /* ~16 vertices per work-item and at most 256 groups per component;
         * depends on the sizes only, so the summation order does too */
        size_t maxnv = 1;
        for (size_t k = 0; k < nc; k++)
            maxnv = c->start[k + 1] - c->start[k] > maxnv ? c->start[k + 1] - c->start[k] : maxnv;
        size_t g = (maxnv + 16 * TR_LOCAL_SIZE - 1) / (16 * TR_LOCAL_SIZE);
        s->ebar_groups = (int)(g < 256 ? g : 256);
        if (s->ctx.block_items) /* one partial per component and jt_vertex item */
            s->ebar_groups = (int)tr_cl_items_global(&s->ctx, nv);
        TR_TRY(clb_buffer(s, &s->ebar_part, nc * (size_t)s->ebar_groups * d, err));
    }
    TR_TRY(clb_buffer(s, &s->closed, nc * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->vterm_a, nv * d, err));
    TR_TRY(clb_buffer(s, &s->vterm_b, nv * d, err));
    TR_TRY(clb_buffer(s, &s->vterm_c, nv * d, err));
    TR_TRY(clb_buffer(s, &s->sc, (SC_COMP + nc) * d, err));
    TR_TRY(clb_buffer(s, &s->upper_count, nv * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->upper_first, nv * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->pair_off, (nv + 1) * sizeof(int), err));
    s->aacap = 64;
    TR_TRY(clb_buffer(s, &s->aadj, s->aacap * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->acoef, s->aacap * d, err));
    TR_TRY(clb_buffer(s, &s->agrad, 3 * s->aacap * d, err));
    TR_TRY(clb_buffer(s, &s->aaoff, (nv + 1) * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->aadjn, nv * sizeof(int), err));
    s->pcap = 64;
    TR_TRY(clb_buffer(s, &s->pair_a, (size_t)s->pcap * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->pair_b, (size_t)s->pcap * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->act, (size_t)s->pcap * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->dist, (size_t)s->pcap * sizeof(double), err));
    TR_TRY(clb_buffer(s, &s->nbr, 4 * (size_t)s->pcap * sizeof(int), err));
    TR_TRY(clb_buffer(s, &s->actc, ((size_t)s->pcap / TR_ACT_BLOCK + 2) * sizeof(int), err));
    TR_TRY(clb_ensure_rows(s, err));

    cl_command_queue q = s->ctx.queue;
    TR_CL_CHECK(clEnqueueWriteBuffer(q, s->start, CL_TRUE, 0, (nc + 1) * sizeof(int), s->h_start, 0,
                                     NULL, NULL));
    TR_CL_CHECK(clEnqueueWriteBuffer(q, s->ne, CL_TRUE, 0, nc * sizeof(int), s->h_ne, 0, NULL, NULL));
    {
        int *cl = malloc(nc * sizeof *cl);
        if (!cl) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory opening the opencl backend");
            goto cleanup;
        }
        for (size_t k = 0; k < nc; k++)
            cl[k] = c->closed[k] ? 1 : 0;
        e = clEnqueueWriteBuffer(q, s->closed, CL_TRUE, 0, nc * sizeof(int), cl, 0, NULL, NULL);
        free(cl);
        TR_CL_CHECK(e);
    }
    double zeros = 0.0;
    TR_CL_CHECK(clEnqueueFillBuffer(q, s->edge_off, &zeros, sizeof zeros, 0, nv * d, 0, NULL, NULL));
    TR_CL_CHECK(clEnqueueWriteBuffer(q, s->cidx, CL_TRUE, 0, nv * sizeof(int), cidx, 0, NULL, NULL));
    TR_CL_CHECK(clEnqueueWriteBuffer(q, s->cst, CL_TRUE, 0, TR_CST_STRIDE * nrec * d, cst, 0, NULL, NULL));
    double zero[SC_COMP] = {0};
    TR_CL_CHECK(clEnqueueWriteBuffer(q, s->sc, CL_TRUE, 0, sizeof zero, zero, 0, NULL, NULL));
    TR_TRY(cl_upload(s, x, eb, err));

    out->ops = &opencl_ops;
    out->state = s;
    snprintf(out->description, sizeof out->description, "OpenCL %d:%d: %.100s (%.80s)",
             dev->cl.platform, dev->cl.device, dev->cl.name, dev->cl.platform_name);
    s = NULL;
cleanup:
    cl_destroy(s);
    free(x);
    free(eb);
    free(cst);
    free(cidx);
    return rc;
}

static int open_spec(const char *spec, const tr_curve *c, int profiling, tr_backend *out,
                     tr_error *err)
{
    if (!spec || !*spec)
        spec = "auto";
    if (tr_device_spec_is_reference(spec))
        return tr_fail(err, TR_EUNSUPPORTED, "'%s' is not an opencl device", spec);
    tr_device_choice dev;
    int rc = tr_device_select(spec, &dev, err);
    if (rc != TR_OK)
        return rc;
    if (dev.kind != TR_DEVICE_OPENCL) {
        const char *w = dev.warning[0] ? dev.warning : "no opencl device";
        const char *prefix = "using the serial reference: ";
        if (!strncmp(w, prefix, strlen(prefix)))
            w += strlen(prefix);
        return tr_fail(err, TR_EUNSUPPORTED, "%s", w);
    }
    memset(out, 0, sizeof *out);
    return open_on(&dev, c, profiling, out, err);
}

int tr_backend_opencl_open(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err)
{
    return open_spec(spec, c, 0, out, err);
}

int tr_backend_opencl_open_profiled(const char *spec, const tr_curve *c, tr_backend *out,
                                    tr_error *err)
{
    return open_spec(spec, c, 1, out, err);
}

_Static_assert(TR_CL_PROF_MAX == TR_BACKEND_PROFILE_MAX, "one profile table size");

static int cl_profile(void *sp, tr_kernel_time *out, int max)
{
    const tr_cl_prof *p = ((const cl_state *)sp)->ctx.prof;
    int n = 0;
    for (int i = 0; p && i < p->count && n < max; i++) {
        snprintf(out[n].kernel, sizeof out[n].kernel, "%s", p->name[i]);
        out[n].launches = p->launches[i];
        out[n].seconds = p->seconds[i];
        n++;
    }
    return n;
}

static const char *tridiag_name(const cl_state *s)
{
    return s->tri_twist ? "twisted" : !s->tri_pcr ? "thomas" : s->tri_group ? "pcr-group" : "pcr-levels";
}

const char *tr_backend_opencl_tridiag(const tr_backend *b)
{
    if (!b || b->ops != &opencl_ops)
        return NULL;
    return tridiag_name(b->state);
}

static void cl_describe(void *sp, char *out, size_t size)
{
    snprintf(out, size, "edge block %s", tridiag_name(sp));
}

static const char *type_name(cl_device_type t)
{
    if (t & CL_DEVICE_TYPE_GPU)
        return "gpu";
    if (t & CL_DEVICE_TYPE_ACCELERATOR)
        return "accelerator";
    if (t & CL_DEVICE_TYPE_CPU)
        return "cpu";
    return "other";
}

int tr_backend_opencl_list_devices(tr_device_list *out, tr_error *err)
{
    tr_cl_device_list l;
    int rc = tr_cl_enumerate(&l, err);
    if (rc != TR_OK)
        return rc;
    out->n = l.n;
    snprintf(out->none_reason, sizeof out->none_reason, "%s", l.none_reason);
    out->dev = l.n ? calloc((size_t)l.n, sizeof *out->dev) : NULL;
    if (l.n && !out->dev) {
        tr_cl_device_list_free(&l);
        return tr_fail(err, TR_ENOMEM, "out of memory listing devices");
    }
    for (int i = 0; i < l.n; i++) {
        const tr_cl_device_info *d = &l.dev[i];
        tr_device_desc *o = &out->dev[i];
        snprintf(o->id, sizeof o->id, "%d:%d", d->platform, d->device);
        snprintf(o->platform, sizeof o->platform, "%s", d->platform_name);
        snprintf(o->platform_vendor, sizeof o->platform_vendor, "%s", d->platform_vendor);
        snprintf(o->name, sizeof o->name, "%s", d->name);
        snprintf(o->vendor, sizeof o->vendor, "%s", d->vendor);
        snprintf(o->version, sizeof o->version, "%s", d->version);
        snprintf(o->driver, sizeof o->driver, "%s", d->driver);
        o->type = type_name(d->type);
        o->compute_units = d->compute_units;
        o->clock_mhz = d->clock_mhz;
        o->global_mem = (unsigned long long)d->global_mem;
        o->fp64 = d->fp64;
        o->usable = d->usable;
        snprintf(o->reason, sizeof o->reason, "%s", d->reason);
    }
    tr_cl_device_list_free(&l);
    snprintf(out->default_spec, sizeof out->default_spec, "%s", tr_device_spec_default());
    tr_device_choice pick;
    tr_error perr = {{0}};
    out->picked = tr_device_select(NULL, &pick, &perr) == TR_OK;
    if (!out->picked)
        snprintf(out->pick_error, sizeof out->pick_error, "%s", perr.msg);
    else if (pick.kind == TR_DEVICE_REFERENCE)
        snprintf(out->selected, sizeof out->selected, "reference");
    else
        snprintf(out->selected, sizeof out->selected, "%d:%d", pick.cl.platform, pick.cl.device);
    if (out->picked)
        snprintf(out->warning, sizeof out->warning, "%s", pick.warning);
    return TR_OK;
}

int tr_backend_opencl_check_spec(const char *spec, tr_error *err)
{
    tr_device_choice dc;
    return tr_device_select(spec, &dc, err);
}
