/* Keeping the shorter of two batches' results of a knot (batch_merge.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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

int tr_batch_merge_knot(const char *out, const char *other, const char *name, tr_merge_outcome *outcome,
                        char *what, size_t what_size, tr_error *err)
{
    char row_o[MERGE_PATH], vect_o[MERGE_PATH], row[MERGE_PATH], vect[MERGE_PATH], ckpt[MERGE_PATH];
    snprintf(row_o, sizeof row_o, "%s/%s.row.tsv", other, name);
    snprintf(vect_o, sizeof vect_o, "%s/%s.vect", other, name);
    snprintf(row, sizeof row, "%s/%s.row.tsv", out, name);
    snprintf(vect, sizeof vect, "%s/%s.vect", out, name);
    snprintf(ckpt, sizeof ckpt, "%s/%s.ckpt", out, name);
    *outcome = TR_MERGE_ABSENT;
    snprintf(what, what_size, "no record in %s", other);
    if (!exists(row_o))
        return TR_OK;
    tr_batch_row theirs, ours;
    int rc = tr_batch_row_read(row_o, &theirs, err);
    if (rc != TR_OK)
        return rc;
    int have = exists(row);
    if (have && (rc = tr_batch_row_read(row, &ours, err)) != TR_OK)
        return rc;
    if (have) {
        /* a ropelength at another N answers another question; NAN never wins */
        int shorter = theirs.n == ours.n && isfinite(theirs.ropelength) &&
                      (!isfinite(ours.ropelength) || theirs.ropelength < ours.ropelength);
        if (!shorter) {
            *outcome = TR_MERGE_KEPT;
            if (theirs.n != ours.n)
                snprintf(what, what_size, "kept (%s's N %zu is not this one's %zu)", other, theirs.n, ours.n);
            else
                snprintf(what, what_size, "kept %.10f (%s's %.10f is not shorter)", ours.ropelength, other,
                         theirs.ropelength);
            return TR_OK;
        }
    }
    if ((rc = copy_atomic(vect_o, vect, err)) != TR_OK || (rc = tr_batch_row_write(row, &theirs, err)) != TR_OK)
        return rc;
    unlink(ckpt);
    *outcome = have ? TR_MERGE_SHORTER : TR_MERGE_TAKEN;
    if (have)
        snprintf(what, what_size, "%.10f -> %.10f from %s", ours.ropelength, theirs.ropelength, other);
    else
        snprintf(what, what_size, "%.10f taken from %s", theirs.ropelength, other);
    return TR_OK;
}
