/* The built-in KnotInfo reference of batch --compare (batch_knotinfo.h). */
#include "cli/batch_knotinfo.h"

#include <math.h>
#include <string.h>

#include "topology/knot_table.h"

int tr_batch_ref_knotinfo(const tr_batch_list *l, tr_batch_ref *ref, tr_error *err)
{
    *ref = (tr_batch_ref){0};
    tr_knot_table t;
    int rc = tr_knot_table_load(&t, err);
    if (rc)
        return rc;
    for (size_t i = 0; rc == TR_OK && i < l->count; i++) {
        const tr_batch_knot *k = &l->knots[i];
        const tr_table_entry *e = NULL;
        if (k->from == TR_BATCH_FROM_KNOT)
            e = tr_knot_table_find(&t, strchr(k->source, ':') + 1, 0);
        else if (k->from == TR_BATCH_FROM_FILE)
            e = tr_knot_table_find(&t, k->name, 0);
        if (e && isfinite(e->ropelength) && tr_batch_ref_add(ref, k->name, e->ropelength, 0))
            rc = tr_fail(err, TR_ENOMEM, "out of memory");
    }
    tr_knot_table_free(&t);
    if (rc)
        tr_batch_ref_free(ref);
    return rc;
}
