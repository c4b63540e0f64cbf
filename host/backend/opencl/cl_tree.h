/* Device neighbour search (kernels/tree.cl): the reference's tree over the
 * edges (host/geometry/neighbour_search.h), copied to the device once per curve
 * topology, refitted per search, and walked by every edge. For every vertex
 * whose edge exists, the sorted list of partner vertices whose edges are
 * backend.h's contact pairs (segment distance < cutoff, not excluded by the
 * arclength rule, and nearly normal to both edges when 0 < tilt < 1). */
#ifndef TR_CL_TREE_H
#define TR_CL_TREE_H

#include "backend/opencl/cl_device.h"
#include "backend/opencl/cl_reduce.h"
#include "backend/opencl/cl_topology.h"
#include "curve/curve.h"

typedef struct tr_cl_tree {
    cl_kernel leaf_box, inner_box, leaf_slab, pairs, list_room;
    int nv, ne, nnodes, nleaf;
    int nlevels, *level_off;          /* host: inner nodes by depth, deepest first */
    int min_gap_floor;                /* 2 */
    cl_mem tedge, vedge, comp_estart; /* tree edge -> vertex, vertex -> tree edge, per component */
    cl_mem node_a, node_b, node_comp, left, right; /* nnodes ints each */
    cl_mem leaf_id, level_id;                      /* leaves; inner nodes by level */
    cl_mem box, slab;                              /* 6 and 8 reals per node */
    cl_mem count, loff, room, overflow;            /* nv, nv + 1, nv ints; one int */
    cl_mem tsum;                                   /* one double: the counts' sum */
    cl_mem list;                                   /* list_cap ints */
    size_t list_cap;
    int counted; /* count holds the last walk's counts, which size the next walk's rows */
    int regrown; /* walks repeated because a row overflowed (read by the tests) */
} tr_cl_tree;

/* Sets up the tree for the curve's topology (positions are not read); the
 * first walk has room for cap partners per edge. */
int tr_cl_tree_init(tr_cl_tree *t, const tr_cl_ctx *ctx, cl_program prog, const tr_curve *c, int cap,
                    tr_error *err);
void tr_cl_tree_free(tr_cl_tree *t);

/* Refits the boxes to x and rebuilds the lists: count[i] partners at
 * list[loff[i] ..], in increasing partner index. gap: per-component
 * exclusion gaps (device buffer) and gmin their minimum. Each edge's row is
 * sized from its count in the last walk (and a quarter more), so the list
 * holds about as many entries as there are partners, however they are
 * spread over the edges; when a row overflows, the rows are resized from
 * that walk's counts and the walk repeats once. red scans the row sizes. */
int tr_cl_tree_search(tr_cl_tree *t, const tr_cl_ctx *ctx, tr_cl_reduce *red,
                      const tr_cl_topology *topo, cl_mem x, double cutoff, double tilt, cl_mem gap,
                      int gmin, tr_error *err);

#endif
