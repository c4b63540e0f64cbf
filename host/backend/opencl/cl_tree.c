/* This file contains the device neighbour search: the edge tree copied to the device, refitted
 * and walked (cl_tree.h). */
#include "backend/opencl/cl_tree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/cl_error.h"
#include "geometry/neighbour_search.h"

static void release(cl_mem *m) {
    if (*m)
        clReleaseMemObject(*m);
    *m = NULL;
}

/* Makes room for n list entries (keeping the buffer when it is big enough). */
static int reserve_list(tr_cl_tree *t, const tr_cl_ctx *ctx, size_t n, tr_error *err) {
    if (n <= t->list_cap && t->list)
        return TR_OK;
    release(&t->list);
    t->list_cap = 0;
    n += n / 4;
    cl_int e = CL_SUCCESS;
    t->list = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, (n ? n : 1) * sizeof(int), NULL, &e);
    if (e != CL_SUCCESS)
        return tr_fail(err, TR_EOPENCL, "clCreateBuffer: %s for the neighbour lists (%zu entries, %.0f MB)",
                       tr_cl_strerror(e), n, 4e-6 * (double)n);
    t->list_cap = n;
    return TR_OK;
}

void tr_cl_tree_free(tr_cl_tree *t) {
    cl_kernel *k[] = {&t->leaf_box, &t->inner_box, &t->leaf_slab, &t->pairs, &t->list_room};
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        if (*k[i])
            clReleaseKernel(*k[i]);
    cl_mem *m[] = {&t->tedge,     &t->vedge, &t->comp_estart, &t->node_a,  &t->node_b,
                   &t->node_comp, &t->left,  &t->right,       &t->leaf_id, &t->level_id,
                   &t->box,       &t->slab,  &t->count,       &t->list,    &t->overflow,
                   &t->loff,      &t->room,  &t->tsum};
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
        release(m[i]);
    free(t->level_off);
    memset(t, 0, sizeof *t);
}

/* Host arrays of the tree's layout, uploaded once. */
typedef struct layout {
    int *tedge, *vedge, *estart, *a, *b, *comp, *left, *right, *leaf, *level, *depth, *loff;
} layout;

static void layout_free(layout *l) {
    int *p[] = {l->tedge, l->vedge, l->estart, l->a,     l->b,     l->comp,
                l->left,  l->right, l->leaf,   l->level, l->depth, l->loff};
    for (size_t i = 0; i < sizeof p / sizeof p[0]; i++)
        free(p[i]);
}

/* Inner nodes ordered by depth, deepest first (a level's children are all
 * deeper, so one launch per level refits bottom-up); level_off[L] starts
 * level L of nlevels. */
static int order_levels(tr_cl_tree *t, layout *l, const tr_nsearch *ns) {
    int maxd = 0;
    for (int id = 0; id < t->nnodes; id++) {
        size_t a, b, lf, rt;
        int comp;
        tr_nsearch_node(ns, (size_t)id, &a, &b, &comp, &lf, &rt);
        if (id == 0)
            l->depth[0] = 0;
        if (lf) {
            l->depth[lf] = l->depth[id] + 1;
            l->depth[rt] = l->depth[id] + 1;
        }
        maxd = l->depth[id] > maxd ? l->depth[id] : maxd;
    }
    t->nlevels = maxd + 1;
    t->level_off = calloc((size_t)t->nlevels + 1, sizeof *t->level_off);
    if (!t->level_off)
        return -1;
    int k = 0;
    for (int d = maxd; d >= 0; d--) {
        t->level_off[maxd - d] = k;
        for (int id = 0; id < t->nnodes; id++)
            if (l->depth[id] == d && l->left[id] != 0)
                l->level[k++] = id;
    }
    t->level_off[t->nlevels] = k;
    return 0;
}

int tr_cl_tree_init(tr_cl_tree *t, const tr_cl_ctx *ctx, cl_program prog, const tr_curve *c, int cap,
                    tr_error *err) {
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    memset(t, 0, sizeof *t);
    tr_nsearch ns;
    layout l = {0};
    if ((rc = tr_nsearch_build(&ns, c, err)))
        return rc;
    t->nv = (int)c->nv;
    t->ne = (int)ns.ne;
    t->nnodes = (int)ns.nnodes;
    size_t nn = ns.nnodes ? ns.nnodes : 1, ne = ns.ne ? ns.ne : 1;
    l.tedge = malloc(ne * sizeof(int));
    l.vedge = malloc(c->nv * sizeof(int));
    l.estart = malloc((size_t)(c->ncomp + 1) * sizeof(int));
    l.a = malloc(nn * sizeof(int));
    l.b = malloc(nn * sizeof(int));
    l.comp = malloc(nn * sizeof(int));
    l.left = malloc(nn * sizeof(int));
    l.right = malloc(nn * sizeof(int));
    l.leaf = malloc(nn * sizeof(int));
    l.level = malloc(nn * sizeof(int));
    l.depth = calloc(nn, sizeof(int));
    if (!l.tedge || !l.vedge || !l.estart || !l.a || !l.b || !l.comp || !l.left || !l.right || !l.leaf ||
        !l.level || !l.depth) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory for the device neighbour tree (%zu edges)", ns.ne);
        goto cleanup;
    }
    for (size_t v = 0; v < c->nv; v++)
        l.vedge[v] = -1;
    for (size_t k = 0; k < ns.ne; k++) {
        l.tedge[k] = (int)ns.ea[k];
        l.vedge[ns.ea[k]] = (int)k;
    }
    for (int k = 0; k <= c->ncomp; k++)
        l.estart[k] = (int)ns.estart[k];
    for (int id = 0; id < t->nnodes; id++) {
        size_t a, b, lf, rt;
        tr_nsearch_node(&ns, (size_t)id, &a, &b, &l.comp[id], &lf, &rt);
        l.a[id] = (int)a;
        l.b[id] = (int)b;
        l.left[id] = (int)lf;
        l.right[id] = (int)rt;
        if (!lf)
            l.leaf[t->nleaf++] = id;
    }
    if (order_levels(t, &l, &ns)) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory for the device neighbour tree");
        goto cleanup;
    }
    TR_TRY(tr_cl_upload_ints(ctx, l.tedge, ns.ne, &t->tedge, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.vedge, c->nv, &t->vedge, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.estart, (size_t)c->ncomp + 1, &t->comp_estart, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.a, nn, &t->node_a, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.b, nn, &t->node_b, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.comp, nn, &t->node_comp, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.left, nn, &t->left, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.right, nn, &t->right, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.leaf, (size_t)t->nleaf, &t->leaf_id, err));
    TR_TRY(tr_cl_upload_ints(ctx, l.level, nn, &t->level_id, err));
    TR_CL_CHECK(
        (t->box = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, 6 * nn * sizeof(double), NULL, &e), e));
    TR_CL_CHECK(
        (t->slab = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, 8 * nn * sizeof(double), NULL, &e), e));
    TR_CL_CHECK(
        (t->count = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, c->nv * sizeof(int), NULL, &e), e));
    TR_CL_CHECK(
        (t->room = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, c->nv * sizeof(int), NULL, &e), e));
    TR_CL_CHECK((t->tsum = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, sizeof(double), NULL, &e), e));
    int izero = 0; /* a curve with no edge is never walked, and has no partners */
    TR_CL_CHECK(clEnqueueFillBuffer(ctx->queue, t->count, &izero, sizeof izero, 0, c->nv * sizeof(int), 0,
                                    NULL, NULL));
    TR_CL_CHECK((t->overflow = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, sizeof(int), NULL, &e), e));
    TR_CL_CHECK((t->leaf_box = clCreateKernel(prog, "tree_leaf_box", &e), e));
    TR_CL_CHECK((t->inner_box = clCreateKernel(prog, "tree_inner_box", &e), e));
    TR_CL_CHECK((t->leaf_slab = clCreateKernel(prog, "tree_leaf_slab", &e), e));
    TR_CL_CHECK((t->pairs = clCreateKernel(prog, "tree_pairs", &e), e));
    TR_CL_CHECK((t->list_room = clCreateKernel(prog, "list_room", &e), e));
    /* the first walk's rows: cap entries for every vertex */
    if (cap < 1)
        cap = 16;
    l.loff = malloc((c->nv + 1) * sizeof(int));
    if (!l.loff || (double)cap * (double)c->nv > 5e8) {
        rc = tr_fail(err, TR_ENOMEM, "no room for %d neighbours of each of %zu edges", cap, c->nv);
        goto cleanup;
    }
    for (size_t v = 0; v <= c->nv; v++)
        l.loff[v] = (int)v * cap;
    /* rewritten by size_rows' scan: read-write */
    TR_TRY(tr_cl_upload_ints_rw(ctx, l.loff, c->nv + 1, &t->loff, err));
    TR_TRY(reserve_list(t, ctx, (size_t)cap * c->nv, err));
cleanup:
    layout_free(&l);
    tr_nsearch_free(&ns);
    if (rc != TR_OK)
        tr_cl_tree_free(t);
    return rc;
}


/* The arguments the per-leaf kernels (tree_leaf_box, tree_leaf_slab) share:
 * positions, next, the tree's edge order, its leaves and their edge ranges. */
static int leaf_args(const tr_cl_tree *t, cl_kernel k, const tr_cl_topology *topo, cl_mem x,
                     tr_error *err) {
    int rc = TR_OK;
    TR_CL_ARGS(k, 0, TR_CL_A(x), TR_CL_A(topo->next), TR_CL_A(t->tedge), TR_CL_A(t->leaf_id),
               TR_CL_A(t->nleaf), TR_CL_A(t->node_a), TR_CL_A(t->node_b));
cleanup:
    return rc;
}

/* Boxes of every node for positions x, bottom-up. */
static int refit(tr_cl_tree *t, const tr_cl_ctx *ctx, const tr_cl_topology *topo, cl_mem x, tr_error *err) {
    int rc = TR_OK;
    TR_TRY(leaf_args(t, t->leaf_box, topo, x, err));
    TR_CL_ARGS(t->leaf_box, 7, TR_CL_A(t->box));
    TR_TRY(tr_cl_launch_items(ctx, t->leaf_box, (size_t)t->nleaf, err));
    TR_CL_ARGS(t->inner_box, 0, TR_CL_A(t->level_id));
    TR_CL_ARGS(t->inner_box, 3, TR_CL_A(t->left), TR_CL_A(t->right), TR_CL_A(t->box));
    for (int L = 0; L < t->nlevels; L++) {
        int off = t->level_off[L], n = t->level_off[L + 1] - off;
        if (n == 0)
            continue;
        TR_CL_ARGS(t->inner_box, 1, TR_CL_A(off), TR_CL_A(n));
        TR_TRY(tr_cl_launch_items(ctx, t->inner_box, (size_t)n, err));
    }
cleanup:
    return rc;
}

/* Rows sized from count (the last walk's): loff = the exclusive scan of
 * list_room, and a list that holds them all. */
static int size_rows(tr_cl_tree *t, const tr_cl_ctx *ctx, tr_cl_reduce *red, const tr_cl_topology *topo,
                     tr_error *err) {
    int rc = TR_OK;
    /* The rooms are summed in ints, so their total is bounded first, from
     * the counts summed exactly in doubles: 2^29 entries (a 2 GB list) is
     * far beyond any curve the step could use, and leaves the int scan
     * clear of wrapping. */
    double counted = 0.0;
    TR_TRY(tr_cl_reduce_count(red, ctx, t->count, t->nv, t->tsum, 0, err));
    TR_CL_CHECK(
        clEnqueueReadBuffer(ctx->queue, t->tsum, CL_TRUE, 0, sizeof counted, &counted, 0, NULL, NULL));
    if (!(1.25 * counted + 4.0 * t->nv <= (double)(1 << 29))) {
        rc = tr_fail(err, TR_EGEOMETRY, "%.0f contact candidates: the curve is far too dense", counted);
        goto cleanup;
    }
    TR_CL_ARGS(t->list_room, 0, TR_CL_A(t->count), TR_CL_A(topo->next), TR_CL_A(t->nv), TR_CL_A(t->room));
    TR_TRY(tr_cl_launch_items(ctx, t->list_room, (size_t)t->nv, err));
    TR_TRY(tr_cl_reduce_scan(red, ctx, t->room, t->nv, t->loff, err));
    /* the rooms' total is at most the bound above, so the list is sized from
     * it without reading the scan's total back */
    TR_TRY(reserve_list(t, ctx, (size_t)ceil(1.25 * counted) + 4 * (size_t)t->nv, err));
cleanup:
    return rc;
}

int tr_cl_tree_search(tr_cl_tree *t, const tr_cl_ctx *ctx, tr_cl_reduce *red,
                      const tr_cl_topology *topo, cl_mem x, double cutoff, double tilt, cl_mem gap,
                      int gmin, tr_error *err) {
    int rc = TR_OK;
    if (topo->nv != t->nv)
        return tr_fail(err, TR_EINVAL, "neighbour tree prepared for %d vertices, curve has %d", t->nv,
                       topo->nv);
    if (t->ne == 0)
        return TR_OK;
    TR_TRY(refit(t, ctx, topo, x, err));
    double root[6];
    TR_CL_CHECK(clEnqueueReadBuffer(ctx->queue, t->box, CL_TRUE, 0, sizeof root, root, 0, NULL, NULL));
    for (int k = 0; k < 6; k++)
        if (!isfinite(root[k])) {
            rc = tr_fail(err, TR_EGEOMETRY, "non-finite coordinates on the device");
            goto cleanup;
        }
    int use_slab = tilt > 0.0 && tilt < 1.0;
    if (use_slab) {
        double pad = tilt * cutoff;
        TR_TRY(leaf_args(t, t->leaf_slab, topo, x, err));
        TR_CL_ARGS(t->leaf_slab, 7, TR_CL_A(cutoff), TR_CL_A(pad), TR_CL_A(t->slab));
        TR_TRY(tr_cl_launch_items(ctx, t->leaf_slab, (size_t)t->nleaf, err));
    }
    if (t->counted)
        TR_TRY(size_rows(t, ctx, red, topo, err));
    int min_gap = gmin < 2 ? 2 : gmin;
    int flag = 0;
    for (int attempt = 0; attempt < 2; attempt++) {
        int zero = 0;
        TR_CL_CHECK(
            clEnqueueWriteBuffer(ctx->queue, t->overflow, CL_FALSE, 0, sizeof zero, &zero, 0, NULL, NULL));
        TR_CL_ARGS(t->pairs, 0, TR_CL_A(x), TR_CL_A(topo->next), TR_CL_A(t->nv), TR_CL_A(topo->comp),
                   TR_CL_A(topo->pos), TR_CL_A(topo->comp_n), TR_CL_A(topo->comp_closed), TR_CL_A(gap),
                   TR_CL_A(min_gap), TR_CL_A(t->vedge), TR_CL_A(t->tedge), TR_CL_A(t->comp_estart),
                   TR_CL_A(t->node_a), TR_CL_A(t->node_b), TR_CL_A(t->node_comp), TR_CL_A(t->left),
                   TR_CL_A(t->right), TR_CL_A(t->box), TR_CL_A(t->slab), TR_CL_A(cutoff), TR_CL_A(tilt),
                   TR_CL_A(t->loff), TR_CL_A(t->count), TR_CL_A(t->list), TR_CL_A(t->overflow));
        TR_TRY(tr_cl_launch_items(ctx, t->pairs, (size_t)t->nv, err));
        TR_CL_CHECK(
            clEnqueueReadBuffer(ctx->queue, t->overflow, CL_TRUE, 0, sizeof flag, &flag, 0, NULL, NULL));
        if (flag == 2) {
            rc = tr_fail(err, TR_EOPENCL, "neighbour tree walk ran out of stack");
            goto cleanup;
        }
        t->counted = 1; /* count is exact even where a row overflowed */
        if (!flag)
            break;
        /* some edge found more partners than its row holds (the first walk,
         * or a big move): rows from these counts, and again */
        t->regrown++;
        TR_TRY(size_rows(t, ctx, red, topo, err));
    }
    /* the rows were sized to the first pass's counts; a second overflow
     * means the kernel disagrees with itself, never a silent cut */
    if (flag)
        rc = tr_fail(err, TR_EOPENCL, "neighbour lists still overflow after growing them");
cleanup:
    return rc;
}
