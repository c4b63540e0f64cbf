/* The checkpoint of a series of roads (tighten --tries K --checkpoint P):
 * every road's engine writes P (and P.newton, its second-order solve's
 * state, engine/solver_state.c) and the last road's end is what the files
 * hold, whichever road is kept. A copy of both files as the kept road's
 * end left them, put back after the series, makes them the written
 * curve's, as a run of that one road would have left them. */
#ifndef TR_TIGHTEN_ROAD_CHECKPOINT_H
#define TR_TIGHTEN_ROAD_CHECKPOINT_H

#include <stddef.h>

#include "util/error.h"

typedef struct tt_road_checkpoint {
    int taken;       /* 1: the copy below is of a road's end */
    char *ckpt;      /* P's bytes */
    size_t ckpt_len;
    char *state;     /* P.newton's bytes (NULL: there was no solver state) */
    size_t state_len;
} tt_road_checkpoint;

/* Copies P and P.newton (a solver state file only) as they are now into c,
 * replacing what c held. A P that is not a regular file (a FIFO, a
 * device: written in place, no state beside it) is not copied: c->taken 0,
 * TR_OK. */
int tt_road_checkpoint_take(const char *path, tt_road_checkpoint *c, tr_error *err);

/* Writes the copy back, each file atomically, the state first (a
 * checkpoint names its state by the hash of its bytes): P.newton as it
 * was, or removed where there was none and a solver state is there now
 * (a later road's, written by this run); then P. */
int tt_road_checkpoint_put(const char *path, const tt_road_checkpoint *c, tr_error *err);

void tt_road_checkpoint_free(tt_road_checkpoint *c);

#endif
