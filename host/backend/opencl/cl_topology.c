/* This file contains the upload of a curve's chain structure to the device
 * (successor, predecessor, component and position per vertex; cl_topology.h). */
#include "backend/opencl/cl_topology.h"

#include <stdlib.h>
#include <string.h>

#include "backend/opencl/cl_error.h"

int tr_topology_arrays(const tr_curve *c, int **next, int **prev, int **comp, int **pos,
                       tr_error *err)
{
    size_t nv = c->nv ? c->nv : 1;
    *next = malloc(nv * sizeof(int));
    *prev = malloc(nv * sizeof(int));
    *comp = malloc(nv * sizeof(int));
    *pos = malloc(nv * sizeof(int));
    if (!*next || !*prev || !*comp || !*pos) {
        free(*next), free(*prev), free(*comp), free(*pos);
        *next = *prev = *comp = *pos = NULL;
        return tr_fail(err, TR_ENOMEM, "out of memory for the chain topology");
    }
    for (int k = 0; k < c->ncomp; k++) {
        size_t s = c->start[k], e = c->start[k + 1];
        for (size_t i = s; i < e; i++) {
            (*comp)[i] = k;
            (*pos)[i] = (int)(i - s);
            (*next)[i] = i + 1 < e ? (int)(i + 1) : (c->closed[k] ? (int)s : -1);
            (*prev)[i] = i > s ? (int)(i - 1) : (c->closed[k] ? (int)(e - 1) : -1);
        }
    }
    return TR_OK;
}

static int upload_ints(const tr_cl_ctx *ctx, cl_mem_flags access, const int *v, size_t n,
                       cl_mem *out, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    TR_CL_CHECK((*out = clCreateBuffer(ctx->context, access | CL_MEM_COPY_HOST_PTR,
                                       (n ? n : 1) * sizeof(int), (void *)v, &e),
                 e));
cleanup:
    return rc;
}

int tr_cl_upload_ints(const tr_cl_ctx *ctx, const int *v, size_t n, cl_mem *out, tr_error *err)
{
    return upload_ints(ctx, CL_MEM_READ_ONLY, v, n, out, err);
}

int tr_cl_upload_ints_rw(const tr_cl_ctx *ctx, const int *v, size_t n, cl_mem *out, tr_error *err)
{
    return upload_ints(ctx, CL_MEM_READ_WRITE, v, n, out, err);
}

int tr_cl_topology_upload(const tr_cl_ctx *ctx, const tr_curve *c, tr_cl_topology *t,
                          tr_error *err)
{
    int rc = TR_OK;
    int *next = NULL, *prev = NULL, *comp = NULL, *pos = NULL, *cn = NULL, *cc = NULL;
    memset(t, 0, sizeof *t);
    if (c->nv > (size_t)1 << 30)
        return tr_fail(err, TR_EINVAL, "%zu vertices exceed the device's 2^30 limit", c->nv);
    t->nv = (int)c->nv;
    t->ncomp = c->ncomp;
    TR_TRY(tr_topology_arrays(c, &next, &prev, &comp, &pos, err));
    cn = malloc((size_t)c->ncomp * sizeof *cn + 1);
    cc = malloc((size_t)c->ncomp * sizeof *cc + 1);
    if (!cn || !cc) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory for the chain topology");
        goto cleanup;
    }
    for (int k = 0; k < c->ncomp; k++) {
        cn[k] = (int)tr_comp_nv(c, k);
        cc[k] = c->closed[k] ? 1 : 0;
    }
    TR_TRY(tr_cl_upload_ints(ctx, next, c->nv, &t->next, err));
    TR_TRY(tr_cl_upload_ints(ctx, prev, c->nv, &t->prev, err));
    TR_TRY(tr_cl_upload_ints(ctx, comp, c->nv, &t->comp, err));
    TR_TRY(tr_cl_upload_ints(ctx, pos, c->nv, &t->pos, err));
    TR_TRY(tr_cl_upload_ints(ctx, cn, (size_t)c->ncomp, &t->comp_n, err));
    TR_TRY(tr_cl_upload_ints(ctx, cc, (size_t)c->ncomp, &t->comp_closed, err));
cleanup:
    free(next), free(prev), free(comp), free(pos), free(cn), free(cc);
    if (rc != TR_OK)
        tr_cl_topology_free(t);
    return rc;
}

void tr_cl_topology_free(tr_cl_topology *t)
{
    cl_mem *m[] = {&t->next, &t->prev, &t->comp, &t->pos, &t->comp_n, &t->comp_closed};
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
        if (*m[i])
            clReleaseMemObject(*m[i]);
    memset(t, 0, sizeof *t);
}
