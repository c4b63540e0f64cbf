/* `tightrope batch --compare knotinfo`: the reference of the knots' table
 * built into the program, KnotInfo's ropelength of each knot (the
 * published best values of the ridgerunner era; topology/knot_table.h),
 * in place of a reference file. LinkInfo lists no ropelength: a link has
 * no line (a file such as bench/data/link_ropelength.tsv compares links). */
#ifndef TR_BATCH_KNOTINFO_H
#define TR_BATCH_KNOTINFO_H

#include "cli/batch_manifest.h"
#include "cli/batch_table.h"
#include "util/error.h"

/* The word --compare takes for it; a file so named is ./knotinfo. */
#define TR_BATCH_REF_KNOTINFO "knotinfo"

/* The reference for the knots of l, a line under each knot's batch name:
 * a start by name (knot 3_1) takes its knot's value; a start by file is
 * looked up by the knot's batch name as make knot reads names (3.1, K3_1
 * and 3_1 alike). A knot without a KnotInfo ropelength (a link, the
 * unknot, a name not in the table) has no line. N is none (KnotInfo gives
 * the smooth curve's value). */
int tr_batch_ref_knotinfo(const tr_batch_list *l, tr_batch_ref *ref, tr_error *err);

#endif
