/* This file declares the crankshaft shuffle of a start curve: the start of
 * a shuffled road of tighten --shuffles (tighten/roads.c), another
 * conformation of the same knot. */
#ifndef TR_SHUFFLE_H
#define TR_SHUFFLE_H

#include <stdint.h>

#include "curve/curve.h"
#include "util/clock.h"
#include "util/error.h"

/* Walks c by `moves` crankshaft moves: a random arc (2 to n/2 edges) of a
 * random component (chosen by its share of the vertices) is turned about
 * the chord through its end vertices by a random angle, small enough that
 * no vertex moves by more than 0.9 times the thickness t before the move
 * (oracle/thickness.h). That makes every move an isotopy: on the straight
 * path between the two states every point moves less than t, and strands
 * 2t apart or more cannot meet, so the knot (or link) type is kept. A move
 * is kept only if the thickness after it is at least the gate; with
 * ratchet > 0 the gate rises after each kept move to ratchet times the
 * thickness reached (a walk that compacts the rope: the thickness grows at
 * fixed length). Edge lengths are kept exactly (the arc turns rigidly). The
 * same seed gives the same curve on every machine (splitmix64, no libc
 * random). *kept (may be NULL) gets the number of moves kept. Every
 * component must be closed, of 4 vertices or more, and unconstrained
 * (TR_EINVAL); TR_EGEOMETRY if c is thinner than gate. Past bound (may be
 * NULL) the walk stops with TR_EINTERRUPTED, c a valid (shorter) walk. */
int tr_curve_shuffle(tr_curve *c, long moves, double gate, double ratchet, uint64_t seed, const tr_deadline *bound,
                     long *kept, tr_error *err);

#endif
