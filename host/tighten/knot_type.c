/* This file contains the check that a tightening kept its start's knot
 * type (knot_type.h): the invariants of both curves and their comparison. */
#include "tighten/knot_type.h"

#include <stdio.h>
#include <string.h>

#include "topology/linking.h"

void tt_knot_type_of(const tr_curve *c, tt_knot_type *t)
{
    memset(t, 0, sizeof *t);
    for (int k = 0; k < c->ncomp; k++)
        if (!c->closed[k]) {
            snprintf(t->why, sizeof t->why, "component %d is open", k);
            return;
        }
    tr_error err = {0};
    if (c->ncomp == 1) {
        if (tr_knot_invariants_of(c, &t->inv, &err) == TR_OK)
            t->kind = 1;
        else
            snprintf(t->why, sizeof t->why, "%.1000s", err.msg);
        return;
    }
    if (c->ncomp > TT_TYPE_MAX_COMPONENTS) {
        snprintf(t->why, sizeof t->why, "%d components (the check takes %d)", c->ncomp, TT_TYPE_MAX_COMPONENTS);
        return;
    }
    if (tr_linking_numbers(c, t->lk, &err) == TR_OK) {
        t->kind = 2;
        t->ncomp = c->ncomp;
    } else
        snprintf(t->why, sizeof t->why, "%.1000s", err.msg);
}

int tt_knot_type_same(const tt_knot_type *a, const tt_knot_type *b)
{
    if (a->kind != b->kind)
        return 0;
    if (a->kind == 1)
        return tr_alexander_equal(&a->inv.alexander, &b->inv.alexander) &&
               a->inv.alexander.determinant == b->inv.alexander.determinant &&
               a->inv.signature == b->inv.signature;
    if (a->ncomp != b->ncomp)
        return 0;
    size_t m = (size_t)a->ncomp * (size_t)a->ncomp;
    for (size_t i = 0; i < m; i++)
        if (a->lk[i] != b->lk[i])
            return 0;
    return 1;
}

void tt_knot_type_line(const tt_knot_type *t, char *buf, size_t n)
{
    size_t used;
    if (t->kind == 1) {
        used = (size_t)snprintf(buf, n, "Alexander polynomial");
        for (int i = 0; i <= t->inv.alexander.span && used < n; i++)
            used += (size_t)snprintf(buf + used, n - used, " %lld", t->inv.alexander.coef[i]);
        if (used < n)
            snprintf(buf + used, n - used, ", determinant %lld, signature %d", t->inv.alexander.determinant,
                     t->inv.signature);
        return;
    }
    used = (size_t)snprintf(buf, n, "linking numbers");
    for (int i = 0; i < t->ncomp && used < n; i++)
        for (int j = i + 1; j < t->ncomp && used < n; j++)
            used += (size_t)snprintf(buf + used, n - used, " %d", t->lk[i * t->ncomp + j]);
}
