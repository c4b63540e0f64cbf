/* This file contains the sparse Cholesky solve of (A A^T + U U^T + beta I) z = v that the KKT
 * certificate needs (rowchol.h). */
#include "oracle/rowchol.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>

struct tr_rowchol {
    cholmod_common cm;
    cholmod_factor *L;
    size_t nr;
    int nu;     /* the dense columns left to Woodbury (the others are in L) */
    int *ucol;  /* per row: its Woodbury column, or -1 */
    double *uval;
    double *KU; /* nr x nu, column-major: (A A^T + beta I)^-1 U */
    double *S;  /* nu x nu Cholesky factor (lower) of I + U^T KU */
    /* pins: rows held at 0 (tr_rowchol_pin) */
    size_t np, capp;
    size_t *pin;
    double *MP; /* nr x np, column-major: N^-1 e_pin (N the whole matrix) */
    double *LP; /* capp x capp, lower: Cholesky of (N^-1)[pin, pin] */
};

static int chol_fail(tr_rowchol *f, tr_error *err, const char *what)
{
    return tr_fail(err, f->cm.status == CHOLMOD_OUT_OF_MEMORY ? TR_ENOMEM : TR_EGEOMETRY,
                   "KKT certificate: cholmod %s failed (status %d)", what, f->cm.status);
}

/* K^-1 v with the CHOLMOD factor, into z (nr). */
static int ksolve(tr_rowchol *f, const double *v, double *z, tr_error *err)
{
    cholmod_dense *b = cholmod_l_allocate_dense(f->nr, 1, f->nr, CHOLMOD_REAL, &f->cm);
    if (!b)
        return chol_fail(f, err, "allocate_dense");
    memcpy(b->x, v, f->nr * sizeof *v);
    cholmod_dense *x = cholmod_l_solve(CHOLMOD_A, f->L, b, &f->cm);
    cholmod_l_free_dense(&b, &f->cm);
    if (!x)
        return chol_fail(f, err, "solve");
    memcpy(z, x->x, f->nr * sizeof *z);
    cholmod_l_free_dense(&x, &f->cm);
    return TR_OK;
}

static int dense_cholesky(double *S, int n)
{
    for (int j = 0; j < n; j++) {
        double d = S[j * n + j];
        for (int k = 0; k < j; k++)
            d -= S[j * n + k] * S[j * n + k];
        if (!(d > 0.0))
            return -1;
        S[j * n + j] = sqrt(d);
        for (int i = j + 1; i < n; i++) {
            double a = S[i * n + j];
            for (int k = 0; k < j; k++)
                a -= S[i * n + k] * S[j * n + k];
            S[i * n + j] = a / S[j * n + j];
        }
    }
    return 0;
}

/* Which dense columns go into the sparse factor. A column u_k is non-zero
 * on the m_k rows of component k only. Kept apart (Sherman-Morrison-
 * Woodbury) it costs a solve with the whole factor, nr numbers of KU, nr
 * operations in every later solve and a row and column of the dense nu x nu
 * Cholesky (nu^3 / 3 in all: with 2000 small components that was minutes,
 * and KU gigabytes). Put into A as one more sparse column it costs the
 * clique it makes among its m_k rows: m_k^2 / 2 entries of L, m_k^2
 * operations per solve. So it goes in when m_k^2 <= nr: every component
 * of a link of many small ones, never the component of a knot (m_k = nr),
 * which keeps its Woodbury column and its numbers as before. */
static int embedded(size_t mk, size_t nr)
{
    return mk > 0 && (double)mk * (double)mk <= (double)nr;
}

int tr_rowchol_factor(tr_rowchol **out, const tr_rowsys *a, double beta, tr_error *err)
{
    *out = NULL;
    tr_rowchol *f = calloc(1, sizeof *f);
    if (!f)
        return tr_fail(err, TR_ENOMEM, "out of memory (KKT factor)");
    cholmod_l_start(&f->cm);
    f->cm.print = 0; /* the library reports through its status, never on stderr */
    f->cm.error_handler = NULL;
    f->nr = a->nr;
    int rc = TR_OK;
    cholmod_sparse *A = NULL;
    /* rows per dense column, then each column's place: -2 - j for sparse
     * column ncols + j, or its Woodbury index w >= 0 */
    size_t nuz = a->nu > 0 ? (size_t)a->nu : 1, nemb = 0, nnz = a->rowptr[a->nr];
    size_t *mk = calloc(nuz, sizeof *mk);
    int *place = malloc(nuz * sizeof *place);
    if (!mk || !place) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (KKT factor)");
        goto fail;
    }
    for (size_t r = 0; r < a->nr; r++)
        if (a->nu > 0 && a->uval[r] != 0.0)
            mk[a->ucol[r]]++;
    for (int k = 0; k < a->nu; k++) {
        if (embedded(mk[k], a->nr))
            place[k] = -2 - (int)nemb++;
        else
            place[k] = f->nu++;
    }
    for (size_t r = 0; r < a->nr; r++)
        nnz += a->nu > 0 && a->uval[r] != 0.0 && place[a->ucol[r]] < 0;
    cholmod_triplet *t =
        cholmod_l_allocate_triplet(a->nr, a->ncols + nemb, nnz ? nnz : 1, 0, CHOLMOD_REAL, &f->cm);
    if (!t) {
        rc = chol_fail(f, err, "allocate_triplet");
        goto fail;
    }
    SuiteSparse_long *ti = t->i, *tj = t->j;
    double *tx = t->x;
    for (size_t r = 0; r < a->nr; r++) {
        for (size_t e = a->rowptr[r]; e < a->rowptr[r + 1]; e++) {
            ti[t->nnz] = (SuiteSparse_long)r;
            tj[t->nnz] = (SuiteSparse_long)a->col[e];
            tx[t->nnz++] = a->val[e];
        }
        if (a->nu > 0 && a->uval[r] != 0.0 && place[a->ucol[r]] < 0) {
            ti[t->nnz] = (SuiteSparse_long)r;
            tj[t->nnz] = (SuiteSparse_long)(a->ncols + (size_t)(-2 - place[a->ucol[r]]));
            tx[t->nnz++] = a->uval[r];
        }
    }
    A = cholmod_l_triplet_to_sparse(t, nnz, &f->cm);
    cholmod_l_free_triplet(&t, &f->cm);
    if (!A) {
        rc = chol_fail(f, err, "triplet_to_sparse");
        goto fail;
    }
    /* unsymmetric A: CHOLMOD analyses and factors A A^T + beta I */
    f->L = cholmod_l_analyze(A, &f->cm);
    double b2[2] = {beta, 0.0};
    int ok = f->L && cholmod_l_factorize_p(A, b2, NULL, 0, f->L, &f->cm) && f->cm.status == CHOLMOD_OK;
    cholmod_l_free_sparse(&A, &f->cm);
    if (!ok) {
        rc = chol_fail(f, err, "factorize");
        goto fail;
    }
    if (f->nu > 0) {
        size_t nu = (size_t)f->nu;
        f->ucol = malloc(a->nr * sizeof *f->ucol);
        f->uval = malloc(a->nr * sizeof *f->uval);
        f->KU = calloc(a->nr * nu, sizeof *f->KU);
        f->S = calloc(nu * nu, sizeof *f->S);
        if (!f->ucol || !f->uval || !f->KU || !f->S) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory (KKT factor)");
            goto fail;
        }
        for (size_t r = 0; r < a->nr; r++) {
            int w = place[a->ucol[r]];
            f->ucol[r] = w >= 0 && a->uval[r] != 0.0 ? w : -1;
            f->uval[r] = a->uval[r];
        }
        for (int k = 0; k < f->nu; k++) {
            double *col = f->KU + (size_t)k * a->nr;
            for (size_t r = 0; r < a->nr; r++)
                col[r] = f->ucol[r] == k ? f->uval[r] : 0.0;
            if ((rc = ksolve(f, col, col, err)))
                goto fail;
        }
        /* S = I + U^T KU, column by column: one pass over the rows each */
        for (int j = 0; j < f->nu; j++) {
            const double *col = f->KU + (size_t)j * a->nr;
            f->S[j * f->nu + j] = 1.0;
            for (size_t r = 0; r < a->nr; r++)
                if (f->ucol[r] >= 0)
                    f->S[f->ucol[r] * f->nu + j] += f->uval[r] * col[r];
        }
        if (dense_cholesky(f->S, f->nu)) {
            rc = tr_fail(err, TR_EGEOMETRY, "KKT certificate: the edge-length block is not positive definite");
            goto fail;
        }
    }
    free(mk);
    free(place);
    *out = f;
    return TR_OK;
fail:
    free(mk);
    free(place);
    tr_rowchol_free(f);
    return rc;
}

/* z = N^-1 v, N = A A^T + U U^T + beta I, pins ignored. */
static int full_solve(tr_rowchol *f, const double *v, double *z, tr_error *err)
{
    int rc = ksolve(f, v, z, err);
    if (rc || f->nu == 0)
        return rc;
    /* Woodbury: z -= KU (I + U^T KU)^-1 U^T z */
    int n = f->nu;
    double e[64], *ev = n <= 64 ? e : malloc((size_t)n * sizeof *ev);
    if (!ev)
        return tr_fail(err, TR_ENOMEM, "out of memory (KKT solve)");
    for (int k = 0; k < n; k++)
        ev[k] = 0.0;
    for (size_t r = 0; r < f->nr; r++)
        if (f->ucol[r] >= 0)
            ev[f->ucol[r]] += f->uval[r] * z[r];
    for (int i = 0; i < n; i++) { /* forward, then back substitution with S S^T */
        for (int k = 0; k < i; k++)
            ev[i] -= f->S[i * n + k] * ev[k];
        ev[i] /= f->S[i * n + i];
    }
    for (int i = n - 1; i >= 0; i--) {
        for (int k = i + 1; k < n; k++)
            ev[i] -= f->S[k * n + i] * ev[k];
        ev[i] /= f->S[i * n + i];
    }
    for (int k = 0; k < n; k++) {
        const double *col = f->KU + (size_t)k * f->nr;
        for (size_t r = 0; r < f->nr; r++)
            z[r] -= col[r] * ev[k];
    }
    if (ev != e)
        free(ev);
    return TR_OK;
}

int tr_rowchol_solve(tr_rowchol *f, const double *v, double *z, tr_error *err)
{
    int rc = full_solve(f, v, z, err);
    if (rc || f->np == 0)
        return rc;
    /* z -= N^-1 E lambda with (E^T N^-1 E) lambda = E^T z: then z_pin = 0 */
    size_t n = f->np;
    double *lam = malloc(n * sizeof *lam);
    if (!lam)
        return tr_fail(err, TR_ENOMEM, "out of memory (KKT solve)");
    for (size_t i = 0; i < n; i++) {
        double a = z[f->pin[i]];
        for (size_t k = 0; k < i; k++)
            a -= f->LP[i * f->capp + k] * lam[k];
        lam[i] = a / f->LP[i * f->capp + i];
    }
    for (size_t i = n; i-- > 0;) {
        for (size_t k = i + 1; k < n; k++)
            lam[i] -= f->LP[k * f->capp + i] * lam[k];
        lam[i] /= f->LP[i * f->capp + i];
    }
    for (size_t k = 0; k < n; k++) {
        const double *col = f->MP + k * f->nr;
        for (size_t r = 0; r < f->nr; r++)
            z[r] -= col[r] * lam[k];
    }
    for (size_t k = 0; k < n; k++)
        z[f->pin[k]] = 0.0; /* exactly, not to rounding */
    free(lam);
    return TR_OK;
}

size_t tr_rowchol_pinned(const tr_rowchol *f)
{
    return f->np;
}

int tr_rowchol_pin(tr_rowchol *f, size_t j, tr_error *err)
{
    if (j >= f->nr)
        return tr_fail(err, TR_EINVAL, "KKT certificate: pin of row %zu of %zu", j, f->nr);
    for (size_t k = 0; k < f->np; k++)
        if (f->pin[k] == j)
            return TR_OK;
    if (f->np == f->capp) {
        size_t nc = f->capp ? 2 * f->capp : 16;
        size_t *pin = realloc(f->pin, nc * sizeof *pin);
        if (pin)
            f->pin = pin;
        double *mp = pin ? realloc(f->MP, nc * f->nr * sizeof *mp) : NULL;
        if (mp)
            f->MP = mp;
        double *lp = mp ? calloc(nc * nc, sizeof *lp) : NULL;
        if (!lp)
            return tr_fail(err, TR_ENOMEM, "out of memory (KKT pins)");
        for (size_t a = 0; a < f->np; a++)
            memcpy(lp + a * nc, f->LP + a * f->capp, f->np * sizeof *lp);
        free(f->LP);
        f->LP = lp;
        f->capp = nc;
    }
    double *u = f->MP + f->np * f->nr;
    memset(u, 0, f->nr * sizeof *u);
    u[j] = 1.0;
    int rc = full_solve(f, u, u, err);
    if (rc)
        return rc;
    /* append to the Cholesky factor of (N^-1)[pin, pin]: row l = L^-1 s, d */
    size_t n = f->np;
    double *row = f->LP + n * f->capp, d = u[j];
    for (size_t i = 0; i < n; i++) {
        double a = u[f->pin[i]];
        for (size_t k = 0; k < i; k++)
            a -= f->LP[i * f->capp + k] * row[k];
        row[i] = a / f->LP[i * f->capp + i];
        d -= row[i] * row[i];
    }
    if (!(d > 0.0))
        return tr_fail(err, TR_EGEOMETRY, "KKT certificate: pinned rows are dependent");
    row[n] = sqrt(d);
    f->pin[n] = j;
    f->np = n + 1;
    return TR_OK;
}

void tr_rowchol_free(tr_rowchol *f)
{
    if (!f)
        return;
    if (f->L)
        cholmod_l_free_factor(&f->L, &f->cm);
    cholmod_l_finish(&f->cm);
    free(f->ucol);
    free(f->uval);
    free(f->KU);
    free(f->S);
    free(f->pin);
    free(f->MP);
    free(f->LP);
    free(f);
}
