/* Device neighbour search (kernels/tree.cl): the reference's tree over the
 * edges (host/neighbour_search.h), copied to the device once per curve
 * topology, refitted per search, and walked by every edge. For every vertex
 * whose edge exists, the sorted list of partner vertices whose edges are
 * backend.h's contact pairs (segment distance < cutoff, not excluded by the
 * arclength rule, and nearly normal to both edges when 0 < tilt < 1). */
#ifndef TR_CL_TREE_H
#define TR_CL_TREE_H

#include "cl_device.h"
#include "cl_topology.h"
#include "curve.h"

typedef struct tr_cl_tree {
    cl_kernel leaf_box, inner_box, leaf_slab, pairs;
    int nv, ne, nnodes, nleaf, cap;
    int nlevels, *level_off;          /* host: inner nodes by depth, deepest first */
    int min_gap_floor;                /* 2 */
    cl_mem tedge, vedge, comp_estart; /* tree edge -> vertex, vertex -> tree edge, per component */
    cl_mem node_a, node_b, node_comp, left, right; /* nnodes ints each */
    cl_mem leaf_id, level_id;                      /* leaves; inner nodes by level */
    cl_mem box, slab;                              /* 6 and 8 reals per node */
    cl_mem count, list, overflow;                  /* nv ints; nv * cap ints; one int */
    int max_count;
} tr_cl_tree;

/* Sets up the tree for the curve's topology (positions are not read). */
int tr_cl_tree_init(tr_cl_tree *t, const tr_cl_ctx *ctx, cl_program prog, const tr_curve *c, int cap,
                    tr_error *err);
void tr_cl_tree_free(tr_cl_tree *t);

/* Refits the boxes to x and rebuilds the lists: count[i], list[i * cap ..]
 * in increasing partner index. gap: per-component exclusion gaps (device
 * buffer) and gmin their minimum. Grows the lists and repeats when a vertex
 * has more than cap partners. */
int tr_cl_tree_search(tr_cl_tree *t, const tr_cl_ctx *ctx, const tr_cl_topology *topo, cl_mem x,
                      double cutoff, double tilt, cl_mem gap, int gmin, tr_error *err);

#endif
