/* The vertex model of thickness: SP-FEM's contacts (Przybyl & Pieranski;
 * ../shared/REFERENCE.md 1.1-1.2, docs/physics.md "The vertex model"),
 * measured independently of any solver's contact lists.
 *
 * A rope of radius R is feasible in this model when every two vertices
 * that count are at least 2R apart and Rawdon's MinRad is at least R.
 * Vertices count as a pair when they lie on different components, or on the
 * same component at least K apart along it, K = ceil(pi R / e), e = L_p /
 * (number of edges): closer pairs lie on one arc of length < pi R, whose
 * chord a curve of curvature <= 1/R may make shorter than 2R (on a
 * saturated arc the chord first reaches 2R at arclength pi R). The index
 * gap on a closed component is the shorter way round.
 *
 * The thickness is the largest feasible R, so the measure is scale free:
 * K is set by the thickness itself, which for a curve at thickness 1 (what
 * tighten writes, the paper's curves) is SP-FEM's K = ceil(pi / e). With
 * opts->radius > 0 the exclusion is fixed at that radius instead (SP-FEM's
 * own convention with radius 1, bench/vertex_contacts). Either way
 *   thickness = min(MinRad, vertex_dmin / 2),  ropelength = L_p / thickness,
 * with vertex_dmin the least distance over the pairs that count for the
 * K reported. Between two curved strands an edge may dip into the other
 * strand's tube by its sag e^2/8, which this model does not see (Rawdon's,
 * thickness.h, measures edges): a knot tightened in it is shorter, by
 * O(e^2) (bench/notes/2026-11-28-vertex-contact-length.md).
 *
 * The least vertex distance is found in time linear in N for tight or smooth
 * curves: the least pair either has its index gap exactly K (N pairs, looked
 * at directly), or involves the end vertex of an open component (looked at
 * against every vertex), or is a local minimum along both strands, so each
 * vertex lies in the other's bisector slab, which the edge tree's slab
 * search (geometry/neighbour_search.h) finds. The result is the same double
 * as an all-pairs search (opts->brute_force). */
#ifndef TR_VERTEX_THICKNESS_H
#define TR_VERTEX_THICKNESS_H

#include "curve/curve.h"
#include "oracle/thickness.h"

typedef struct tr_vertex_opts {
    /* > 0: the rope radius the exclusion K = ceil(pi radius / e) is set for,
     * in the curve's units; 0: the thickness itself (scale free). */
    double radius;
    /* Look at all N^2 vertex pairs instead of the search (tests). */
    int brute_force;
} tr_vertex_opts;

typedef struct tr_vertex_thickness {
    size_t vertices;
    double length;      /* L_p, as the thickness oracle has it */
    double edge;        /* e = L_p / number of edges */
    double radius;      /* R of K = ceil(pi R / e): opts->radius, or the thickness */
    size_t exclusion;   /* K; SIZE_MAX when R is infinite (no pair on one component counts) */
    double minrad;      /* Rawdon's MinRad (thickness.h); INFINITY if straight */
    size_t minrad_vertex;
    double vertex_dmin; /* least distance between vertices that count; INFINITY if none */
    size_t vi, vj;      /* the vertices realising it (global indices, vi > vj) */
    double thickness;   /* min(minrad, vertex_dmin / 2) */
    double ropelength;  /* length / thickness */
} tr_vertex_thickness;

/* Whole curve. rawdon: the curve's tr_thickness_measure result when the
 * caller has it (its length and MinRad are used), or NULL to measure here.
 * opts may be NULL (scale free, fast search). Refuses what
 * tr_thickness_measure refuses (a curve that passes through itself). */
int tr_vertex_thickness_measure(const tr_curve *c, const tr_vertex_opts *opts, const tr_thickness *rawdon,
                                tr_vertex_thickness *out, tr_error *err);

#endif
