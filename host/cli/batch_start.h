/* The start of a knot that a batch manifest names (`knot 3_1`, `link
 * L2a1`; batch_manifest.h) instead of giving a file: made by the batch, as
 * `tightrope make knot|link NAME` makes it (tighten/knot_notation_start.h: the
 * closure of the table's braid word, its type checked against the
 * table's), into OUT/starts/NAME.vect, a file of the batch's own that
 * tighten then reads like any start. The construction is deterministic,
 * and the start's identity is its name and notation, not the file
 * (tr_batch_knot_start_id), so a batch resumed or run again, here or on
 * another machine, sees the same start. */
#ifndef TR_BATCH_START_H
#define TR_BATCH_START_H

#include "cli/batch_manifest.h"
#include "util/error.h"

/* Makes knot k's start (k->from a start by name) into k->file, its folder
 * made when missing, the file written atomically; a start by file is left
 * alone. TR_EGEOMETRY when the made curve is not of the named type (the
 * construction's failure; tr_knot_start_make), TR_EIO when it cannot be
 * written. */
int tr_batch_make_start(const tr_batch_knot *k, tr_error *err);

#endif
