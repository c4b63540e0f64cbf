/* Neighbour search over the edges of a curve: which pairs of edges can be
 * closer than a cutoff, without looking at all N^2 pairs.
 *
 * Why a tree along the curve and not a uniform grid: the interesting distance
 * (the shortest strut, about 2 for a tight knot) is thousands of edge lengths
 * at N = 10^6, so a grid cell of that size holds O(N) edges and a grid of
 * edge-sized cells has O(N^2/3) cells per query. Instead the edges, in curve
 * order, are the leaves of a balanced binary tree of axis-aligned boxes: each
 * node bounds a run of consecutive edges. Because the curve is a chain, the
 * tree never needs sorting; when vertices move (the engine), tr_nsearch_refit
 * recomputes the boxes in O(N) and the topology stays.
 *
 * A query reports every pair (i, j), j < i, whose edge boxes are within the
 * cutoff and that is not excluded by index. The callback may lower the cutoff
 * as it goes (branch and bound: the thickness oracle shrinks it to the
 * shortest strut found so far). With TR_NSEARCH_CRITICAL and a finite cutoff,
 * each leaf's run of consecutive edges walks the tree once, against a slab
 * along its chord that holds the normal slabs and wedges of all its edges
 * out to the cutoff, and then each edge tests only the leaves found; this is
 * what makes the oracle linear in N for tight or smooth curves.
 * Pruning is conservative (boxes are widened by a relative 1e-12 against
 * rounding), so the set of pairs reported is a superset of the pairs whose
 * segment distance is <= cutoff, and the result of an exact min search agrees
 * bit for bit with tr_nsearch_pairs_brute. */
#ifndef TR_NEIGHBOUR_SEARCH_H
#define TR_NEIGHBOUR_SEARCH_H

#include <stddef.h>

#include "curve/curve.h"
#include "util/clock.h"

/* Global edge numbering: the edges of component 0 first (edge l of a
 * component runs from its vertex l to vertex l+1, the last edge of a closed
 * component back to its first vertex), then component 1, ... */
typedef struct tr_nsearch {
    const tr_curve *c; /* not owned; the coordinates may change between refits */
    size_t ne;         /* number of edges */
    size_t *ea, *eb;   /* ne: first and second vertex of each edge */
    size_t *eprev;     /* ne: the vertex before ea (octrope's wrap: v_{-1} = v_1 on open components) */
    int *ecomp;        /* ne: component of each edge */
    size_t *estart;    /* ncomp+1: first global edge of each component */
    size_t nnodes;
    struct tr_nsearch_node *node;
    /* NULL (tr_nsearch_build's): none. Else a walk of tr_nsearch_pairs looks
     * at it between runs of leaves and, once it has passed, stops with
     * TR_NSEARCH_STOPPED: at 10^7 edges one walk is tens of seconds, which
     * a --time-limit must be able to cut (the caller sets it). */
    const tr_deadline *bound;
} tr_nsearch;

/* What tr_nsearch_pairs returns when s->bound stopped it (never a
 * callback's own value: callbacks return small positive codes). */
#define TR_NSEARCH_STOPPED (-1000)

/* Flags for a query. */
enum {
    /* Only pairs where edge j can hold a point that is doubly critical for
     * edge i: prunes boxes that lie wholly in front of edge i (beyond its end
     * vertex, unless it is the last edge of an open component) or wholly
     * outside the normal slab and the normal wedge at its start vertex
     * (docs/physics.md 2.2). The callback must still do the exact test. */
    TR_NSEARCH_CRITICAL = 1u,
    /* Internal to tr_nsearch_pairs_slab (ignored elsewhere). */
    TR_NSEARCH_SLAB = 2u
};

/* Called for each candidate pair ei > ej; may lower *cutoff. Returns 0 to go
 * on, anything else stops the search and is returned by tr_nsearch_pairs. */
typedef int (*tr_pair_fn)(void *ctx, size_t ei, size_t ej, double *cutoff);

int tr_nsearch_build(tr_nsearch *s, const tr_curve *c, tr_error *err);
/* The edge numbering and index rules only, no tree (tr_nsearch_pairs and
 * tr_nsearch_edge must not be called on it): for callers that enumerate a
 * small curve's pairs themselves (the oracle's tr_thickness_gate). */
int tr_nsearch_build_flat(tr_nsearch *s, const tr_curve *c, tr_error *err);
/* Recomputes the boxes after the vertices of s->c moved (same topology). */
void tr_nsearch_refit(tr_nsearch *s);
void tr_nsearch_free(tr_nsearch *s);

/* True if the pair is skipped by index: same component and index gap
 * d = |li - lj| < min_gap, or on a closed component d > ne_comp - min_gap
 * (octrope's pi_count rule). min_gap 0 or 1 excludes only i == j. */
int tr_nsearch_excluded(const tr_nsearch *s, size_t ei, size_t ej, size_t min_gap);

/* Every pair (ei > ej), not excluded, whose edge bounding boxes are within
 * *cutoff (INFINITY allowed), subject to flags. *cutoff is updated to the
 * callback's final value. */
int tr_nsearch_pairs(const tr_nsearch *s, double *cutoff, size_t min_gap, unsigned flags,
                     tr_pair_fn fn, void *ctx);

/* Every pair (ei > ej), not excluded, whose edge boxes are within cutoff
 * and where edge j's box meets the slab of edge i stretched by pad at both
 * ends, {y : (y - p_i).u_i in [-pad, |e_i| + pad]} (p_i its start vertex, u_i
 * its direction), and edge i's box meets edge j's slab likewise (the test is
 * also made for whole leaves, by the slab along a leaf's chord). A pair
 * whose closest-point connector c satisfies |c.u_i| <= pad and |c.u_j| <=
 * pad (a strut nearly normal to both edges) always passes, so with pad =
 * tilt * cutoff this finds the nearly doubly-normal
 * pairs of a tight curve in time linear in N: the slab cuts each nearby
 * strand in a few edges, whereas all pairs within a fixed cutoff grow like
 * N^2 once the edges are much shorter than the cutoff. The cutoff stays
 * fixed (the callback's changes are ignored); pad < 0 (or NaN) means no
 * slab, only the cutoff. */
int tr_nsearch_pairs_slab(const tr_nsearch *s, double cutoff, size_t min_gap, double pad, tr_pair_fn fn,
                          void *ctx);

/* The partners j != i (on both sides) of one edge i, with the same tests:
 * fn gets (i, j) in that order. The thickness oracle uses a few of these to
 * find a first strut, so that the full search starts with a finite cutoff. */
int tr_nsearch_edge(const tr_nsearch *s, size_t i, double *cutoff, size_t min_gap, unsigned flags,
                    tr_pair_fn fn, void *ctx);

/* The tree's layout, for a device copy (host/backend/opencl/cl_tree.c): node id (0 is the
 * root; children come after their parent) covers edges [a, b), all of
 * component comp or comp -1; left == 0 marks a leaf. */
void tr_nsearch_node(const tr_nsearch *s, size_t id, size_t *a, size_t *b, int *comp, size_t *left,
                     size_t *right);

/* The O(N^2) reference the tests compare tr_nsearch_pairs against: offers
 * every pair that is not excluded by index, ignoring boxes and flags. */
int tr_nsearch_pairs_brute(const tr_nsearch *s, double *cutoff, size_t min_gap, unsigned flags,
                           tr_pair_fn fn, void *ctx);

#endif
