/* Device neighbour search (kernels/grid.cl): a uniform grid by cell sort.
 * For every item (vertex, or edge from vertex i to next[i]) the sorted list
 * of partner items closer than r that the arclength rule does not exclude
 * (index distance along the same component >= gap[component], at least 2). */
#ifndef TR_CL_GRID_H
#define TR_CL_GRID_H

#include "cl_reduce.h"
#include "cl_topology.h"

typedef struct tr_cl_grid {
    cl_kernel axis, keys, bitonic, reset, bounds, pairs;
    int n, npad, cap;
    size_t ncell_cap;
    cl_mem keybuf;       /* npad ulong */
    cl_mem cell_start, cell_end;
    cl_mem tmp;          /* n doubles: coordinates or edge lengths for the box reduction */
    cl_mem scal;         /* 8 doubles: box (min, max per axis) and the edge-length range */
    cl_mem count, list;  /* n ints; n * cap ints (partners of item i at list[i*cap ..]) */
    cl_mem overflow;     /* one int */
    /* what the last build used (for tests and the bench) */
    double h;
    int dims[3];
    int max_count;
} tr_cl_grid;

int tr_cl_grid_init(tr_cl_grid *g, const tr_cl_ctx *ctx, cl_program prog, int n, int cap,
                    tr_error *err);
void tr_cl_grid_free(tr_cl_grid *g);

/* Rebuilds the lists for coordinates x. edges: 1 for segment-segment
 * distances between edges, 0 for vertex-vertex distances; tilt (edges only,
 * 0 < tilt < 1, else no test): keep only pairs nearly normal to both edges,
 * as backend.h's candidate list. Reads back eight
 * box scalars and one overflow flag; grows the lists and repeats when an item
 * has more than cap partners. */
int tr_cl_grid_build(tr_cl_grid *g, const tr_cl_ctx *ctx, tr_cl_reduce *red,
                     const tr_cl_topology *t, cl_mem x, int edges, double r, double tilt,
                     cl_mem gap, tr_error *err);

#endif
