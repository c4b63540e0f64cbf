/* tightrope measure --invariants (measure_invariants.h). */
#include "cli/measure_invariants.h"

#include "topology/alexander.h"

int tr_measure_invariants_append(tr_text *t, const tr_curve *c, int json, tr_error *err)
{
    tr_knot_invariants inv;
    int rc = tr_knot_invariants_of(c, &inv, err);
    if (rc)
        return rc;
    const tr_alexander *a = &inv.alexander;
    tr_text_printf(t, "%s", json ? ", \"alexander\": [" : "alexander");
    for (int k = 0; k <= a->span; k++)
        tr_text_printf(t, "%s%lld", json ? (k ? ", " : "") : " ", a->coef[k]);
    if (json)
        tr_text_printf(t, "], \"determinant\": %lld, \"crossings\": %d, \"projected_crossings\": %d", a->determinant,
                       inv.crossings, inv.projected_crossings);
    else
        tr_text_printf(t, "  determinant %lld  crossings %d\n", a->determinant, inv.crossings);
    return 0;
}
