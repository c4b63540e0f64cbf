/* tightrope measure --identify (measure_identify.h). */
#include "cli/measure_identify.h"

#include <stdio.h>
#include <string.h>

#include "tighten/knot_start.h"
#include "topology/knot_table.h"

int tr_measure_identify(const char *file, const tr_curve *c, const char *name)
{
    tr_error err = {{0}};
    tr_knot_table t;
    if (tr_knot_table_load(&t, &err)) {
        fprintf(stderr, "tightrope measure: the embedded knot table: %s\n", err.msg);
        return 1;
    }
    int is_link = c->ncomp > 1, status = 0;
    const tr_table_entry *want = NULL;
    if (name) {
        want = tr_knot_table_find(&t, name, -1);
        if (!want) {
            char near[256];
            tr_knot_table_suggest(&t, name, is_link, near, sizeof near);
            fprintf(stderr, "tightrope measure: --identify: no knot or link named '%s' in the table; nearest: %s\n",
                    name, near);
            tr_knot_table_free(&t);
            return 2;
        }
    }
    tr_type_check tc;
    int rc = tr_type_check_of(c, &tc, &err);
    if (rc) {
        fprintf(stderr, "tightrope measure: %s: its type cannot be computed: %s\n", file, err.msg);
        tr_knot_table_free(&t);
        return rc == TR_ENOMEM ? 1 : 2;
    }
    char got[600], why[1024];
    tr_type_describe(&tc, got, sizeof got);
    printf("%s: %s\n", file, got);
    if (want) {
        int ok = tr_type_matches(&tc, want, why, sizeof why);
        if (ok)
            printf("identify %s: match (its invariants are %s's%s)\n", want->name, want->name,
                   tr_type_is_mirror(&tc, want) ? "; the signature opposite: the mirror image of KnotInfo's diagram"
                                                : "");
        else {
            printf("identify %s: MISMATCH: %s\n", want->name, why);
            fprintf(stderr, "tightrope measure: %s is not %s: %s\n", file, want->name, why);
        }
        status = ok ? 0 : 1;
    }
    /* the candidates: every table entry of the same invariants (a link by
     * its unoriented name, once) */
    int count = 0;
    printf("candidates:");
    for (int i = 0; i < t.n; i++) {
        const tr_table_entry *e = &t.e[i];
        if (e->is_link != is_link || !tr_type_matches(&tc, e, why, sizeof why))
            continue;
        if (e->is_link && i > 0 && !strcmp(t.e[i - 1].unoriented, e->unoriented) && count > 0)
            continue;
        printf(" %s", e->is_link ? e->unoriented : e->name);
        count++;
    }
    printf(count ? " (%d of the table's %s with these invariants%s)\n" : " none in the table (%d; %s%s)\n", count,
           is_link ? "links to 9 crossings" : "knots to 12 crossings",
           is_link ? "" : "; a name stands for a knot and its mirror image");
    if (!want && count == 0) {
        fprintf(stderr, "tightrope measure: %s: no %s in the table has these invariants\n", file,
                is_link ? "link" : "knot");
        status = 1;
    }
    tr_knot_table_free(&t);
    return status;
}
