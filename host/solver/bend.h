/* This file declares a Newton step's bound on how far it bends the rope: the whole step cut, or the bent vertices taken back. */
#ifndef TR_BEND_H
#define TR_BEND_H

#include <stddef.h>

/* A rope's chain as the bend bounds see it: nv vertices, each with its
 * neighbours (TR_BEND_NONE past an open end) and the start edge l0 of its
 * component; held (NULL: none) marks vertices that must not move. The
 * curvature at vertex i is read as |w_i| / l0^2, w_i = x_{i+1} - 2 x_i +
 * x_{i-1} (2 l sin(theta / 2) for equal edges l, so l0^2 kappa for the
 * small turns of a fine rope). */
typedef struct tr_bend_chain {
    size_t nv;
    const size_t *prev, *next;
    const int *comp;
    const double *l0; /* per component */
    const unsigned char *held;
} tr_bend_chain;

#define TR_BEND_NONE ((size_t)-1)

/* The largest change of a vertex's curvature along dir (3 nv entries):
 * max |dw_i| / l0^2. */
double tr_bend_max_change(const tr_bend_chain *c, const double *dir);

/* Takes the bends of the trial point yt (3 nv entries) of a step from y
 * back: every vertex whose curvature at yt passes max(its curvature at y,
 * 1) + bend is moved along its w toward its neighbours' midpoint until it
 * is at that bound; up to four sweeps, as moving a vertex changes its
 * neighbours' w by half as much the other way. Returns the moves made. */
size_t tr_bend_take_back(const tr_bend_chain *c, const double *y, double *yt, double bend);

#endif
