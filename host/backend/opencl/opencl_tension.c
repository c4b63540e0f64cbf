/* This file contains the OpenCL backend's tension_step (backend.h): the
 * force, its low-pass passes, its projection on the tangent cone of the
 * active rows, and the capped move (kernels/tension.cl). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/opencl_state.h"

/* backend.h tension_step 2b: G <- P G, then its component tangent to the
 * active rows (releasing pulling inequality rows between passes); leaves the
 * ebar velocity's negative in debar. */
static int project_tangent(cl_state *s, const tr_correct_params *q, cl_mem G, tr_error *err)
{
    int rc = TR_OK;
    int nv = s->nv, n3 = 3 * nv;
    double reg0 = 0.0, zero = 0.0;
    int izero = 0;
    TR_TRY(clb_eval_rows(s, q, err));
    TR_TRY(clb_run(s, K_project_field, (size_t)nv, err, A(G), A(s->cidx), A(s->cst), A(nv), END));
    for (int pass = 0; pass < q->max_newton; pass++) {
        TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, G, s->dx, 0, 0, (size_t)n3 * sizeof(double), 0,
                                        NULL, NULL));
        TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->debar, &zero, sizeof zero, 0,
                                        (size_t)s->ncomp * sizeof(double), 0, NULL, NULL));
        TR_TRY(clb_solve_rows(s, err));
        int nl = s->cg_nl;
        TR_CL_CHECK(clEnqueueFillBuffer(s->ctx.queue, s->y, &zero, sizeof zero, 0,
                                        (size_t)nl * sizeof(double), 0, NULL, NULL));
        /* b = J (G, debar = 0), no regularisation term (y = 0) */
        TR_TRY(clb_run(s, K_j_rows, clb_jrows_units(s, nl), err, A(s->dx), A(s->debar), A(s->cdeb), A(s->row_grad),
                   A(s->cgq), A(s->row_active), A(s->topo.next), A(s->topo.prev), A(s->topo.comp),
                   A(s->sab), A(s->sw), A(s->y), A(nv), A(reg0), A(s->act), A(nl), A(s->b),
                   A(s->part), A(s->blkf), END));
        TR_TRY(clb_run(s, K_cg_reset, (size_t)nl, err, A(s->b), A(s->y), A(s->r), A(s->p), A(nl), END));
        int iters = 0;
        TR_TRY(clb_cg_iterate(s, q, &iters, err));
        if (pass + 1 < q->max_newton && nl > nv) {
            int changed = 0;
            TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, s->changed, CL_FALSE, 0, sizeof izero, &izero, 0,
                                             NULL, NULL));
            TR_TRY(clb_run(s, K_release_pulling, (size_t)(nl - nv), err, A(s->row_active), A(s->y), A(nv), A(s->act),
                       A(nl), A(s->changed), END));
            TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->changed, CL_TRUE, 0, sizeof changed, &changed,
                                            0, NULL, NULL));
            if (changed)
                continue;
        }
        break;
    }
    TR_TRY(clb_apply_JT(s, q, s->y, err));
    TR_TRY(clb_run(s, K_tangent_finish, (size_t)n3, err, A(G), A(s->dx), A(n3), END));
cleanup:
    return rc;
}

int clb_tension_step(void *sp, const tr_tension_params *prm, tr_tension_stats *out,
                           tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    int nv = s->nv;
    double h = prm->h, mm = prm->max_move;
    TR_TRY(clb_run(s, K_tension_force, (size_t)nv, err, A(s->x), A(s->topo.next), A(s->topo.prev), A(nv),
               A(s->force), END));
    cl_mem G = s->field, H = s->field_tmp;
    TR_CL_CHECK(clEnqueueCopyBuffer(s->ctx.queue, s->force, G, 0, 0, 3 * (size_t)nv * sizeof(double), 0,
                                    NULL, NULL));
    for (int pass = 0; pass < prm->smooth_passes; pass++) {
        TR_TRY(clb_run(s, K_tension_smooth, (size_t)nv, err, A(G), A(s->topo.next), A(s->topo.prev),
                   A(nv), A(H), END));
        cl_mem t = G;
        G = H;
        H = t;
    }
    TR_TRY(clb_run(s, K_tension_smooth2, (size_t)nv, err, A(G), A(s->cidx), A(s->cst), A(nv), A(s->vterm_a), END));
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->vterm_a, nv, s->sc, SC_SMOOTH2, err));
    if (prm->project) {
        TR_TRY(clb_ensure_rows(s, err));
        TR_TRY(project_tangent(s, prm->project, G, err));
        TR_TRY(tr_cl_reduce_dot(&s->red, &s->ctx, G, G, 3 * nv, s->sc, SC_FREE2, err));
    }
    TR_TRY(clb_run(s, K_tension_move, (size_t)nv, err, A(s->x), A(s->force), A(G), A(s->cidx), A(s->cst), A(nv), A(h),
               A(mm), A(s->vterm_a), A(s->vterm_b), A(s->vterm_c), END));
    if (prm->project)
        TR_TRY(clb_run(s, K_ebar_velocity, (size_t)s->ncomp, err, A(s->ebar), A(s->debar), A(h),
                   A(s->ncomp), END));
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->vterm_a, nv, s->sc, SC_F2, err));
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, s->vterm_b, nv, s->sc, SC_PRED, err));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->vterm_c, nv, s->sc, SC_MOVE, err));
    double v[14];
    TR_TRY(clb_read_scalars(s, SC_F2, 14, v, err)); /* slots 16 .. 29 */
    if (out) {
        out->force2 = v[0];
        out->predicted = v[1];
        out->max_move = v[3];
        out->smooth2 = v[SC_SMOOTH2 - SC_F2];
        out->free2 = prm->project ? v[SC_FREE2 - SC_F2] : v[SC_SMOOTH2 - SC_F2];
    }
cleanup:
    return rc;
}

