/* This file contains the vertex constraints (clasp ends on planes), eliminated onto the allowed motions. */
#include "solver/newton_internal.h"

#include <string.h>

/* ---- vertex constraints (clasp ends on planes) ----
 *
 * A constrained vertex moves only within its constraint: P_i, the
 * projector onto the motions it allows (curve.h: the plane's directions,
 * the line's, none for a fixed point). The constraints are linear, so they
 * are eliminated rather than written as rows of L_A: every row's gradient
 * and Hessian are taken on the allowed motions (g_i <- P_i g_i, the row's
 * block Q^T H Q with Q = diag(P_i): exact for the reduced problem, since Q
 * is block diagonal per vertex), and I - P_i goes on the vertex's diagonal
 * block so the matrix stays nonsingular. The Newton system then has
 * (I - P_i) dir_i = 0, so a vertex on its plane stays there to rounding at
 * every step, and no multiplier or penalty is involved. Equality rows
 * n.x_i - d = 0 in L_A would instead need their own multipliers to
 * converge (linearly, at a rate 1 / mu) and leave the ends lambda / mu off
 * their planes at every pass, to be projected back at the end at some cost
 * in thickness; the elimination is also what the reference backend's P_i
 * and the KKT oracle (kkt.h) do, so the three agree on what "held" means. */
const tr_constraint *tr_newton_i_vertex_cst(const solver *s, size_t v)
{
    return s->w.vcst && s->w.vcst[v] >= 0 ? &s->w.cst[s->w.vcst[v]] : NULL;
}

/* P (3 x 3, symmetric): the projector onto the motions k allows */
void tr_newton_i_allowed_projector(const tr_constraint *k, double P[9])
{
    for (int c = 0; c < 3; c++) {
        double e[3] = {c == 0, c == 1, c == 2};
        tr_constraint_project_motion(k, e);
        for (int r = 0; r < 3; r++)
            P[3 * r + c] = e[r];
    }
}

/* v (3 nv + ncomp) with every constrained vertex's part on its allowed motions */
void tr_newton_i_project_allowed(const solver *s, double *v)
{
    for (size_t q = 0; q < s->ncv; q++) {
        size_t i = s->cv[q];
        tr_constraint_project_motion(tr_newton_i_vertex_cst(s, i), v + 3 * i);
    }
}

/* A row's gradient gr and Hessian H (m x m, or NULL) over idx, whose vertex
 * coordinates come in triples (3 i, 3 i + 1, 3 i + 2) from position 0, on
 * the allowed motions: gr <- Q gr, H <- Q H Q. Returns 0 (nothing copied)
 * when the row touches no constrained vertex. */
int tr_newton_i_project_row(const solver *s, int m, const size_t *idx, const double *gr, const double *H,
                            double *gq, double *Hq)
{
    int any = 0;
    for (int a = 0; a + 2 < m && !any; a += 3)
        any = idx[a] < 3 * s->nv && idx[a] % 3 == 0 && tr_newton_i_vertex_cst(s, idx[a] / 3);
    if (!any)
        return 0;
    memcpy(gq, gr, (size_t)m * sizeof *gq);
    if (H)
        memcpy(Hq, H, (size_t)m * (size_t)m * sizeof *Hq);
    for (int a = 0; a + 2 < m; a += 3) {
        const tr_constraint *k = idx[a] < 3 * s->nv && idx[a] % 3 == 0 ? tr_newton_i_vertex_cst(s, idx[a] / 3) : NULL;
        if (!k)
            continue;
        double P[9], t[3];
        tr_newton_i_allowed_projector(k, P);
        for (int r = 0; r < 3; r++)
            t[r] = P[3 * r] * gq[a] + P[3 * r + 1] * gq[a + 1] + P[3 * r + 2] * gq[a + 2];
        memcpy(gq + a, t, sizeof t);
        if (!H)
            continue;
        for (int c = 0; c < m; c++) { /* rows a..a+2: P H */
            for (int r = 0; r < 3; r++)
                t[r] = P[3 * r] * Hq[a * m + c] + P[3 * r + 1] * Hq[(a + 1) * m + c] + P[3 * r + 2] * Hq[(a + 2) * m + c];
            for (int r = 0; r < 3; r++)
                Hq[(a + r) * m + c] = t[r];
        }
        for (int r = 0; r < m; r++) { /* columns a..a+2: H P */
            for (int c = 0; c < 3; c++)
                t[c] = Hq[r * m + a] * P[c] + Hq[r * m + a + 1] * P[3 + c] + Hq[r * m + a + 2] * P[6 + c];
            for (int c = 0; c < 3; c++)
                Hq[r * m + a + c] = t[c];
        }
    }
    return 1;
}
