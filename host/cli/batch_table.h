/* The batch's one table (OUT/table.tsv and OUT/table.json) and the
 * reference table it is compared with (--compare), such as the TightKnot
 * peer table: a TSV whose header names the columns, the knot's name first,
 * a column whose name starts with "ropelength" and optionally "N". */
#ifndef TR_BATCH_TABLE_H
#define TR_BATCH_TABLE_H

#include <stddef.h>

#include "cli/batch_row.h"
#include "util/error.h"

typedef struct tr_batch_ref {
    char **names;
    double *ropelength;
    long *n; /* 0 where the table has no N column */
    size_t count;
} tr_batch_ref;

/* Reads a reference table; TR_EPARSE "FILE:LINE: ..." for a bad line. */
int tr_batch_ref_read(const char *path, tr_batch_ref *ref, tr_error *err);

/* Appends a line (n 0: no N) to ref; -1 out of memory. */
int tr_batch_ref_add(tr_batch_ref *ref, const char *name, double ropelength, long n);
void tr_batch_ref_free(tr_batch_ref *ref);

/* The reference's line for a knot, or -1. Names match with '.' and '_'
 * taken as one character, so KnotPlot's 3.1 is TightKnot's 3_1. */
long tr_batch_ref_find(const tr_batch_ref *ref, const char *knot);

/* Writes the rows (in their order) to dir/table.tsv and dir/table.json,
 * each atomically; with ref, each row gains the reference's N and
 * ropelength and the difference (ours - reference, absolute and in %);
 * the reference's N is '-' (JSON null) where it has none. */
int tr_batch_table_write(const char *dir, const tr_batch_row *rows, size_t count, const tr_batch_ref *ref,
                         tr_error *err);

#endif
