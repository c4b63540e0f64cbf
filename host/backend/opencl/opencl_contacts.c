/* This file contains the OpenCL backend's find_contacts (backend.h): the
 * device tree search, the pair list in both edges' orders, and the closest
 * listed pair (kernels/contacts.cl, kernels/tree.cl). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/opencl_state.h"

/* sc[SC_STRUT] = the smallest distance of a listed pair (np > 0). */
int clb_closest_pair(cl_state *s, tr_error *err)
{
    int rc = TR_OK;
    int np = s->np;
    size_t g = tr_cl_items_global(&s->ctx, (size_t)np);
    TR_TRY(clb_partials(s, g, err));
    TR_TRY(clb_run(s, K_pairs_min_dist, (size_t)np, err, A(s->x), A(s->topo.next), A(s->pair_a), A(s->pair_b),
               A(np), A(s->part), END));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, s->part, (int)g, s->sc, SC_STRUT, err));
cleanup:
    return rc;
}

int clb_find_contacts(void *sp, const tr_contact_params *prm, tr_contact_stats *out,
                            tr_error *err)
{
    cl_state *s = sp;
    int rc = TR_OK;
    int nv = s->nv;
    s->np = 0;
    TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, s->gap, CL_FALSE, 0, (size_t)s->ncomp * sizeof(int),
                                     prm->exclude_gap, 0, NULL, NULL));
    int gmin = 0;
    for (int k = 0; k < s->ncomp; k++)
        gmin = k == 0 || prm->exclude_gap[k] < gmin ? prm->exclude_gap[k] : gmin;
    TR_TRY(tr_cl_tree_search(&s->tree, &s->ctx, &s->red, &s->topo, s->x, prm->cutoff, prm->tilt,
                             s->gap, gmin, err));
    cl_mem list = s->tree.list, loff = s->tree.loff;
    TR_TRY(clb_run(s, K_pairs_upper, (size_t)nv, err, A(s->tree.count), A(list), A(loff), A(s->topo.next),
               A(nv), A(s->upper_count), A(s->upper_first), END));
    /* pair offsets off[0..nv], and the lists' total (2 np when symmetric) */
    TR_TRY(tr_cl_reduce_scan(&s->red, &s->ctx, s->upper_count, nv, s->pair_off, err));
    TR_TRY(tr_cl_reduce_count(&s->red, &s->ctx, s->tree.count, nv, s->sc, SC_LISTED, err));
    int np = 0;
    double listed = 0.0;
    TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, s->pair_off, CL_FALSE, (size_t)nv * sizeof(int), sizeof np,
                                    &np, 0, NULL, NULL));
    TR_TRY(clb_read_scalars(s, SC_LISTED, 1, &listed, err));
    /* every pair is in both edges' lists */
    if (np < 0 || np > (1 << 28) || listed != 2.0 * np) {
        rc = tr_fail(err, TR_EGEOMETRY,
                     "%d contact candidates in partner lists of %.0f entries (want 2 each, at most 2^28 "
                     "pairs): far too many, or the lists are not symmetric",
                     np, listed);
        goto cleanup;
    }
    if (np > s->pcap) {
        int pc = np + np / 2 + 64;
        s->pcap = 0; /* until every buffer of the group is there */
        TR_TRY(clb_buffer(s, &s->pair_a, (size_t)pc * sizeof(int), err));
        TR_TRY(clb_buffer(s, &s->pair_b, (size_t)pc * sizeof(int), err));
        TR_TRY(clb_buffer(s, &s->act, (size_t)pc * sizeof(int), err));
        TR_TRY(clb_buffer(s, &s->dist, (size_t)pc * sizeof(double), err));
        TR_TRY(clb_buffer(s, &s->nbr, 4 * (size_t)pc * sizeof(int), err));
        TR_TRY(clb_buffer(s, &s->actc, ((size_t)pc / TR_ACT_BLOCK + 2) * sizeof(int), err));
        s->pcap = pc;
    }
    TR_TRY(clb_run(s, K_pairs_write, (size_t)nv, err, A(s->tree.count), A(list), A(loff), A(s->upper_first),
               A(s->pair_off), A(nv), A(s->pair_a), A(s->pair_b), END));
    if (np > 0)
        TR_TRY(clb_run(s, K_pairs_neighbours, (size_t)nv, err, A(list), A(loff), A(s->tree.count),
                   A(s->upper_first), A(s->pair_off), A(s->topo.next), A(s->topo.prev), A(nv), A(s->nbr), END));
    s->np = np;
    TR_TRY(clb_ensure_rows(s, err));
    double mind = INFINITY;
    if (np > 0) {
        TR_TRY(clb_closest_pair(s, err));
        TR_TRY(clb_read_scalars(s, SC_STRUT, 1, &mind, err));
    }
    if (out) {
        out->pairs = (size_t)np;
        out->min_dist = mind;
    }
cleanup:
    if (rc != TR_OK)
        s->np = 0; /* an empty list, as after an upload */
    return rc;
}

