/* This file contains the check that a tightening kept its start's knot
 * type (knot_type.h). */
#include "tighten/knot_type.h"

#include <stdio.h>
#include <string.h>

void tt_knot_type_of(const tr_curve *c, tt_knot_type *t)
{
    memset(t, 0, sizeof *t);
    for (int k = 0; k < c->ncomp; k++)
        if (!c->closed[k]) {
            snprintf(t->why, sizeof t->why, "component %d is open", k);
            return;
        }
    tr_error err = {0};
    if (tr_type_check_of(c, &t->tc, &err) == TR_OK)
        t->known = 1;
    else
        snprintf(t->why, sizeof t->why, "%.1000s", err.msg);
}

/* a knot's three, exactly: the Alexander polynomial, determinant, signature */
static int same_knot(const tr_knot_invariants *a, const tr_knot_invariants *b)
{
    return tr_alexander_equal(&a->alexander, &b->alexander) && a->alexander.determinant == b->alexander.determinant &&
           a->signature == b->signature;
}

int tt_knot_type_same(const tt_knot_type *a, const tt_knot_type *b)
{
    const tr_type_check *x = &a->tc, *y = &b->tc;
    if (x->components != y->components || x->npairs != y->npairs)
        return 0;
    if (x->components == 1)
        return same_knot(&x->inv, &y->inv);
    for (int i = 0; i < x->npairs; i++)
        if (x->linking[i] != y->linking[i])
            return 0;
    /* a component whose type one of the two lacks is judged by the
     * linking numbers alone */
    for (int k = 0; k < x->components; k++)
        if (x->comp_known[k] && y->comp_known[k] && !same_knot(&x->comp[k], &y->comp[k]))
            return 0;
    return 1;
}
