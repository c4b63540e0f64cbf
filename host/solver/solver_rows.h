/* The second-order solver's strut rows through a backend (backend.h
 * strut_rows): the seam between the solver's rows (newton_rows.c) and the
 * device, so that the solver does not know which backend it drives. */
#ifndef TR_SOLVER_ROWS_H
#define TR_SOLVER_ROWS_H

#include <stddef.h>

#include "backend/backend.h"
#include "geometry/struts.h"

/* The list as the backend takes it (four vertices and a multiplier per
 * pair), rebuilt from the solver's list at every call: the list and its
 * multipliers change between calls (rebuilds, multiplier updates) and
 * copying them costs a few nanoseconds per pair against ~1 us for a
 * Hessian block. */
typedef struct tr_solver_rows {
    size_t *quad;
    double *lam;
    size_t cap;
} tr_solver_rows;

void tr_solver_rows_free(tr_solver_rows *r);

/* Evaluates the pairs sp[0..nsp) (edges a and b; next[] the successor of a
 * vertex) at the positions x (nv vertices) on b: out as strut_rows leaves
 * it for mode (TR_ROWS_VALUE, _GRAD, _HESS), with the bound 2, the
 * multipliers sp[].lam, penalty mu, band and sum0 as backend.h says. */
int tr_solver_rows_eval(const tr_backend *b, tr_solver_rows *r, const double *x, size_t nv, const tr_strut_pair *sp,
                        size_t nsp, const size_t *next, double mu, int mode, double band, double sum0,
                        tr_strut_rows *out, tr_error *err);

#endif
