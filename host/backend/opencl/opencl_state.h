/* This file contains the OpenCL backend's state and the helpers its files
 * share (internal to host/backend/opencl/): backend_opencl.c (open, upload,
 * download, save, restore, measure, the launch helpers), opencl_contacts.c
 * (find_contacts), opencl_tension.c (tension_step) and opencl_correct.c
 * (correct), one file per operation of backend.h as in the reference backend
 * and in kernels/ (contacts.cl, tension.cl, correct.cl). */
#ifndef TR_OPENCL_STATE_H
#define TR_OPENCL_STATE_H

#include <stddef.h>

#include "backend/backend.h"
#include "backend/opencl/cl_device.h"
#include "backend/opencl/cl_error.h"
#include "backend/opencl/cl_reduce.h"
#include "backend/opencl/cl_topology.h"
#include "backend/opencl/cl_tree.h"
#include "layout.h"

/* Kernels the backend launches itself (the reduction and tree modules hold their own). */
#define KERNELS(X)                                                                             \
    X(tension_force) X(tension_smooth) X(tension_move) X(pairs_upper) X(pairs_write)           \
    X(pairs_min_dist) X(rows_chain) X(rows_strut) X(cg_init) X(jt_vertex)          \
    X(jt_ebar_partial) X(jt_ebar) X(j_rows) X(cg_start) X(cg_top) X(cg_r)         \
    X(cg_p) X(dx_norm) X(step_scale) X(apply_dx) X(apply_debar) X(measure_edges)    \
    X(measure_minrad) X(measure_disp) X(comp_sum) X(cg_reset) X(release_pulling)               \
    X(project_field) X(tangent_finish) X(ebar_velocity) X(tension_smooth2) X(precond_setup)    \
    X(precond_diag) X(precond_edges) X(copy_rows) X(precond_edges_factor) X(curv_limits)       \
    X(tridiag_matrix) X(tridiag_level) X(tridiag_finish) X(tridiag_group) X(twist_factor)      \
    X(twist_factor_mid) X(twist_sweep_rows) X(twist_back_rows) X(twist_ring_fact)              \
    X(twist_ring_fix) X(adj_active_count) X(adj_active_write) X(act_count) X(act_scan)         \
    X(act_write) X(act_gather) X(adj_active_sort) X(pairs_neighbours) X(rows_strut_min)     \
    X(cg_p_ring) X(block_flags) X(jjt_rows) X(j_struts)                                       \
    X(strut_rows_value) X(strut_rows_select) X(strut_rows_blocks)
#define ENUM(k) K_##k,
#define NAME(k) #k,
enum { KERNELS(ENUM) K_COUNT };
extern const char *const clb_kernel_names[K_COUNT];

/* strut_rows (opencl_solver_rows.c): on the device the solver's positions,
 * pair list (as ints) and multipliers as the call brings them, per pair its
 * distance, selection flag and the flags' scan (its block's place), the
 * selected blocks, per-item partials and three scalars (sum, min, max); on
 * the host the list as ints and what the call's results point into. Each
 * buffer's capacity in elements beside it. */
typedef struct clb_rows {
    cl_mem x, quad, lam, d, flag, off, g, h, psum, pmin, sc;
    size_t xcap, qcap, lcap, dcap, fcap, ocap, gcap, hcap, partcap, pmcap, sccap;
    int *hquad, *hoff, *hsel;
    double *hd, *hg, *hh;
    size_t hqcap, hocap, hscap, hdcap, hgcap, hhcap;
} clb_rows;

typedef struct cl_state {
    tr_cl_ctx ctx;
    cl_program prog;
    cl_kernel k[K_COUNT];
    tr_cl_reduce red;
    tr_cl_tree tree;
    int tree_ready;
    tr_cl_topology topo;
    int nv, ncomp, saved;
    int *h_start, *h_ne;
    tr_curve shape; /* host copy of the topology and constraints (for upload's snap-free ebar) */
    cl_mem start, ne, cidx, cst, gap;
    cl_mem x, x_saved, ebar, ebar_saved, debar; /* positions, ebar, and their saved copies (save) */
    cl_mem curv; /* per component: largest turning angle and its ebar term (curv_limits) */
    /* the tension step: the force, the field that moves the curve (the force
     * low-passed, then projected), the low-pass's other buffer; the
     * correction's displacement */
    cl_mem force, field, field_tmp, dx;
    /* nv reals each: per-vertex terms an operation reduces to scalars
     * (tension: |F|^2, F . dx, |dx|; measure: lengths, deviations, MinRad) */
    cl_mem vterm_a, vterm_b, vterm_c;
    cl_mem sc;         /* scalars */
    /* contacts */
    int np, pcap;
    /* per vertex: its upper partners' count and the first of them in its
     * list, the pairs' offsets (a scan of the counts); per pair: its two
     * edges' first vertices */
    cl_mem upper_count, upper_first, pair_off, pair_a, pair_b;
    cl_mem dist, nbr; /* each pair's distance (rows_strut); its neighbours in the list (pairs_neighbours) */
    /* one partial result per work-item of a folding kernel (rows_chain and
     * rows_strut: largest violations; pairs_min_dist: closest pairs; j_rows
     * and cg_r: the CG's p . q and r . r); with the twisted edge block
     * also rzp, the CG's r . z: cg_r's items' shares, then each
     * component's edge rows' (twist_ring_fact) */
    cl_mem part, rzp;
    size_t partcap;
    /* each vertex's active strut entries, per CG solve, compact (CSR by
     * aaoff, aadjn long) with each entry's weight and strut direction
     * (kernels/correct.cl adj_active_*) */
    cl_mem aadj, aadjn, aaoff, acoef, agrad;
    size_t aacap; /* entries aadj, acoef and agrad hold */
    /* The CG's row list (kernels/correct.cl row_of), built per solve: the
     * active strut rows in list order (pcap), block counts for building it. */
    cl_mem act, actc;
    cl_mem sab, sw; /* act_gather: the active struts' vertices, s, t and direction */
    cl_mem blkf;    /* CPU devices: block_flags' byte per four vertices, per solve */
    size_t scap;    /* active struts sab and sw hold */
    int cg_nl; /* rows in the list: 2 nv + active struts */
    int vcap;  /* entries of the CG's vectors y, r, p, q, b, z (by list position) */
    /* rows */
    int rcap;
    /* per row: value, gradient, active flag, closest-point parameters s and
     * t; the CG's vectors (multipliers y, residual r, direction p, q = A p,
     * right-hand side b) */
    cl_mem row_c, row_grad, row_active, row_s, row_t, y, r, p, q, b;
    cl_mem cgq, cdeb, changed; /* curvature rows' second gradient and ebar derivative; a flag */
    cl_mem pdiag, z, edge_off, edge_work, closed; /* preconditioner: diagonal, M^-1 r, edge off-diagonal, work */
    /* The edge block by parallel cyclic reduction (kernels/tridiag.cl) instead
     * of precond_edges' sequential sweep: level-0 set, two alternating sets,
     * the Sherman-Morrison vector; tri_group > 0: one work-group of that size
     * does the whole solve. */
    int tri_pcr, tri_levels, any_closed;
    /* Or (CPU devices) the twisted factorisation of kernels/twisted.cl: two
     * work-groups per component; scratch of 2 ncomp reals for the rows
     * beside the middle row, and 7 ncomp for the blocks' first and last
     * rows and Sherman-Morrison factors (3 ncomp) and the halves' shares of
     * r . z and r . uu (twist_back_rows, twist_sweep_rows). */
    int tri_twist;
    cl_mem tmid, tends;
    /* work-groups per component of the ebar sums (jt_ebar_partial; on CPU
     * devices jt_vertex's and jjt_rows' items, both launched over nv), and
     * their partial sums */
    int ebar_groups;
    cl_mem ebar_part;
    size_t tri_group;
    cl_mem pcr_set0, pcr_p, pcr_q, pcr_uu;
    clb_rows rows;
} cl_state;

/* Strut rows per item when the CG's row list is built (act_count, act_write). */
#define TR_ACT_BLOCK 1024

/* Short spellings for the many argument lists. */
#define A TR_CL_A
#define END TR_CL_END

/* ---- backend_opencl.c: buffers, launches, scalars ---- */

/* Releases *m and sets it to NULL. */
void clb_release(cl_mem *m);
/* (Re)allocates *m with bytes (at least 8) of device memory. */
int clb_buffer(cl_state *s, cl_mem *m, size_t bytes, tr_error *err);
/* Sets kernel id's arguments (TR_CL_A pairs up to TR_CL_END) and launches it:
 * over n indices (a TR_ITEMS kernel, tr_cl_launch_items); in `groups`
 * work-groups of TR_LOCAL_SIZE; as n single-item work-groups; as one
 * work-group of `local` items. */
int clb_run(cl_state *s, int id, size_t n, tr_error *err, ...);
int clb_run_groups(cl_state *s, int id, size_t groups, tr_error *err, ...);
int clb_run_items(cl_state *s, int id, size_t n, tr_error *err, ...);
int clb_run_one_group(cl_state *s, int id, size_t local, tr_error *err, ...);
/* Reads sc[first .. first + count) (blocking). */
int clb_read_scalars(cl_state *s, int first, int count, double *out, tr_error *err);
/* Row buffers for 2 nv + np rows. */
int clb_ensure_rows(cl_state *s, tr_error *err);
/* Room for n partial results (part, and rzp with the twisted edge block). */
int clb_partials(cl_state *s, size_t n, tr_error *err);

/* ---- opencl_contacts.c ---- */

/* sc[SC_STRUT] = the smallest distance of a listed pair (np > 0). */
int clb_closest_pair(cl_state *s, tr_error *err);
/* backend.h find_contacts. */
int clb_find_contacts(void *sp, const tr_contact_params *prm, tr_contact_stats *out,
                      tr_error *err);

/* ---- opencl_correct.c (the pieces the tension step's projection shares) ---- */

/* The rows' values, gradients and activity at the current positions. */
int clb_eval_rows(cl_state *s, const tr_correct_params *prm, tr_error *err);
/* dx <- M^-1 J^T y (and debar). */
int clb_apply_JT(cl_state *s, const tr_correct_params *prm, cl_mem y, tr_error *err);
/* The CG's row list and its per-solve setup. */
int clb_solve_rows(cl_state *s, tr_error *err);
/* Work-items of a j_rows launch over nl rows. */
size_t clb_jrows_units(const cl_state *s, int nl);
/* CG on J M^-1 J^T y = b from the current y, r, p. */
int clb_cg_iterate(cl_state *s, const tr_correct_params *prm, int *iters, tr_error *err);
/* backend.h correct. */
int clb_correct(void *sp, const tr_correct_params *prm, tr_correct_stats *out, tr_error *err);

/* ---- opencl_solver_rows.c ---- */

/* backend.h strut_rows. */
int clb_strut_rows(void *sp, tr_strut_rows *q, tr_error *err);
/* Releases strut_rows' buffers. */
void clb_rows_free(clb_rows *r);

/* ---- opencl_tension.c ---- */

/* backend.h tension_step. */
int clb_tension_step(void *sp, const tr_tension_params *prm, tr_tension_stats *out,
                     tr_error *err);

#endif
