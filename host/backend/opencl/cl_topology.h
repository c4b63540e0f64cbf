/* The chain structure of a curve on the device: for every vertex its
 * successor and predecessor along its component (-1 at the ends of an open
 * rope), its component and its position in it, plus each component's
 * vertex count and closure flag. Kernels use these instead of the host's
 * start[] offsets so that one launch covers knots, links and open ropes. */
#ifndef TR_CL_TOPOLOGY_H
#define TR_CL_TOPOLOGY_H

#include "backend/opencl/cl_device.h"
#include "curve/curve.h"

typedef struct tr_cl_topology {
    int nv, ncomp;
    cl_mem next, prev, comp, pos; /* nv ints each */
    cl_mem comp_n, comp_closed;   /* ncomp ints each */
} tr_cl_topology;

/* Host-side arrays (malloc'd, nv ints each) for tests and the reference comparison. */
int tr_topology_arrays(const tr_curve *c, int **next, int **prev, int **comp, int **pos,
                       tr_error *err);

int tr_cl_topology_upload(const tr_cl_ctx *ctx, const tr_curve *c, tr_cl_topology *t,
                          tr_error *err);
void tr_cl_topology_free(tr_cl_topology *t);

/* A device copy of n ints (n == 0 allocates one): read-only, for data the
 * kernels only read; _rw for a start that kernels later overwrite (a scan's
 * output). A kernel writing a CL_MEM_READ_ONLY buffer is undefined
 * behaviour, which Oclgrind reports (scripts/test.sh --oclgrind). */
int tr_cl_upload_ints(const tr_cl_ctx *ctx, const int *v, size_t n, cl_mem *out, tr_error *err);
int tr_cl_upload_ints_rw(const tr_cl_ctx *ctx, const int *v, size_t n, cl_mem *out, tr_error *err);

#endif
