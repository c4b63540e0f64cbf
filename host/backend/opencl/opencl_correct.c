/* This file contains the OpenCL backend's correct (backend.h): the rows,
 * their Gauss-Newton iterations and the CG on J M^-1 J^T with its
 * preconditioner (kernels/correct.cl, tridiag.cl, twisted.cl). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/opencl_state.h"

int clb_eval_rows(cl_state *s, const tr_correct_params *prm, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, np = s->np;
    double minrad = prm->minrad, ac = prm->active_curv, sd = prm->strut_dist, as = prm->active_strut;
    /* the largest violation: one partial per work-item, chain rows' first */
    size_t gc = tr_cl_items_global(&s->ctx, (size_t)nv);
    size_t gs = np > 0 ? tr_cl_items_global(&s->ctx, (size_t)np) : 0;
    int voff = (int)gc;
    TR_TRY(clb_partials(s, gc + gs, err));
    TR_TRY(clb_run(s, K_curv_limits, (size_t)s->ncomp, err, A(s->ebar), A(s->ncomp), A(minrad),
               A(s->curv), END));
    TR_TRY(clb_run(s, K_rows_chain, (size_t)nv, err, A(s->x), A(s->topo.next), A(s->topo.prev),
               A(s->topo.comp), A(s->ebar), A(s->curv), A(nv), A(ac), A(s->row_c), A(s->row_grad),
               A(s->row_active), A(s->part), A(s->cgq), A(s->cdeb), END));
    if (np > 0)
        TR_TRY(clb_run(s, K_rows_strut, (size_t)np, err, A(s->x), A(s->topo.next), A(s->topo.prev),
                   A(s->pair_a), A(s->pair_b), A(nv), A(np), A(sd), A(as), A(s->row_c), A(s->row_grad), A(s->row_active),
                   A(s->row_s), A(s->row_t), A(s->dist), A(s->part), A(voff), END));
    if (np > 0)
        TR_TRY(clb_run(s, K_rows_strut_min, (size_t)np, err, A(s->x), A(s->topo.next), A(s->topo.prev),
                   A(s->pair_a), A(s->pair_b), A(s->dist), A(s->nbr), A(nv), A(np), A(s->row_active), END));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->part, (int)(gc + gs), s->sc, SC_VIOL, err));
cleanup:
    return rc;
}

/* dx, debar from the row vector y (the J^T half of the operator). */
int clb_apply_JT(cl_state *s, const tr_correct_params *prm, cl_mem y, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv;
    double w = prm->ebar_weight;
    TR_TRY(clb_run(s, K_jt_vertex, (size_t)nv, err, A(y), A(s->row_grad), A(s->cgq), A(s->row_active), A(s->topo.next),
               A(s->topo.prev), A(s->aadj), A(s->aadjn), A(s->aaoff), A(s->acoef), A(s->agrad), A(s->cidx), A(s->cst),
               A(nv), A(s->dx), A(s->cdeb), A(s->topo.comp), A(s->ncomp), A(s->ebar_part), A(s->blkf),
               END));
    int G = s->ebar_groups;
    if (!s->ctx.block_items) /* on CPU devices jt_vertex's items sum them */
        TR_TRY(clb_run_groups(s, K_jt_ebar_partial, (size_t)s->ncomp * (size_t)G, err, A(y), A(s->row_active),
                          A(s->start), A(s->cdeb), A(nv), A(G), A(s->ebar_part), END));
    cl_mem none = NULL;
    int zero = 0;
    TR_TRY(clb_run_groups(s, K_jt_ebar, (size_t)s->ncomp, err, A(s->ebar_part), A(s->ne), A(G), A(w),
                      A(s->debar), A(none), A(zero), END));
cleanup:
    return rc;
}

/* Solves the edge block whose level-0 set (matrix and right-hand side) is in
 * tset0 by PCR into out; sm: apply the Sherman-Morrison correction of closed
 * components (uu must be solved), else a plain solve (how uu is made). */
static int tridiag_solve(cl_state *s, int sm, cl_mem out, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv;
    cl_mem uu = sm ? s->pcr_uu : s->pdiag; /* pdiag: any buffer, unread when !sm */
    if (s->tri_group) {
        TR_TRY(clb_run_one_group(s, K_tridiag_group, s->tri_group, err, A(s->tri_levels), A(s->pcr_set0),
                             A(s->pcr_p), A(s->pcr_q), A(s->pdiag), A(s->edge_off), A(s->topo.comp),
                             A(s->start), A(s->ne), A(s->closed), A(uu), A(sm), A(nv), A(out),
                             END));
        return TR_OK;
    }
    cl_mem src = s->pcr_set0, dst = s->pcr_p;
    for (int l = 0, stride = 1; l < s->tri_levels; l++, stride *= 2) {
        TR_TRY(clb_run(s, K_tridiag_level, (size_t)nv, err, A(stride), A(s->topo.comp), A(s->start),
                   A(s->ne), A(nv), A(src), A(dst), END));
        src = dst;
        dst = dst == s->pcr_p ? s->pcr_q : s->pcr_p;
    }
    TR_TRY(clb_run(s, K_tridiag_finish, (size_t)nv, err, A(src), A(s->pdiag), A(s->edge_off), A(s->topo.comp),
               A(s->start), A(s->ne), A(s->closed), A(uu), A(sm), A(nv), A(out), END));
cleanup:
    return rc;
}

/* After precond_setup: the PCR level-0 matrix and, for closed components,
 * the Sherman-Morrison vector uu (once per setup; the reference re-solves it
 * in every application, same arithmetic up to rounding). */
static int tridiag_setup(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv;
    TR_TRY(clb_run(s, K_tridiag_matrix, (size_t)nv, err, A(s->pdiag), A(s->edge_off), A(s->topo.comp),
               A(s->start), A(s->ne), A(s->closed), A(nv), A(s->pcr_set0), END));
    if (s->any_closed)
        TR_TRY(tridiag_solve(s, 0, s->pcr_uu, err));
cleanup:
    return rc;
}

/* z = M^-1 r (backend.h correct (c)): the edge block by the chosen solver,
 * and with diag the diagonal on the other rows, which inside the CG loop
 * cg_r has already applied. in_loop (twisted edge block only): inside the
 * CG loop, where the closed blocks' Sherman-Morrison fix is left to
 * cg_p_ring and the edge rows' r . z goes to rzp after cg_r's rz_items
 * shares (cg_iterate). */
static int precond_apply(cl_state *s, cl_mem r, int diag, int in_loop, int rz_items,
                         tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, nl = s->cg_nl;
    size_t d = sizeof(double);
    if (s->tri_twist) {
        size_t items = 2 * (size_t)s->ncomp;
        TR_TRY(clb_run_items(s, K_twist_sweep_rows, items, err, A(r), A(s->edge_off), A(s->start), A(s->ne),
                         A(s->ncomp), A(nv), A(s->edge_work), A(s->tmid), A(s->tends), A(s->z), END));
        TR_TRY(clb_run_items(s, K_twist_back_rows, items, err, A(r), A(s->edge_off), A(s->start), A(s->ne),
                         A(s->ncomp), A(nv), A(s->edge_work), A(s->tmid), A(s->tends), A(s->z), END));
        if (s->any_closed || in_loop)
            TR_TRY(clb_run_items(s, K_twist_ring_fact, (size_t)s->ncomp, err, A(s->pdiag), A(s->edge_off),
                             A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->edge_work),
                             A(s->tends), A(s->rzp), A(rz_items), END));
        if (s->any_closed && !in_loop)
            TR_TRY(clb_run(s, K_twist_ring_fix, (size_t)nv, err, A(s->topo.comp), A(s->ncomp), A(nv),
                       A(s->edge_work), A(s->tends), A(s->z), END));
    } else if (s->tri_pcr) {
        TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, r, s->pcr_set0, 0, 3 * (size_t)nv * d,
                                        (size_t)nv * d, 0, NULL, NULL));
        TR_TRY(tridiag_solve(s, 1, s->z, err));
    } else {
        TR_TRY(clb_run(s, K_precond_edges, (size_t)s->ncomp, err, A(r), A(s->pdiag), A(s->edge_off),
                   A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->edge_work), A(s->z),
                   END));
    }
    if (diag)
        TR_TRY(clb_run(s, K_precond_diag, (size_t)(nl - nv), err, A(r), A(s->pdiag), A(s->row_active), A(nv),
                   A(s->act), A(nl), A(s->z), END));
cleanup:
    return rc;
}

/* The CG's row list for this solve (kernels/correct.cl row_of): every edge
 * and curvature row, then the active strut rows in list order; s->cg_nl
 * its length. One read of the count, once per solve. */
static int row_list(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, np = s->np, bsize = TR_ACT_BLOCK, nb = (np + TR_ACT_BLOCK - 1) / TR_ACT_BLOCK;
    int nact = 0;
    if (np > 0) {
        TR_TRY(clb_run(s, K_act_count, (size_t)nb, err, A(s->row_active), A(nv), A(np), A(bsize), A(nb),
                   A(s->actc), END));
        TR_TRY(clb_run_groups(s, K_act_scan, 0, err, A(nb), A(s->actc), END));
        TR_TRY(clb_run(s, K_act_write, (size_t)nb, err, A(s->row_active), A(nv), A(np), A(bsize), A(nb),
                   A(s->actc), A(s->act), END));
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->actc, CL_TRUE, (size_t)nb * sizeof(int),
                                        sizeof nact, &nact, 0, NULL, NULL));
    }
    s->cg_nl = 2 * nv + nact;
cleanup:
    return rc;
}

/* Fixes the active set of a solve (the caller has evaluated the rows): the
 * CG's row list, by whose positions the solve's vectors are stored, and
 * apply_JT's compact adjacency (4 entries per active strut row). */
int clb_solve_rows(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv;
    TR_TRY(row_list(s, err));
    if (s->cg_nl > s->vcap) { /* the CG's vectors, by row list position */
        size_t n = (size_t)s->cg_nl + (size_t)s->cg_nl / 2 + 64, d = sizeof(double);
        s->vcap = 0;
        cl_mem *v[] = {&s->y, &s->r, &s->p, &s->q, &s->b, &s->z};
        for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
            TR_TRY(clb_buffer(s, v[i], n * d, err));
        s->vcap = (int)n;
    }
    size_t nact = (size_t)(s->cg_nl - 2 * nv), nae = 4 * nact;
    if (nact > s->scap || !s->sab) {
        size_t c = nact + nact / 2 + 64;
        s->scap = 0;
        TR_TRY(clb_buffer(s, &s->sab, 2 * c * sizeof(int), err));
        TR_TRY(clb_buffer(s, &s->sw, 5 * c * sizeof(double), err));
        s->scap = c;
    }
    int na = (int)nact;
    if (na > 0)
        TR_TRY(clb_run(s, K_act_gather, nact, err, A(s->act), A(s->pair_a), A(s->pair_b), A(s->row_s), A(s->row_t),
                   A(s->row_grad), A(nv), A(na), A(s->sab), A(s->sw), END));
    if (nae > s->aacap) {
        size_t c = nae + nae / 2 + 64;
        s->aacap = 0;
        TR_TRY(clb_buffer(s, &s->aadj, c * sizeof(int), err));
        TR_TRY(clb_buffer(s, &s->acoef, c * sizeof(double), err));
        TR_TRY(clb_buffer(s, &s->agrad, 3 * c * sizeof(double), err));
        s->aacap = c;
    }
    /* j_rows' and cg_r's dot product partials, one per work-item (on CPU
     * devices jjt_rows', jt_ebar's and j_struts', cg_iterate) */
    TR_TRY(clb_partials(s, 2 * tr_cl_items_global(&s->ctx, (size_t)s->cg_nl) + (size_t)s->ncomp, err));
    int izero = 0;
    TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->aadjn, &izero, sizeof izero, 0,
                                    (size_t)nv * sizeof(int), 0, NULL, NULL));
    if (na == 0) { /* no active struts: every row of the adjacency is empty */
        TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->aaoff, &izero, sizeof izero, 0,
                                        (size_t)(nv + 1) * sizeof(int), 0, NULL, NULL));
    } else {
        TR_TRY(clb_run(s, K_adj_active_count, nact, err, A(s->act), A(s->pair_a), A(s->pair_b), A(s->topo.next),
                   A(na), A(s->aadjn), END));
        TR_TRY(tr_cl_reduce_scan(&s->red, &s->ctx, s->aadjn, nv, s->aaoff, err));
        TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->aadjn, &izero, sizeof izero, 0,
                                        (size_t)nv * sizeof(int), 0, NULL, NULL));
        TR_TRY(clb_run(s, K_adj_active_write, nact, err, A(s->act), A(s->pair_a), A(s->pair_b), A(s->topo.next),
                   A(s->row_s), A(s->row_t), A(s->row_grad), A(nv), A(na), A(s->aaoff), A(s->aadjn),
                   A(s->aadj), A(s->acoef), A(s->agrad), END));
        TR_TRY(clb_run(s, K_adj_active_sort, (size_t)nv, err, A(s->aaoff), A(nv), A(s->aadj), A(s->acoef),
                   A(s->agrad), END));
    }
    if (s->ctx.block_items && nv >= 4)
        TR_TRY(clb_run(s, K_block_flags, (size_t)(nv / 4), err, A(s->row_active), A(s->topo.next),
                   A(s->topo.prev), A(s->aadjn), A(s->cidx), A(nv), A(s->blkf), END));
cleanup:
    return rc;
}

/* j_rows' and cg_r's global size: one item per row list position on a GPU;
 * on a CPU device one unit per vertex (its edge and curvature rows) and per
 * strut row (kernels/correct.cl j_rows). */
size_t clb_jrows_units(const cl_state *s, int nl)
{
    return s->ctx.block_items ? (size_t)(nl - s->nv) : (size_t)nl;
}

/* q = A p on a CPU device (kernels/correct.cl jjt_rows): the chain rows
 * less their debar term (cg_r adds it), debar, the strut rows, and p . q
 * from jjt_rows' items' shares, then jt_ebar's debar term's shares per
 * component, then j_struts' items' shares. */
static int apply_JJT(cl_state *s, const tr_correct_params *prm, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, nl = s->cg_nl, G = s->ebar_groups;
    int iv = (int)tr_cl_items_global(&s->ctx, (size_t)nv), off = iv + s->ncomp;
    double reg = prm->reg, w = prm->ebar_weight;
    TR_TRY(clb_run(s, K_jjt_rows, (size_t)nv, err, A(s->p), A(s->row_grad), A(s->cgq), A(s->row_active),
               A(s->topo.next), A(s->topo.prev), A(s->aadj), A(s->aadjn), A(s->aaoff), A(s->acoef),
               A(s->agrad), A(s->cidx), A(s->cst), A(nv), A(s->dx), A(s->cdeb), A(s->topo.comp),
               A(s->ncomp), A(s->ebar_part), A(s->blkf), A(reg), A(s->q), A(s->part), END));
    TR_TRY(clb_run_groups(s, K_jt_ebar, (size_t)s->ncomp, err, A(s->ebar_part), A(s->ne), A(G), A(w),
                      A(s->debar), A(s->part), A(iv), END));
    if (nl > 2 * nv) {
        TR_TRY(clb_run(s, K_j_struts, (size_t)(nl - 2 * nv), err, A(s->dx), A(s->debar), A(s->cdeb),
                   A(s->row_grad), A(s->cgq), A(s->row_active), A(s->topo.next), A(s->topo.prev),
                   A(s->topo.comp), A(s->sab), A(s->sw), A(s->p), A(nv), A(reg), A(s->act), A(nl),
                   A(s->q), A(s->part), A(off), END));
        off += (int)tr_cl_items_global(&s->ctx, (size_t)(nl - 2 * nv));
    }
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->part, off, s->sc, SC_PQ, err));
cleanup:
    return rc;
}

/* Preconditioned CG on A y = b from y = 0, r = b (already in place, by row
 * list position; solve_rows has run), as
 * backend.h (c): the device keeps the scalars and turns iterations after
 * convergence into no-ops; the host looks at the flag every fourth iteration. */
int clb_cg_iterate(cl_state *s, const tr_correct_params *prm, int *iters, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, nl = s->cg_nl;
    /* the dot products p . q and r . r come as partials per work-item of
     * j_rows (on CPU devices apply_JJT's kernels) and cg_r (solve_rows
     * reserved them) */
    int items = (int)tr_cl_items_global(&s->ctx, clb_jrows_units(s, nl));
    cl_mem rzp = s->tri_twist ? s->rzp : NULL; /* cg_r's r . z shares: the twisted path's */
    double reg = prm->reg, w = prm->ebar_weight, tol2 = prm->cg_rtol * prm->cg_rtol, it;
    TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, s->sc, CL_FALSE, SC_TOL2 * sizeof(double),
                                     sizeof tol2, &tol2, 0, NULL, NULL));
    TR_TRY(clb_run(s, K_precond_setup, (size_t)nl, err, A(s->row_grad), A(s->cgq), A(s->cdeb), A(s->row_active),
               A(s->topo.next), A(s->topo.prev), A(s->topo.comp), A(s->ne), A(s->pair_a), A(s->pair_b),
               A(s->row_s), A(s->row_t), A(s->cidx), A(s->cst), A(nv), A(s->act), A(nl), A(w), A(reg), A(s->pdiag),
               A(s->edge_off), END));
    if (s->tri_pcr) {
        TR_TRY(tridiag_setup(s, err));
    } else if (s->tri_twist) {
        TR_TRY(clb_run_items(s, K_twist_factor, 2 * (size_t)s->ncomp, err, A(s->pdiag), A(s->edge_off),
                         A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->edge_work),
                         A(s->tmid), A(s->z), END));
        TR_TRY(clb_run_items(s, K_twist_factor_mid, (size_t)s->ncomp, err, A(s->pdiag), A(s->edge_off),
                         A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->edge_work),
                         A(s->tmid), END));
    } else
        TR_TRY(clb_run(s, K_precond_edges_factor, (size_t)s->ncomp, err, A(s->pdiag), A(s->edge_off),
                   A(s->start), A(s->ne), A(s->closed), A(s->ncomp), A(nv), A(s->edge_work), END));
    TR_TRY(precond_apply(s, s->r, 1, 0, 0, err));
    TR_TRY(clb_run(s, K_copy_rows, (size_t)nl, err, A(s->z), A(s->p), A(nl), END));
    TR_TRY(tr_cl_reduce_dot(&s->red, &s->ctx, s->r, s->r, nl, s->sc, SC_RR, err));
    TR_TRY(tr_cl_reduce_dot(&s->red, &s->ctx, s->r, s->z, nl, s->sc, SC_RZ, err));
    TR_TRY(clb_run_groups(s, K_cg_start, 0, err, A(s->sc), END));
    int k;
    for (k = 0; k < prm->max_cg; k++) {
        TR_TRY(clb_run_groups(s, K_cg_top, 0, err, A(s->sc), A(k), END));
        if (k > 0 && k % 4 == 0) {
            double done;
            TR_TRY(clb_read_scalars(s, SC_DONE, 1, &done, err));
            if (done != 0.0)
                break;
        }
        if (s->ctx.block_items)
            TR_TRY(apply_JJT(s, prm, err));
        else {
            TR_TRY(clb_apply_JT(s, prm, s->p, err));
            TR_TRY(clb_run(s, K_j_rows, clb_jrows_units(s, nl), err, A(s->dx), A(s->debar), A(s->cdeb),
                       A(s->row_grad), A(s->cgq), A(s->row_active), A(s->topo.next), A(s->topo.prev),
                       A(s->topo.comp), A(s->sab), A(s->sw), A(s->p), A(nv), A(reg), A(s->act),
                       A(nl), A(s->q), A(s->part), A(s->blkf), END));
            TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->part, items, s->sc, SC_PQ, err));
        }
        TR_TRY(clb_run(s, K_cg_r, clb_jrows_units(s, nl), err, A(s->r), A(s->q), A(s->sc), A(nl),
                   A(s->part), A(s->pdiag), A(s->row_active), A(nv), A(s->act), A(s->z), A(rzp),
                   A(s->debar), A(s->cdeb), A(s->topo.comp), A(s->blkf), END));
        TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->part, items, s->sc, SC_RR, err));
        TR_TRY(precond_apply(s, s->r, 0, 1, items, err));
        if (s->tri_twist) {
            /* r . z from cg_r's and the edge block's shares, and the ring
             * fix applied where cg_p_ring reads z: two passes over the rows
             * fewer than reduce_dot, twist_ring_fix and cg_p */
            TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->rzp, items + s->ncomp, s->sc, SC_RR1, err));
            TR_TRY(clb_run(s, K_cg_p_ring, (size_t)nl, err, A(s->y), A(s->p), A(s->z), A(s->sc), A(nl),
                       A(s->topo.comp), A(s->ncomp), A(nv), A(s->edge_work), A(s->tends), END));
        } else {
            TR_TRY(tr_cl_reduce_dot(&s->red, &s->ctx, s->r, s->z, nl, s->sc, SC_RR1, err));
            TR_TRY(clb_run(s, K_cg_p, (size_t)nl, err, A(s->y), A(s->p), A(s->z), A(s->sc), A(nl), END));
        }
    }
    /* the end of the last iteration (kernels/correct.cl cg_top; nothing
     * after a break, which found the solve done) */
    TR_TRY(clb_run_groups(s, K_cg_top, 0, err, A(s->sc), A(k), END));
    TR_TRY(clb_read_scalars(s, SC_ITERS, 1, &it, err));
    *iters = (int)it;
cleanup:
    return rc;
}

int clb_correct(void *sp, const tr_correct_params *prm, tr_correct_stats *out, tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    TR_TRY(clb_ensure_rows(s, err));
    int nv = s->nv;
    double ms = prm->max_step;
    tr_correct_stats st = {0};
    int it;
    double v[2];
    for (it = 0; it < prm->max_newton; it++) {
        TR_TRY(clb_eval_rows(s, prm, err));
        TR_TRY(clb_read_scalars(s, SC_VIOL, 2, v, err));
        double viol = v[1] > 0.0 ? v[1] : 0.0;
        if (it == 0)
            st.viol_before = viol;
        if (viol <= prm->viol_tol)
            break;
        TR_TRY(clb_solve_rows(s, err));
        int nl = s->cg_nl;
        TR_TRY(clb_run(s, K_cg_init, (size_t)nl, err, A(s->row_c), A(s->row_active), A(nv), A(s->act), A(nl), A(s->b),
                   A(s->y), A(s->r), A(s->p), END));
        /* active rows: those of the chain counted here, the struts are the list's */
        int nchain = 2 * nv;
        TR_TRY(tr_cl_reduce_count(&s->red, &s->ctx, s->row_active, nchain, s->sc, SC_NACT, err));
        int iters = 0;
        TR_TRY(clb_cg_iterate(s, prm, &iters, err));
        st.cg_iters += iters;
        TR_TRY(clb_apply_JT(s, prm, s->y, err));
        TR_TRY(clb_run(s, K_dx_norm, (size_t)nv, err, A(s->dx), A(nv), A(s->vterm_a), END));
        TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->vterm_a, nv, s->sc, SC_MAXDX, err));
        TR_TRY(clb_run_groups(s, K_step_scale, 0, err, A(s->sc), A(ms), END));
        TR_TRY(clb_run(s, K_apply_dx, (size_t)nv, err, A(s->x), A(s->dx), A(s->cidx), A(s->cst), A(s->sc), A(nv), END));
        TR_TRY(clb_run(s, K_apply_debar, (size_t)s->ncomp, err, A(s->ebar), A(s->debar), A(s->sc),
                   A(s->ncomp), END));
        double nact;
        TR_TRY(clb_read_scalars(s, SC_NACT, 1, &nact, err));
        st.active_rows = (size_t)nact + (size_t)(nl - 2 * nv);
    }
    st.newton_iters = it;
    TR_TRY(clb_eval_rows(s, prm, err));
    TR_TRY(clb_read_scalars(s, SC_VIOL, 2, v, err));
    st.viol_after = v[1] > 0.0 ? v[1] : 0.0;
    if (out)
        *out = st;
cleanup:
    return rc;
}

/* ---- force evaluation ---- */

