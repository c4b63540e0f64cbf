/* Solves with the normal matrix of a sparse row system plus a few dense
 * columns:  (A A^T + U U^T + beta I) z = v,
 * A: nr x ncols sparse (each row touches a few columns), U: nr x nu with at
 * most one non-zero per row (row r has U[r, ucol[r]] = uval[r]).
 *
 * This is the linear algebra of the KKT certificate (kkt.c): the rows are
 * constraint gradients in vertex space (A) and in the common edge lengths
 * of the components (U, one column per component, dense on that
 * component's rows, which would fill A A^T there if factored directly).
 * A A^T + beta I is factored by CHOLMOD (SuiteSparse; fill-reducing ordering,
 * supernodal), with the columns of the small components (m_k rows, m_k^2 <=
 * nr: a link of many small rings) in it as sparse columns of their own, and
 * the rest of U U^T is added by Sherman-Morrison-Woodbury with a Cholesky of
 * their count squared (rowchol.c: the cost of each way).
 * beta > 0 keeps the factor defined when rows are dependent (struts of a
 * tight knot are: many more than the vertices can independently feel). */
#ifndef TR_ROWCHOL_H
#define TR_ROWCHOL_H

#include <stddef.h>
#include <stdint.h>

#include "util/error.h"

typedef struct tr_rowchol tr_rowchol;

/* Row r's entries are col[rowptr[r] .. rowptr[r+1]) with values val[...]. */
typedef struct tr_rowsys {
    size_t nr, ncols;
    const size_t *rowptr, *col;
    const double *val;
    int nu;             /* dense columns (0 allowed) */
    const int *ucol;    /* per row, in [0, nu) */
    const double *uval; /* per row */
} tr_rowsys;

int tr_rowchol_factor(tr_rowchol **out, const tr_rowsys *a, double beta, tr_error *err);
/* z = (A A^T + U U^T + beta I)^-1 v; v and z have nr entries and may alias.
 * With pinned rows: the solution of the same system with z_j = 0 on every
 * pinned j (a bordered system: one Lagrange multiplier per pin). */
int tr_rowchol_solve(tr_rowchol *f, const double *v, double *z, tr_error *err);

/* Pins row j at 0 in every later solve: as if the row had been left out of
 * the factor, for one solve now and a dense update of the pins' small
 * Cholesky factor, instead of a new sparse factorisation. Meant for a few
 * rows at a time (the active-set method drops them one by one); the caller
 * refactors when many are pinned. */
int tr_rowchol_pin(tr_rowchol *f, size_t j, tr_error *err);
size_t tr_rowchol_pinned(const tr_rowchol *f);
void tr_rowchol_free(tr_rowchol *f);

#endif
