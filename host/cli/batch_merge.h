/* Merging one batch's results into another's (tightrope batch --merge):
 * the same knots tightened elsewhere (another seed, another machine, a
 * SLURM array on another cluster) are compared knot by knot, and the
 * shorter tight curve stays with its record. */
#ifndef TR_BATCH_MERGE_H
#define TR_BATCH_MERGE_H

#include <stddef.h>

#include "cli/batch_row.h"
#include "util/error.h"

typedef enum tr_merge_outcome {
    TR_MERGE_ABSENT,  /* OTHER has no record of the knot */
    TR_MERGE_TAKEN,   /* OUT had none: OTHER's result is now OUT's */
    TR_MERGE_SHORTER, /* OTHER's was shorter at the same N and replaced OUT's */
    TR_MERGE_KEPT,    /* OUT's is as short or shorter (or at another N) */
    TR_MERGE_OTHER_START, /* OTHER's came from another start: another knot, not merged */
} tr_merge_outcome;

/* Merges knot name of folder other into folder out: OTHER/NAME.vect and
 * its record replace OUT's when OUT has no record, or when OTHER's
 * ropelength is smaller at the same N. The curve is copied first and the
 * record last, both atomically, so a merge killed at any moment and run
 * again ends the same, and merging twice changes nothing. A checkpoint of
 * the knot in OUT is removed once OUT has a record. The caller holds the
 * knot's lock in OUT. *outcome says what happened; what (size what_size)
 * gets a short phrase for the progress line.
 *
 * start is the identity of the knot's start now (tr_batch_start_id; ""
 * unknown). A record of another start is another knot under this name:
 * OTHER's is not merged (TR_MERGE_OTHER_START, nothing written), and OUT's
 * is replaced by OTHER's, whatever their lengths (it is out of date). A
 * record that names no start (written before records did) is compared by
 * its length, as before, and the phrase says that it could not be told. */
int tr_batch_merge_knot(const char *out, const char *other, const char *name, const char *start,
                        tr_merge_outcome *outcome, char *what, size_t what_size, tr_error *err);

/* Whether record r came from another start than start (both known). */
int tr_batch_other_start(const tr_batch_row *r, const char *start);

#endif
