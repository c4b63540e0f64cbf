/* Keeping the shorter of two batches' results of a knot (batch_merge.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/batch_merge.h"
#include "cli/batch_row.h"
#include "util/text_file.h"

#define MERGE_PATH 4400

static int exists(const char *path) { return access(path, F_OK) == 0; }

/* Copies src to dst through a temporary name and a rename. */
static int copy_atomic(const char *src, const char *dst, tr_error *err)
{
    char *bytes;
    size_t len;
    int rc = tr_read_file(src, &bytes, &len, err);
    if (rc != TR_OK)
        return rc;
    rc = tr_write_file_atomic(dst, bytes, len, err);
    free(bytes);
    return rc;
}

int tr_batch_other_start(const tr_batch_row *r, const char *start)
{
    return r->start[0] && start[0] && strcmp(r->start, start) != 0;
}

int tr_batch_merge_knot(const char *out, const char *other, const char *name, const char *start,
                        tr_merge_outcome *outcome, char *what, size_t what_size, tr_error *err)
{
    char row_o[MERGE_PATH], vect_o[MERGE_PATH], row[MERGE_PATH], vect[MERGE_PATH], ckpt[MERGE_PATH],
        side[MERGE_PATH];
    snprintf(row_o, sizeof row_o, "%s/%s.row.tsv", other, name);
    snprintf(vect_o, sizeof vect_o, "%s/%s.vect", other, name);
    snprintf(row, sizeof row, "%s/%s.row.tsv", out, name);
    snprintf(vect, sizeof vect, "%s/%s.vect", out, name);
    snprintf(ckpt, sizeof ckpt, "%s/%s.ckpt", out, name);
    snprintf(side, sizeof side, "%s/%s.start", out, name);
    *outcome = TR_MERGE_ABSENT;
    snprintf(what, what_size, "no record in %s", other);
    if (!exists(row_o))
        return TR_OK;
    tr_batch_row theirs, ours;
    int rc = tr_batch_row_read(row_o, &theirs, err);
    if (rc != TR_OK)
        return rc;
    if (tr_batch_other_start(&theirs, start)) {
        *outcome = TR_MERGE_OTHER_START;
        snprintf(what, what_size, "not merged: %s's record is of another start (%s, this one's %s)", other,
                 theirs.start, start);
        return TR_OK;
    }
    /* said whatever comes of it: the name is all that ties the record to this knot */
    const char *unsure = theirs.start[0] ? "" : " (its record names no start: taken to be this knot by its name)";
    int have = exists(row);
    if (have && (rc = tr_batch_row_read(row, &ours, err)) != TR_OK)
        return rc;
    int stale = have && tr_batch_other_start(&ours, start);
    if (have && !stale) {
        /* a ropelength at another N answers another question; NAN never wins */
        int shorter = theirs.n == ours.n && isfinite(theirs.ropelength) &&
                      (!isfinite(ours.ropelength) || theirs.ropelength < ours.ropelength);
        if (!shorter) {
            *outcome = TR_MERGE_KEPT;
            if (theirs.n != ours.n)
                snprintf(what, what_size, "kept (%s's N %zu is not this one's %zu)%s", other, theirs.n, ours.n,
                         unsure);
            else
                snprintf(what, what_size, "kept %.10f (%s's %.10f is not shorter)%s", ours.ropelength, other,
                         theirs.ropelength, unsure);
            return TR_OK;
        }
    }
    if ((rc = copy_atomic(vect_o, vect, err)) != TR_OK || (rc = tr_batch_row_write(row, &theirs, err)) != TR_OK)
        return rc;
    /* the checkpoint and the start it continues, both the batch's own */
    unlink(ckpt);
    unlink(side);
    *outcome = have && !stale ? TR_MERGE_SHORTER : TR_MERGE_TAKEN;
    if (stale)
        snprintf(what, what_size, "%.10f taken from %s in place of a record of another start%s", theirs.ropelength,
                 other, unsure);
    else if (have)
        snprintf(what, what_size, "%.10f -> %.10f from %s%s", ours.ropelength, theirs.ropelength, other, unsure);
    else
        snprintf(what, what_size, "%.10f taken from %s%s", theirs.ropelength, other, unsure);
    return TR_OK;
}
