/* The OpenCL backend: every operation of backend.h as kernels over device
 * buffers, following the reference's order of operations (see the kernels'
 * comments). Per step the host reads back only the few scalars each op
 * reports; coordinates cross the bus only in upload and download. */
#include "backend/opencl/backend_opencl.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/cl_error.h"
#include "backend/opencl/cl_tree.h"
#include "backend/opencl/cl_reduce.h"
#include "backend/opencl/cl_topology.h"
#include "util/device_spec.h"
#include "layout.h"
#include "util/vec3.h"

/* Kernels this file launches itself (the reduction and tree modules hold their own). */
#define KERNELS(X)                                                                             \
    X(tension_force) X(tension_smooth) X(tension_move) X(pairs_upper) X(pairs_write)           \
    X(pairs_min_dist) X(rows_chain) X(rows_strut) X(cg_init) X(jt_vertex)          \
    X(jt_ebar_partial) X(jt_ebar) X(j_rows) X(cg_start) X(cg_top) X(cg_r)         \
    X(cg_p) X(dx_norm) X(step_scale) X(apply_dx) X(apply_debar) X(measure_edges)    \
    X(measure_minrad) X(measure_disp) X(comp_sum) X(cg_reset) X(release_pulling)               \
    X(project_field) X(tangent_finish) X(ebar_velocity) X(tension_smooth2) X(precond_setup)    \
    X(precond_diag) X(precond_edges) X(copy_rows) X(precond_edges_factor) X(curv_limits)       \
    X(tridiag_matrix) X(tridiag_level) X(tridiag_finish) X(tridiag_group) X(twist_factor)      \
    X(twist_factor_mid) X(twist_sweep_rows) X(twist_back_rows) X(twist_ring_fact)              \
    X(twist_ring_fix) X(adj_active_count) X(adj_active_write) X(act_count) X(act_scan)         \
    X(act_write) X(act_gather) X(adj_active_sort) X(pairs_neighbours) X(rows_strut_min)     \
    X(cg_p_ring) X(block_flags) X(jjt_rows) X(j_struts)
#define ENUM(k) K_##k,
#define NAME(k) #k,
enum { KERNELS(ENUM) K_COUNT };
static const char *const kernel_names[K_COUNT] = {KERNELS(NAME)};

typedef struct cl_state {
    tr_cl_ctx ctx;
    cl_program prog;
    cl_kernel k[K_COUNT];
    tr_cl_reduce red;
    tr_cl_tree tree;
    int tree_ready;
    tr_cl_topology topo;
    int nv, ncomp, saved;
    int *h_start, *h_ne;
    tr_curve shape; /* host copy of the topology and constraints (for upload's snap-free ebar) */
    cl_mem start, ne, cidx, cst, gap;
    cl_mem x, xs, ebar, ebar_s, debar;
    cl_mem curv; /* per component: largest turning angle and its ebar term (curv_limits) */
    cl_mem F, G, H, dx;
    cl_mem t1, t2, t3; /* nv reals: per-vertex terms for reductions */
    cl_mem sc;         /* scalars */
    /* contacts */
    int np, pcap;
    cl_mem up, first, off, pa, pb;
    cl_mem dist, nbr; /* each pair's distance (rows_strut); its neighbours in the list (pairs_neighbours) */
    /* one partial result per work-item of a folding kernel (rows_chain and
     * rows_strut: largest violations; pairs_min_dist: closest pairs; j_rows
     * and cg_r: the CG's p . q and r . r); with the twisted edge block
     * also rzp, the CG's r . z: cg_r's items' shares, then each
     * component's edge rows' (twist_ring_fact) */
    cl_mem part, rzp;
    size_t partcap;
    /* each vertex's active strut entries, per CG solve, compact (CSR by
     * aaoff, aadjn long) with each entry's weight and strut direction
     * (kernels/correct.cl adj_active_*) */
    cl_mem aadj, aadjn, aaoff, acoef, agrad;
    size_t aacap; /* entries aadj, acoef and agrad hold */
    /* The CG's row list (kernels/correct.cl row_of), built per solve: the
     * active strut rows in list order (pcap), block counts for building it. */
    cl_mem act, actc;
    cl_mem sab, sw; /* act_gather: the active struts' vertices, s, t and direction */
    cl_mem blkf;    /* CPU devices: block_flags' byte per four vertices, per solve */
    size_t scap;    /* active struts sab and sw hold */
    int cg_nl; /* rows in the list: 2 nv + active struts */
    int vcap;  /* entries of the CG's vectors y, r, p, q, b, z (by list position) */
    /* rows */
    int rcap;
    cl_mem rC, rgrad, ract, rs, rt, y, r, p, q, b;
    cl_mem cgq, cdeb, chg; /* curvature rows' second gradient and ebar derivative; a flag */
    cl_mem pdiag, z, po, tw, closed; /* preconditioner: diagonal, M^-1 r, edge off-diagonal, work */
    /* The edge block by parallel cyclic reduction (kernels/tridiag.cl) instead
     * of precond_edges' sequential sweep: level-0 set, two alternating sets,
     * the Sherman-Morrison vector; tri_group > 0: one work-group of that size
     * does the whole solve. */
    int tri_pcr, tri_levels, any_closed;
    /* Or (CPU devices) the twisted factorisation of kernels/twisted.cl: two
     * work-groups per component; scratch of 2 ncomp reals for the rows
     * beside the middle row, and 7 ncomp for the blocks' first and last
     * rows and Sherman-Morrison factors (3 ncomp) and the halves' shares of
     * r . z and r . uu (twist_back_rows, twist_sweep_rows). */
    int tri_twist;
    cl_mem tmid, tends;
    /* work-groups per component of the ebar sums (jt_ebar_partial; on CPU
     * devices jt_vertex's and jjt_rows' items, both launched over nv), and
     * their partial sums */
    int ebar_groups;
    cl_mem ebar_part;
    size_t tri_group;
    cl_mem tset0, tp, tq, tuu;
} cl_state;

static void release(cl_mem *m)
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
    cl_mem *m[] = {&s->start, &s->ne,   &s->cidx, &s->cst,  &s->gap,  &s->x,    &s->xs,   &s->ebar,
                   &s->ebar_s, &s->debar, &s->F,  &s->G,    &s->H,    &s->dx,   &s->t1,
                   &s->t2,    &s->t3,   &s->sc,   &s->up,   &s->first, &s->off,
                   &s->pa,    &s->pb,   &s->part, &s->rzp, &s->rC,   &s->rgrad,
                   &s->ract,  &s->rs,   &s->rt,   &s->y,    &s->r,    &s->p,
                   &s->q,     &s->b,    &s->cgq,  &s->cdeb, &s->chg,
                   &s->pdiag, &s->z,    &s->po,   &s->tw,   &s->closed, &s->tset0,
                   &s->tp,    &s->tq,   &s->tuu,  &s->ebar_part, &s->curv, &s->tmid,
                   &s->tends, &s->aadj, &s->aadjn, &s->act, &s->actc,
                   &s->aaoff, &s->acoef, &s->agrad, &s->sab, &s->sw, &s->dist, &s->nbr, &s->blkf};
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
        release(m[i]);
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

static int buffer(cl_state *s, cl_mem *m, size_t bytes, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    release(m);
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
        tr_fail_wrap(err, rc, "%s", kernel_names[id]);
    return rc;
}

/* Sets the arguments and launches kernel id over its n indices (a TR_ITEMS
 * kernel: tr_cl_launch_items). */
static int run(cl_state *s, int id, size_t n, tr_error *err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = set_args(s, id, ap, err);
    va_end(ap);
    if (rc == TR_OK && (rc = tr_cl_launch_items(&s->ctx, s->k[id], n, err)) != TR_OK)
        tr_fail_wrap(err, rc, "%s", kernel_names[id]);
    return rc;
}

/* Launches with explicit work-groups (one per component, or a single one). */
static int run_groups(cl_state *s, int id, size_t groups, tr_error *err, ...)
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
static int run_items(cl_state *s, int id, size_t n, tr_error *err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = set_args(s, id, ap, err);
    va_end(ap);
    return rc != TR_OK ? rc : enqueue(s, id, n, 1, err);
}

/* Launches one work-group of local items. */
static int run_one_group(cl_state *s, int id, size_t local, tr_error *err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = set_args(s, id, ap, err);
    va_end(ap);
    return rc != TR_OK ? rc : enqueue(s, id, local, local, err);
}

/* Strut rows per item when the CG's row list is built (act_count, act_write). */
#define TR_ACT_BLOCK 1024

/* Short spellings for the many argument lists below. */
#define A TR_CL_A
#define END TR_CL_END

static int read_scalars(cl_state *s, int first, int count, double *out, tr_error *err)
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
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->x, s->xs, 0, 0, 3 * (size_t)s->nv * sizeof(double),
                                    0, NULL, NULL));
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->ebar, s->ebar_s, 0, 0,
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
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->xs, s->x, 0, 0, 3 * (size_t)s->nv * sizeof(double),
                                    0, NULL, NULL));
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->ebar_s, s->ebar, 0, 0,
                                    (size_t)s->ncomp * sizeof(double), 0, NULL, NULL));
cleanup:
    return rc;
}

/* Row buffers for 2 nv + np rows. */
static int ensure_rows(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int need = 2 * s->nv + s->np;
    if (need <= s->rcap)
        return TR_OK;
    int cap = need + need / 2 + 64;
    size_t n = (size_t)cap, d = sizeof(double);
    s->rcap = 0; /* until every buffer of the group is there */
    TR_TRY(buffer(s, &s->rC, n * d, err));
    TR_TRY(buffer(s, &s->rgrad, 3 * n * d, err));
    TR_TRY(buffer(s, &s->ract, n * sizeof(int), err));
    TR_TRY(buffer(s, &s->rs, n * d, err));
    TR_TRY(buffer(s, &s->rt, n * d, err));
    TR_TRY(buffer(s, &s->pdiag, n * d, err));
    TR_TRY(tr_cl_reduce_reserve(&s->red, &s->ctx, n, err));
    s->rcap = cap;
cleanup:
    return rc;
}

/* ---- neighbour search ---- */

/* Room for n partial results (part), and a reduction over them. On a GPU
 * each folding kernel's partials are its padded global size, so the chain
 * rows' and strut rows' together can outnumber the rows (a few dozen
 * vertices, a few dozen pairs). */
static int partials(cl_state *s, size_t n, tr_error *err)
{
    int rc = tr_cl_reduce_reserve(&s->red, &s->ctx, n, err);
    if (rc != TR_OK || (n <= s->partcap && s->part && (s->rzp || !s->tri_twist)))
        return rc;
    size_t c = n + n / 2 + 64;
    s->partcap = 0;
    rc = buffer(s, &s->part, c * sizeof(double), err);
    if (rc == TR_OK && s->tri_twist)
        rc = buffer(s, &s->rzp, (c + (size_t)s->ncomp) * sizeof(double), err);
    s->partcap = rc == TR_OK ? c : 0;
    return rc;
}

/* sc[SC_STRUT] = the smallest distance of a listed pair (np > 0). */
static int closest_pair(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int np = s->np;
    size_t g = tr_cl_items_global(&s->ctx, (size_t)np);
    TR_TRY(partials(s, g, err));
    TR_TRY(run(s, K_pairs_min_dist, (size_t)np, err, A(s->x), A(s->topo.next), A(s->pa), A(s->pb),
               A(np), A(s->part), END));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->part, (int)g, s->sc, SC_STRUT, err));
cleanup:
    return rc;
}

static int cl_find_contacts(void *sp, const tr_contact_params *prm, tr_contact_stats *out,
                            tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    int nv = s->nv;
    s->np = 0;
    TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, s->gap, CL_FALSE, 0, (size_t)s->ncomp * sizeof(int),
                                     prm->exclude_gap, 0, NULL, NULL));
    int gmin = 0;
    for (int k = 0; k < s->ncomp; k++)
        gmin = k == 0 || prm->exclude_gap[k] < gmin ? prm->exclude_gap[k] : gmin;
    TR_TRY(tr_cl_tree_search(&s->tree, &s->ctx, &s->red, &s->topo, s->x, prm->cutoff, prm->tilt,
                             s->gap, gmin, err));
    cl_mem list = s->tree.list, loff = s->tree.loff;
    TR_TRY(run(s, K_pairs_upper, (size_t)nv, err, A(s->tree.count), A(list), A(loff), A(s->topo.next),
               A(nv), A(s->up), A(s->first), END));
    /* pair offsets off[0..nv], and the lists' total (2 np when symmetric) */
    TR_TRY(tr_cl_reduce_scan(&s->red, &s->ctx, s->up, nv, s->off, err));
    TR_TRY(tr_cl_reduce_count(&s->red, &s->ctx, s->tree.count, nv, s->sc, SC_LISTED, err));
    int np = 0;
    double listed = 0.0;
    TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->off, CL_FALSE, (size_t)nv * sizeof(int), sizeof np,
                                    &np, 0, NULL, NULL));
    TR_TRY(read_scalars(s, SC_LISTED, 1, &listed, err));
    /* every pair is in both edges' lists */
    if (np < 0 || np > (1 << 28) || listed != 2.0 * np) {
        rc = tr_fail(err, TR_EGEOMETRY,
                     "%d contact candidates in partner lists of %.0f entries (want 2 each, at most 2^28 "
                     "pairs): far too many, or the lists are not symmetric",
                     np, listed);
        goto cleanup;
    }
    if (np > s->pcap) {
        int pc = np + np / 2 + 64;
        s->pcap = 0; /* until every buffer of the group is there */
        TR_TRY(buffer(s, &s->pa, (size_t)pc * sizeof(int), err));
        TR_TRY(buffer(s, &s->pb, (size_t)pc * sizeof(int), err));
        TR_TRY(buffer(s, &s->act, (size_t)pc * sizeof(int), err));
        TR_TRY(buffer(s, &s->dist, (size_t)pc * sizeof(double), err));
        TR_TRY(buffer(s, &s->nbr, 4 * (size_t)pc * sizeof(int), err));
        TR_TRY(buffer(s, &s->actc, ((size_t)pc / TR_ACT_BLOCK + 2) * sizeof(int), err));
        s->pcap = pc;
    }
    TR_TRY(run(s, K_pairs_write, (size_t)nv, err, A(s->tree.count), A(list), A(loff), A(s->first),
               A(s->off), A(nv), A(s->pa), A(s->pb), END));
    if (np > 0)
        TR_TRY(run(s, K_pairs_neighbours, (size_t)nv, err, A(list), A(loff), A(s->tree.count),
                   A(s->first), A(s->off), A(s->topo.next), A(s->topo.prev), A(nv), A(s->nbr), END));
    s->np = np;
    TR_TRY(ensure_rows(s, err));
    double mind = INFINITY;
    if (np > 0) {
        TR_TRY(closest_pair(s, err));
        TR_TRY(read_scalars(s, SC_STRUT, 1, &mind, err));
    }
    if (out) {
        out->pairs = (size_t)np;
        out->min_dist = mind;
    }
cleanup:
    if (rc != TR_OK)
        s->np = 0; /* an empty list, as after an upload */
    return rc;
}

/* ---- coupled constraint correction ---- */

static int eval_rows(cl_state *s, const tr_correct_params *prm, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, np = s->np;
    double minrad = prm->minrad, ac = prm->active_curv, sd = prm->strut_dist, as = prm->active_strut;
    /* the largest violation: one partial per work-item, chain rows' first */
    size_t gc = tr_cl_items_global(&s->ctx, (size_t)nv);
    size_t gs = np > 0 ? tr_cl_items_global(&s->ctx, (size_t)np) : 0;
    int voff = (int)gc;
    TR_TRY(partials(s, gc + gs, err));
    TR_TRY(run(s, K_curv_limits, (size_t)s->ncomp, err, A(s->ebar), A(s->ncomp), A(minrad),
               A(s->curv), END));
    TR_TRY(run(s, K_rows_chain, (size_t)nv, err, A(s->x), A(s->topo.next), A(s->topo.prev),
               A(s->topo.comp), A(s->ebar), A(s->curv), A(nv), A(ac), A(s->rC), A(s->rgrad),
               A(s->ract), A(s->part), A(s->cgq), A(s->cdeb), END));
    if (np > 0)
        TR_TRY(run(s, K_rows_strut, (size_t)np, err, A(s->x), A(s->topo.next), A(s->topo.prev),
                   A(s->pa), A(s->pb), A(nv), A(np), A(sd), A(as), A(s->rC), A(s->rgrad), A(s->ract),
                   A(s->rs), A(s->rt), A(s->dist), A(s->part), A(voff), END));
    if (np > 0)
        TR_TRY(run(s, K_rows_strut_min, (size_t)np, err, A(s->x), A(s->topo.next), A(s->topo.prev),
                   A(s->pa), A(s->pb), A(s->dist), A(s->nbr), A(nv), A(np), A(s->ract), END));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->part, (int)(gc + gs), s->sc, SC_VIOL, err));
cleanup:
    return rc;
}

/* dx, debar from the row vector y (the J^T half of the operator). */
static int apply_JT(cl_state *s, const tr_correct_params *prm, cl_mem y, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv;
    double w = prm->ebar_weight;
    TR_TRY(run(s, K_jt_vertex, (size_t)nv, err, A(y), A(s->rgrad), A(s->cgq), A(s->ract), A(s->topo.next),
               A(s->topo.prev), A(s->aadj), A(s->aadjn), A(s->aaoff), A(s->acoef), A(s->agrad), A(s->cidx), A(s->cst),
               A(nv), A(s->dx), A(s->cdeb), A(s->topo.comp), A(s->ncomp), A(s->ebar_part), A(s->blkf),
               END));
    int G = s->ebar_groups;
    if (!s->ctx.block_items) /* on CPU devices jt_vertex's items sum them */
        TR_TRY(run_groups(s, K_jt_ebar_partial, (size_t)s->ncomp * (size_t)G, err, A(y), A(s->ract),
                          A(s->start), A(s->cdeb), A(nv), A(G), A(s->ebar_part), END));
    cl_mem none = NULL;
    int zero = 0;
    TR_TRY(run_groups(s, K_jt_ebar, (size_t)s->ncomp, err, A(s->ebar_part), A(s->ne), A(G), A(w),
                      A(s->debar), A(none), A(zero), END));
cleanup:
    return rc;
}

/* Solves the edge block whose level-0 set (matrix and right-hand side) is in
 * tset0 by PCR into out; sm: apply the Sherman-Morrison correction of closed
 * components (uu must be solved), else a plain solve (how uu is made). */
static int tridiag_solve(cl_state *s, int sm, cl_mem out, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv;
    cl_mem uu = sm ? s->tuu : s->pdiag; /* pdiag: any buffer, unread when !sm */
    if (s->tri_group) {
        TR_TRY(run_one_group(s, K_tridiag_group, s->tri_group, err, A(s->tri_levels), A(s->tset0),
                             A(s->tp), A(s->tq), A(s->pdiag), A(s->po), A(s->topo.comp),
                             A(s->start), A(s->ne), A(s->closed), A(uu), A(sm), A(nv), A(out),
                             END));
        return TR_OK;
    }
    cl_mem src = s->tset0, dst = s->tp;
    for (int l = 0, stride = 1; l < s->tri_levels; l++, stride *= 2) {
        TR_TRY(run(s, K_tridiag_level, (size_t)nv, err, A(stride), A(s->topo.comp), A(s->start),
                   A(s->ne), A(nv), A(src), A(dst), END));
        src = dst;
        dst = dst == s->tp ? s->tq : s->tp;
    }
    TR_TRY(run(s, K_tridiag_finish, (size_t)nv, err, A(src), A(s->pdiag), A(s->po), A(s->topo.comp),
               A(s->start), A(s->ne), A(s->closed), A(uu), A(sm), A(nv), A(out), END));
cleanup:
    return rc;
}

/* After precond_setup: the PCR level-0 matrix and, for closed components,
 * the Sherman-Morrison vector uu (once per setup; the reference re-solves it
 * in every application, same arithmetic up to rounding). */
static int tridiag_setup(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv;
    TR_TRY(run(s, K_tridiag_matrix, (size_t)nv, err, A(s->pdiag), A(s->po), A(s->topo.comp),
               A(s->start), A(s->ne), A(s->closed), A(nv), A(s->tset0), END));
    if (s->any_closed)
        TR_TRY(tridiag_solve(s, 0, s->tuu, err));
cleanup:
    return rc;
}

/* z = M^-1 r (backend.h correct (c)): the edge block by the chosen solver,
 * and with diag the diagonal on the other rows, which inside the CG loop
 * cg_r has already applied. in_loop (twisted edge block only): inside the
 * CG loop, where the closed blocks' Sherman-Morrison fix is left to
 * cg_p_ring and the edge rows' r . z goes to rzp after cg_r's rz_items
 * shares (cg_iterate). */
static int precond_apply(cl_state *s, cl_mem r, int diag, int in_loop, int rz_items,
                         tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, nl = s->cg_nl;
    size_t d = sizeof(double);
    if (s->tri_twist) {
        size_t items = 2 * (size_t)s->ncomp;
        TR_TRY(run_items(s, K_twist_sweep_rows, items, err, A(r), A(s->po), A(s->start), A(s->ne),
                         A(s->ncomp), A(nv), A(s->tw), A(s->tmid), A(s->tends), A(s->z), END));
        TR_TRY(run_items(s, K_twist_back_rows, items, err, A(r), A(s->po), A(s->start), A(s->ne),
                         A(s->ncomp), A(nv), A(s->tw), A(s->tmid), A(s->tends), A(s->z), END));
        if (s->any_closed || in_loop)
            TR_TRY(run_items(s, K_twist_ring_fact, (size_t)s->ncomp, err, A(s->pdiag), A(s->po),
                             A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->tw),
                             A(s->tends), A(s->rzp), A(rz_items), END));
        if (s->any_closed && !in_loop)
            TR_TRY(run(s, K_twist_ring_fix, (size_t)nv, err, A(s->topo.comp), A(s->ncomp), A(nv),
                       A(s->tw), A(s->tends), A(s->z), END));
    } else if (s->tri_pcr) {
        TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, r, s->tset0, 0, 3 * (size_t)nv * d,
                                        (size_t)nv * d, 0, NULL, NULL));
        TR_TRY(tridiag_solve(s, 1, s->z, err));
    } else {
        TR_TRY(run(s, K_precond_edges, (size_t)s->ncomp, err, A(r), A(s->pdiag), A(s->po),
                   A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->tw), A(s->z),
                   END));
    }
    if (diag)
        TR_TRY(run(s, K_precond_diag, (size_t)(nl - nv), err, A(r), A(s->pdiag), A(s->ract), A(nv),
                   A(s->act), A(nl), A(s->z), END));
cleanup:
    return rc;
}

/* The CG's row list for this solve (kernels/correct.cl row_of): every edge
 * and curvature row, then the active strut rows in list order; s->cg_nl
 * its length. One read of the count, once per solve. */
static int row_list(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, np = s->np, bsize = TR_ACT_BLOCK, nb = (np + TR_ACT_BLOCK - 1) / TR_ACT_BLOCK;
    int nact = 0;
    if (np > 0) {
        TR_TRY(run(s, K_act_count, (size_t)nb, err, A(s->ract), A(nv), A(np), A(bsize), A(nb),
                   A(s->actc), END));
        TR_TRY(run_groups(s, K_act_scan, 0, err, A(nb), A(s->actc), END));
        TR_TRY(run(s, K_act_write, (size_t)nb, err, A(s->ract), A(nv), A(np), A(bsize), A(nb),
                   A(s->actc), A(s->act), END));
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->actc, CL_TRUE, (size_t)nb * sizeof(int),
                                        sizeof nact, &nact, 0, NULL, NULL));
    }
    s->cg_nl = 2 * nv + nact;
cleanup:
    return rc;
}

/* Fixes the active set of a solve (the caller has evaluated the rows): the
 * CG's row list, by whose positions the solve's vectors are stored, and
 * apply_JT's compact adjacency (4 entries per active strut row). */
static int solve_rows(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv;
    TR_TRY(row_list(s, err));
    if (s->cg_nl > s->vcap) { /* the CG's vectors, by row list position */
        size_t n = (size_t)s->cg_nl + (size_t)s->cg_nl / 2 + 64, d = sizeof(double);
        s->vcap = 0;
        cl_mem *v[] = {&s->y, &s->r, &s->p, &s->q, &s->b, &s->z};
        for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
            TR_TRY(buffer(s, v[i], n * d, err));
        s->vcap = (int)n;
    }
    size_t nact = (size_t)(s->cg_nl - 2 * nv), nae = 4 * nact;
    if (nact > s->scap || !s->sab) {
        size_t c = nact + nact / 2 + 64;
        s->scap = 0;
        TR_TRY(buffer(s, &s->sab, 2 * c * sizeof(int), err));
        TR_TRY(buffer(s, &s->sw, 5 * c * sizeof(double), err));
        s->scap = c;
    }
    int na = (int)nact;
    if (na > 0)
        TR_TRY(run(s, K_act_gather, nact, err, A(s->act), A(s->pa), A(s->pb), A(s->rs), A(s->rt),
                   A(s->rgrad), A(nv), A(na), A(s->sab), A(s->sw), END));
    if (nae > s->aacap) {
        size_t c = nae + nae / 2 + 64;
        s->aacap = 0;
        TR_TRY(buffer(s, &s->aadj, c * sizeof(int), err));
        TR_TRY(buffer(s, &s->acoef, c * sizeof(double), err));
        TR_TRY(buffer(s, &s->agrad, 3 * c * sizeof(double), err));
        s->aacap = c;
    }
    /* j_rows' and cg_r's dot product partials, one per work-item (on CPU
     * devices jjt_rows', jt_ebar's and j_struts', cg_iterate) */
    TR_TRY(partials(s, 2 * tr_cl_items_global(&s->ctx, (size_t)s->cg_nl) + (size_t)s->ncomp, err));
    int izero = 0;
    TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->aadjn, &izero, sizeof izero, 0,
                                    (size_t)nv * sizeof(int), 0, NULL, NULL));
    if (na == 0) { /* no active struts: every row of the adjacency is empty */
        TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->aaoff, &izero, sizeof izero, 0,
                                        (size_t)(nv + 1) * sizeof(int), 0, NULL, NULL));
    } else {
        TR_TRY(run(s, K_adj_active_count, nact, err, A(s->act), A(s->pa), A(s->pb), A(s->topo.next),
                   A(na), A(s->aadjn), END));
        TR_TRY(tr_cl_reduce_scan(&s->red, &s->ctx, s->aadjn, nv, s->aaoff, err));
        TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->aadjn, &izero, sizeof izero, 0,
                                        (size_t)nv * sizeof(int), 0, NULL, NULL));
        TR_TRY(run(s, K_adj_active_write, nact, err, A(s->act), A(s->pa), A(s->pb), A(s->topo.next),
                   A(s->rs), A(s->rt), A(s->rgrad), A(nv), A(na), A(s->aaoff), A(s->aadjn),
                   A(s->aadj), A(s->acoef), A(s->agrad), END));
        TR_TRY(run(s, K_adj_active_sort, (size_t)nv, err, A(s->aaoff), A(nv), A(s->aadj), A(s->acoef),
                   A(s->agrad), END));
    }
    if (s->ctx.block_items && nv >= 4)
        TR_TRY(run(s, K_block_flags, (size_t)(nv / 4), err, A(s->ract), A(s->topo.next),
                   A(s->topo.prev), A(s->aadjn), A(s->cidx), A(nv), A(s->blkf), END));
cleanup:
    return rc;
}

/* j_rows' and cg_r's global size: one item per row list position on a GPU;
 * on a CPU device one unit per vertex (its edge and curvature rows) and per
 * strut row (kernels/correct.cl j_rows). */
static size_t jrows_units(const cl_state *s, int nl)
{
    return s->ctx.block_items ? (size_t)(nl - s->nv) : (size_t)nl;
}

/* q = A p on a CPU device (kernels/correct.cl jjt_rows): the chain rows
 * less their debar term (cg_r adds it), debar, the strut rows, and p . q
 * from jjt_rows' items' shares, then jt_ebar's debar term's shares per
 * component, then j_struts' items' shares. */
static int apply_JJT(cl_state *s, const tr_correct_params *prm, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, nl = s->cg_nl, G = s->ebar_groups;
    int iv = (int)tr_cl_items_global(&s->ctx, (size_t)nv), off = iv + s->ncomp;
    double reg = prm->reg, w = prm->ebar_weight;
    TR_TRY(run(s, K_jjt_rows, (size_t)nv, err, A(s->p), A(s->rgrad), A(s->cgq), A(s->ract),
               A(s->topo.next), A(s->topo.prev), A(s->aadj), A(s->aadjn), A(s->aaoff), A(s->acoef),
               A(s->agrad), A(s->cidx), A(s->cst), A(nv), A(s->dx), A(s->cdeb), A(s->topo.comp),
               A(s->ncomp), A(s->ebar_part), A(s->blkf), A(reg), A(s->q), A(s->part), END));
    TR_TRY(run_groups(s, K_jt_ebar, (size_t)s->ncomp, err, A(s->ebar_part), A(s->ne), A(G), A(w),
                      A(s->debar), A(s->part), A(iv), END));
    if (nl > 2 * nv) {
        TR_TRY(run(s, K_j_struts, (size_t)(nl - 2 * nv), err, A(s->dx), A(s->debar), A(s->cdeb),
                   A(s->rgrad), A(s->cgq), A(s->ract), A(s->topo.next), A(s->topo.prev),
                   A(s->topo.comp), A(s->sab), A(s->sw), A(s->p), A(nv), A(reg), A(s->act), A(nl),
                   A(s->q), A(s->part), A(off), END));
        off += (int)tr_cl_items_global(&s->ctx, (size_t)(nl - 2 * nv));
    }
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->part, off, s->sc, SC_PQ, err));
cleanup:
    return rc;
}

/* Preconditioned CG on A y = b from y = 0, r = b (already in place, by row
 * list position; solve_rows has run), as
 * backend.h (c): the device keeps the scalars and turns iterations after
 * convergence into no-ops; the host looks at the flag every fourth iteration. */
static int cg_iterate(cl_state *s, const tr_correct_params *prm, int *iters, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, nl = s->cg_nl;
    /* the dot products p . q and r . r come as partials per work-item of
     * j_rows (on CPU devices apply_JJT's kernels) and cg_r (solve_rows
     * reserved them) */
    int items = (int)tr_cl_items_global(&s->ctx, jrows_units(s, nl));
    cl_mem rzp = s->tri_twist ? s->rzp : NULL; /* cg_r's r . z shares: the twisted path's */
    double reg = prm->reg, w = prm->ebar_weight, tol2 = prm->cg_rtol * prm->cg_rtol, it;
    TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, s->sc, CL_FALSE, SC_TOL2 * sizeof(double),
                                     sizeof tol2, &tol2, 0, NULL, NULL));
    TR_TRY(run(s, K_precond_setup, (size_t)nl, err, A(s->rgrad), A(s->cgq), A(s->cdeb), A(s->ract),
               A(s->topo.next), A(s->topo.prev), A(s->topo.comp), A(s->ne), A(s->pa), A(s->pb),
               A(s->rs), A(s->rt), A(s->cidx), A(s->cst), A(nv), A(s->act), A(nl), A(w), A(reg), A(s->pdiag),
               A(s->po), END));
    if (s->tri_pcr) {
        TR_TRY(tridiag_setup(s, err));
    } else if (s->tri_twist) {
        TR_TRY(run_items(s, K_twist_factor, 2 * (size_t)s->ncomp, err, A(s->pdiag), A(s->po),
                         A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->tw),
                         A(s->tmid), A(s->z), END));
        TR_TRY(run_items(s, K_twist_factor_mid, (size_t)s->ncomp, err, A(s->pdiag), A(s->po),
                         A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->tw),
                         A(s->tmid), END));
    } else
        TR_TRY(run(s, K_precond_edges_factor, (size_t)s->ncomp, err, A(s->pdiag), A(s->po),
                   A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->tw), END));
    TR_TRY(precond_apply(s, s->r, 1, 0, 0, err));
    TR_TRY(run(s, K_copy_rows, (size_t)nl, err, A(s->z), A(s->p), A(nl), END));
    TR_TRY(tr_cl_reduce_dot(&s->red, &s->ctx, s->r, s->r, nl, s->sc, SC_RR, err));
    TR_TRY(tr_cl_reduce_dot(&s->red, &s->ctx, s->r, s->z, nl, s->sc, SC_RZ, err));
    TR_TRY(run_groups(s, K_cg_start, 0, err, A(s->sc), END));
    int k;
    for (k = 0; k < prm->max_cg; k++) {
        TR_TRY(run_groups(s, K_cg_top, 0, err, A(s->sc), A(k), END));
        if (k > 0 && k % 4 == 0) {
            double done;
            TR_TRY(read_scalars(s, SC_DONE, 1, &done, err));
            if (done != 0.0)
                break;
        }
        if (s->ctx.block_items)
            TR_TRY(apply_JJT(s, prm, err));
        else {
            TR_TRY(apply_JT(s, prm, s->p, err));
            TR_TRY(run(s, K_j_rows, jrows_units(s, nl), err, A(s->dx), A(s->debar), A(s->cdeb),
                       A(s->rgrad), A(s->cgq), A(s->ract), A(s->topo.next), A(s->topo.prev),
                       A(s->topo.comp), A(s->sab), A(s->sw), A(s->p), A(nv), A(reg), A(s->act),
                       A(nl), A(s->q), A(s->part), A(s->blkf), END));
            TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->part, items, s->sc, SC_PQ, err));
        }
        TR_TRY(run(s, K_cg_r, jrows_units(s, nl), err, A(s->r), A(s->q), A(s->sc), A(nl),
                   A(s->part), A(s->pdiag), A(s->ract), A(nv), A(s->act), A(s->z), A(rzp),
                   A(s->debar), A(s->cdeb), A(s->topo.comp), A(s->blkf), END));
        TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->part, items, s->sc, SC_RR, err));
        TR_TRY(precond_apply(s, s->r, 0, 1, items, err));
        if (s->tri_twist) {
            /* r . z from cg_r's and the edge block's shares, and the ring
             * fix applied where cg_p_ring reads z: two passes over the rows
             * fewer than reduce_dot, twist_ring_fix and cg_p */
            TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->rzp, items + s->ncomp, s->sc, SC_RR1, err));
            TR_TRY(run(s, K_cg_p_ring, (size_t)nl, err, A(s->y), A(s->p), A(s->z), A(s->sc), A(nl),
                       A(s->topo.comp), A(s->ncomp), A(nv), A(s->tw), A(s->tends), END));
        } else {
            TR_TRY(tr_cl_reduce_dot(&s->red, &s->ctx, s->r, s->z, nl, s->sc, SC_RR1, err));
            TR_TRY(run(s, K_cg_p, (size_t)nl, err, A(s->y), A(s->p), A(s->z), A(s->sc), A(nl), END));
        }
    }
    /* the end of the last iteration (kernels/correct.cl cg_top; nothing
     * after a break, which found the solve done) */
    TR_TRY(run_groups(s, K_cg_top, 0, err, A(s->sc), A(k), END));
    TR_TRY(read_scalars(s, SC_ITERS, 1, &it, err));
    *iters = (int)it;
cleanup:
    return rc;
}

static int cl_correct(void *sp, const tr_correct_params *prm, tr_correct_stats *out, tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    TR_TRY(ensure_rows(s, err));
    int nv = s->nv;
    double ms = prm->max_step;
    tr_correct_stats st = {0};
    int it;
    double v[2];
    for (it = 0; it < prm->max_newton; it++) {
        TR_TRY(eval_rows(s, prm, err));
        TR_TRY(read_scalars(s, SC_VIOL, 2, v, err));
        double viol = v[1] > 0.0 ? v[1] : 0.0;
        if (it == 0)
            st.viol_before = viol;
        if (viol <= prm->viol_tol)
            break;
        TR_TRY(solve_rows(s, err));
        int nl = s->cg_nl;
        TR_TRY(run(s, K_cg_init, (size_t)nl, err, A(s->rC), A(s->ract), A(nv), A(s->act), A(nl), A(s->b),
                   A(s->y), A(s->r), A(s->p), END));
        /* active rows: those of the chain counted here, the struts are the list's */
        int nchain = 2 * nv;
        TR_TRY(tr_cl_reduce_count(&s->red, &s->ctx, s->ract, nchain, s->sc, SC_NACT, err));
        int iters = 0;
        TR_TRY(cg_iterate(s, prm, &iters, err));
        st.cg_iters += iters;
        TR_TRY(apply_JT(s, prm, s->y, err));
        TR_TRY(run(s, K_dx_norm, (size_t)nv, err, A(s->dx), A(nv), A(s->t1), END));
        TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->t1, nv, s->sc, SC_MAXDX, err));
        TR_TRY(run_groups(s, K_step_scale, 0, err, A(s->sc), A(ms), END));
        TR_TRY(run(s, K_apply_dx, (size_t)nv, err, A(s->x), A(s->dx), A(s->cidx), A(s->cst), A(s->sc), A(nv), END));
        TR_TRY(run(s, K_apply_debar, (size_t)s->ncomp, err, A(s->ebar), A(s->debar), A(s->sc),
                   A(s->ncomp), END));
        double nact;
        TR_TRY(read_scalars(s, SC_NACT, 1, &nact, err));
        st.active_rows = (size_t)nact + (size_t)(nl - 2 * nv);
    }
    st.newton_iters = it;
    TR_TRY(eval_rows(s, prm, err));
    TR_TRY(read_scalars(s, SC_VIOL, 2, v, err));
    st.viol_after = v[1] > 0.0 ? v[1] : 0.0;
    if (out)
        *out = st;
cleanup:
    return rc;
}

/* ---- force evaluation ---- */

/* backend.h tension_step 2b: G <- P G, then its component tangent to the
 * active rows (releasing pulling inequality rows between passes); leaves the
 * ebar velocity's negative in debar. */
static int project_tangent(cl_state *s, const tr_correct_params *q, cl_mem G, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, n3 = 3 * nv;
    double reg0 = 0.0, zero = 0.0;
    int izero = 0;
    TR_TRY(eval_rows(s, q, err));
    TR_TRY(run(s, K_project_field, (size_t)nv, err, A(G), A(s->cidx), A(s->cst), A(nv), END));
    for (int pass = 0; pass < q->max_newton; pass++) {
        TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, G, s->dx, 0, 0, (size_t)n3 * sizeof(double), 0,
                                        NULL, NULL));
        TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->debar, &zero, sizeof zero, 0,
                                        (size_t)s->ncomp * sizeof(double), 0, NULL, NULL));
        TR_TRY(solve_rows(s, err));
        int nl = s->cg_nl;
        TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->y, &zero, sizeof zero, 0,
                                        (size_t)nl * sizeof(double), 0, NULL, NULL));
        /* b = J (G, debar = 0), no regularisation term (y = 0) */
        TR_TRY(run(s, K_j_rows, jrows_units(s, nl), err, A(s->dx), A(s->debar), A(s->cdeb), A(s->rgrad),
                   A(s->cgq), A(s->ract), A(s->topo.next), A(s->topo.prev), A(s->topo.comp),
                   A(s->sab), A(s->sw), A(s->y), A(nv), A(reg0), A(s->act), A(nl), A(s->b),
                   A(s->part), A(s->blkf), END));
        TR_TRY(run(s, K_cg_reset, (size_t)nl, err, A(s->b), A(s->y), A(s->r), A(s->p), A(nl), END));
        int iters = 0;
        TR_TRY(cg_iterate(s, q, &iters, err));
        if (pass + 1 < q->max_newton && nl > nv) {
            int changed = 0;
            TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, s->chg, CL_FALSE, 0, sizeof izero, &izero, 0,
                                             NULL, NULL));
            TR_TRY(run(s, K_release_pulling, (size_t)(nl - nv), err, A(s->ract), A(s->y), A(nv), A(s->act),
                       A(nl), A(s->chg), END));
            TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->chg, CL_TRUE, 0, sizeof changed, &changed,
                                            0, NULL, NULL));
            if (changed)
                continue;
        }
        break;
    }
    TR_TRY(apply_JT(s, q, s->y, err));
    TR_TRY(run(s, K_tangent_finish, (size_t)n3, err, A(G), A(s->dx), A(n3), END));
cleanup:
    return rc;
}

static int cl_tension_step(void *sp, const tr_tension_params *prm, tr_tension_stats *out,
                           tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    int nv = s->nv;
    double h = prm->h, mm = prm->max_move;
    TR_TRY(run(s, K_tension_force, (size_t)nv, err, A(s->x), A(s->topo.next), A(s->topo.prev), A(nv),
               A(s->F), END));
    cl_mem G = s->G, H = s->H;
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->F, G, 0, 0, 3 * (size_t)nv * sizeof(double), 0,
                                    NULL, NULL));
    for (int pass = 0; pass < prm->smooth_passes; pass++) {
        TR_TRY(run(s, K_tension_smooth, (size_t)nv, err, A(G), A(s->topo.next), A(s->topo.prev),
                   A(nv), A(H), END));
        cl_mem t = G;
        G = H;
        H = t;
    }
    TR_TRY(run(s, K_tension_smooth2, (size_t)nv, err, A(G), A(s->cidx), A(s->cst), A(nv), A(s->t1), END));
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->t1, nv, s->sc, SC_SMOOTH2, err));
    if (prm->project) {
        TR_TRY(ensure_rows(s, err));
        TR_TRY(project_tangent(s, prm->project, G, err));
        TR_TRY(tr_cl_reduce_dot(&s->red, &s->ctx, G, G, 3 * nv, s->sc, SC_FREE2, err));
    }
    TR_TRY(run(s, K_tension_move, (size_t)nv, err, A(s->x), A(s->F), A(G), A(s->cidx), A(s->cst), A(nv), A(h),
               A(mm), A(s->t1), A(s->t2), A(s->t3), END));
    if (prm->project)
        TR_TRY(run(s, K_ebar_velocity, (size_t)s->ncomp, err, A(s->ebar), A(s->debar), A(h),
                   A(s->ncomp), END));
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->t1, nv, s->sc, SC_F2, err));
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->t2, nv, s->sc, SC_PRED, err));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->t3, nv, s->sc, SC_MOVE, err));
    double v[14];
    TR_TRY(read_scalars(s, SC_F2, 14, v, err)); /* slots 16 .. 29 */
    if (out) {
        out->force2 = v[0];
        out->predicted = v[1];
        out->max_move = v[3];
        out->smooth2 = v[SC_SMOOTH2 - SC_F2];
        out->free2 = prm->project ? v[SC_FREE2 - SC_F2] : v[SC_SMOOTH2 - SC_F2];
    }
cleanup:
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
    TR_TRY(run(s, K_measure_edges, (size_t)nv, err, A(s->x), A(s->topo.next), A(s->topo.comp),
               A(s->ebar), A(nv), A(s->t1), A(s->t2), END));
    TR_TRY(run_groups(s, K_comp_sum, (size_t)s->ncomp, err, A(s->t1), A(s->start), A(s->sc), A(slot),
                      END));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->t2, nv, s->sc, SC_DEV, err));
    TR_TRY(run(s, K_measure_minrad, (size_t)nv, err, A(s->x), A(s->topo.next), A(s->topo.prev), A(nv),
               A(s->t3), END));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->t3, nv, s->sc, SC_MINRAD, err));
    if (np > 0) {
        TR_TRY(closest_pair(s, err));
    }
    if (s->saved) {
        TR_TRY(run(s, K_measure_disp, (size_t)nv, err, A(s->x), A(s->xs), A(nv), A(s->t1), END));
        TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->t1, nv, s->sc, SC_DISP, err));
    }
    cl = malloc((size_t)(SC_COMP + s->ncomp) * sizeof *cl);
    if (!cl) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory measuring");
        goto cleanup;
    }
    TR_TRY(read_scalars(s, 0, SC_COMP + s->ncomp, cl, err));
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
    .find_contacts = cl_find_contacts,
    .tension_step = cl_tension_step,
    .correct = cl_correct,
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
        TR_TRY(buffer(s, &s->tmid, 2 * (size_t)s->ncomp * d, err));
        TR_TRY(buffer(s, &s->tends, 7 * (size_t)s->ncomp * d, err));
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
    TR_TRY(buffer(s, &s->tset0, 4 * nv * d, err));
    TR_TRY(buffer(s, &s->tp, 4 * nv * d, err));
    TR_TRY(buffer(s, &s->tq, 4 * nv * d, err));
    TR_TRY(buffer(s, &s->tuu, nv * d, err));
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
        s->k[i] = clCreateKernel(s->prog, kernel_names[i], &e);
        if (e != CL_SUCCESS) {
            tr_cl_fail(err, e, "clCreateKernel", __FILE__, __LINE__);
            rc = tr_fail_wrap(err, TR_EOPENCL, "kernel %s", kernel_names[i]);
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

    TR_TRY(buffer(s, &s->start, (nc + 1) * sizeof(int), err));
    TR_TRY(buffer(s, &s->ne, nc * sizeof(int), err));
    TR_TRY(buffer(s, &s->gap, nc * sizeof(int), err));
    TR_TRY(buffer(s, &s->cidx, nv * sizeof(int), err));
    TR_TRY(buffer(s, &s->cst, TR_CST_STRIDE * nrec * d, err));
    TR_TRY(buffer(s, &s->x, 3 * nv * d, err));
    TR_TRY(buffer(s, &s->xs, 3 * nv * d, err));
    TR_TRY(buffer(s, &s->ebar, nc * d, err));
    TR_TRY(buffer(s, &s->ebar_s, nc * d, err));
    TR_TRY(buffer(s, &s->debar, nc * d, err));
    TR_TRY(buffer(s, &s->curv, 2 * nc * d, err));
    TR_TRY(buffer(s, &s->F, 3 * nv * d, err));
    TR_TRY(buffer(s, &s->G, 3 * nv * d, err));
    TR_TRY(buffer(s, &s->H, 3 * nv * d, err));
    TR_TRY(buffer(s, &s->dx, 3 * nv * d, err));
    TR_TRY(buffer(s, &s->cgq, 3 * nv * d, err));
    TR_TRY(buffer(s, &s->cdeb, nv * d, err));
    TR_TRY(buffer(s, &s->blkf, nv / 4 + 1, err));
    TR_TRY(buffer(s, &s->chg, sizeof(int), err));
    TR_TRY(buffer(s, &s->po, nv * d, err));
    TR_TRY(buffer(s, &s->tw, 4 * nv * d, err));
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
        TR_TRY(buffer(s, &s->ebar_part, nc * (size_t)s->ebar_groups * d, err));
    }
    TR_TRY(buffer(s, &s->closed, nc * sizeof(int), err));
    TR_TRY(buffer(s, &s->t1, nv * d, err));
    TR_TRY(buffer(s, &s->t2, nv * d, err));
    TR_TRY(buffer(s, &s->t3, nv * d, err));
    TR_TRY(buffer(s, &s->sc, (SC_COMP + nc) * d, err));
    TR_TRY(buffer(s, &s->up, nv * sizeof(int), err));
    TR_TRY(buffer(s, &s->first, nv * sizeof(int), err));
    TR_TRY(buffer(s, &s->off, (nv + 1) * sizeof(int), err));
    s->aacap = 64;
    TR_TRY(buffer(s, &s->aadj, s->aacap * sizeof(int), err));
    TR_TRY(buffer(s, &s->acoef, s->aacap * d, err));
    TR_TRY(buffer(s, &s->agrad, 3 * s->aacap * d, err));
    TR_TRY(buffer(s, &s->aaoff, (nv + 1) * sizeof(int), err));
    TR_TRY(buffer(s, &s->aadjn, nv * sizeof(int), err));
    s->pcap = 64;
    TR_TRY(buffer(s, &s->pa, (size_t)s->pcap * sizeof(int), err));
    TR_TRY(buffer(s, &s->pb, (size_t)s->pcap * sizeof(int), err));
    TR_TRY(buffer(s, &s->act, (size_t)s->pcap * sizeof(int), err));
    TR_TRY(buffer(s, &s->dist, (size_t)s->pcap * sizeof(double), err));
    TR_TRY(buffer(s, &s->nbr, 4 * (size_t)s->pcap * sizeof(int), err));
    TR_TRY(buffer(s, &s->actc, ((size_t)s->pcap / TR_ACT_BLOCK + 2) * sizeof(int), err));
    TR_TRY(ensure_rows(s, err));

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
    TR_CL_CHECK(clEnqueueFillBuffer(q, s->po, &zeros, sizeof zeros, 0, nv * d, 0, NULL, NULL));
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
