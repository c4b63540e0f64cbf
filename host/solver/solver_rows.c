/* This file contains the solver's side of the backend's strut rows
 * (solver_rows.h). */
#include "solver/solver_rows.h"

#include <stdlib.h>

void tr_solver_rows_free(tr_solver_rows *r)
{
    free(r->quad);
    free(r->lam);
    r->quad = NULL;
    r->lam = NULL;
    r->cap = 0;
}

int tr_solver_rows_eval(const tr_backend *b, tr_solver_rows *r, const double *x, size_t nv, const tr_strut_pair *sp,
                        size_t nsp, const size_t *next, double mu, int mode, double band, double sum0,
                        tr_strut_rows *out, tr_error *err)
{
    if (!b->ops->strut_rows)
        return tr_fail(err, TR_EUNSUPPORTED, "the %s backend has no strut rows", b->ops->name);
    if (nsp > r->cap || !r->quad) {
        size_t cap = nsp + nsp / 2 + 64;
        size_t *q = realloc(r->quad, 4 * cap * sizeof *q);
        if (q)
            r->quad = q;
        double *l = q ? realloc(r->lam, cap * sizeof *l) : NULL;
        if (!l)
            return tr_fail(err, TR_ENOMEM, "out of memory (strut rows, %zu pairs)", nsp);
        r->lam = l;
        r->cap = cap;
    }
    for (size_t p = 0; p < nsp; p++) {
        size_t a = sp[p].a, c = sp[p].b;
        r->quad[4 * p] = a;
        r->quad[4 * p + 1] = next[a];
        r->quad[4 * p + 2] = c;
        r->quad[4 * p + 3] = next[c];
        r->lam[p] = sp[p].lam;
    }
    *out = (tr_strut_rows){.mode = mode, .nv = nv, .np = nsp, .x = x, .quad = r->quad, .lam = r->lam, .mu = mu,
                           .dist = 2.0, .band = band, .sum0 = sum0};
    return b->ops->strut_rows(b->state, out, err);
}
