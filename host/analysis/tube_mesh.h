/* The rope as a surface: a triangulated tube of a given radius
 * around each component, for ParaView or Blender. A ring of K vertices sits
 * around every polygon vertex in the plane normal to the bisected tangent;
 * the rings' frames are parallel-transported (rotation-minimising, so the
 * tube does not twist), and on a closed component the holonomy angle is
 * spread evenly over the length so the last ring joins the first. Quads
 * between rings are split into two triangles, open ropes get fan caps; the
 * surface is closed and its triangles face outwards. */
#ifndef TR_TUBE_MESH_H
#define TR_TUBE_MESH_H

#include <stddef.h>

#include "util/error.h"

typedef struct tr_tube_mesh {
    size_t nv, nf;
    double *v;  /* 3 nv coordinates */
    size_t *f;  /* 3 nf vertex indices, counter-clockwise seen from outside */
    size_t vcap, fcap;
} tr_tube_mesh;

#define TR_TUBE_SIDES_MAX 1024

/* Adds the tube around x (n vertices; closed: n >= 3, open: n >= 2) to m,
 * which is zero-initialised or holds earlier tubes. K: vertices per ring,
 * 3 to TR_TUBE_SIDES_MAX. TR_EGEOMETRY for a zero-length edge or a reversal
 * (an edge doubling back on the last). m is unchanged on failure. */
int tr_tube_mesh_add(tr_tube_mesh *m, const double *x, size_t n, int closed, double radius, size_t K,
                     tr_error *err);
void tr_tube_mesh_free(tr_tube_mesh *m);

/* The mesh as ASCII PLY (vertex x y z doubles, face vertex_indices), with
 * comment (one line, may be NULL) in the header. A malloc'd string in *out,
 * or TR_ENOMEM. */
int tr_tube_mesh_ply(const tr_tube_mesh *m, const char *comment, char **out);

#endif
