/* This file contains the serial reference backend's state and the helpers
 * its files share (internal to host/backend/reference/): backend_reference.c
 * (open, upload, download, save, restore, measure), reference_contacts.c
 * (find_contacts), reference_tension.c (tension_step) and
 * reference_correct.c (correct), one file per operation of backend.h, as in
 * the OpenCL backend and in kernels/. */
#ifndef TR_REFERENCE_STATE_H
#define TR_REFERENCE_STATE_H

#include <stddef.h>

#include "backend/backend.h"
#include "geometry/neighbour_search.h"

enum { PJ_NONE = 0, PJ_PLANE, PJ_LINE, PJ_FIXED };

typedef struct ref_state {
    size_t nv;
    int ncomp;
    size_t *start;
    unsigned char *closed;
    int *comp;
    ptrdiff_t *next, *prev; /* -1: none */
    size_t *ne;             /* edges per component */
    double *x, *xs;
    double *ebar, *ebar_s;
    int saved;
    /* per-vertex constraints */
    unsigned char *pj;
    double *pu; /* 3 per vertex: plane normal or line direction */
    int *vcst;
    tr_constraint *cst;
    /* candidate contacts, sorted (a, b) */
    size_t np, pcap;
    size_t *pa, *pb;
    size_t *adj_start, *adj; /* CSR: adj holds 4*pair + slot */
    size_t adj_cap;
    /* work */
    double *F, *G, *H;  /* 3 nv each */
    double *dx;         /* 3 nv */
    double *debar;      /* ncomp */
    /* rows: [0,nv) edges, [nv,2nv) curvature, [2nv, 2nv+np) struts */
    size_t rcap;
    double *rC, *rgrad; /* value; 3-vector (u, w^, n) */
    double *rs, *rt;    /* strut closest-point parameters (np) */
    unsigned char *ract;
    double *y, *r, *p, *q, *b;
    double *cgq, *cdeb; /* curvature rows: second gradient vector, dC/debar */
    double *pd, *z;     /* preconditioner diagonal, preconditioned residual (rows) */
    double *po;         /* edge-row off-diagonal (nv) */
    /* the edge block factored once per solve (precond_factor): Thomas
     * multipliers, reciprocal pivots, Sherman-Morrison vector (nv each) */
    double *tri_w, *tri_ib, *tri_uu;
    /* inside cg_solve: the active strut rows (ascending) and the per-vertex
     * strut adjacency restricted to them, so that CG iterations skip the
     * many inactive rows of a long list (they hold exact zeros: skipping
     * them changes no sum) */
    int compact;
    size_t nact, *act, *aadj_start, *aadj, act_cap, aadj_cap;
    /* neighbour search: a tree over the edges of a curve that views x */
    tr_curve view;
    tr_nsearch ns;
    int ns_built;
    /* strut_rows' output (reference_solver_rows.c): per pair its distance
     * and block number (room for sr_np), the selected rows' gradients and
     * Hessians (room for sr_gcap and sr_hcap blocks) */
    double *sr_d, *sr_g, *sr_h;
    int *sr_sel;
    size_t sr_np, sr_gcap, sr_hcap;
} ref_state;

/* Puts a constrained vertex i back on its set (tr_constraint_project). */
void rb_snap(const ref_state *s, size_t i);
/* v <- P_i v, the motion projector of backend.h. */
void rb_project_motion(const ref_state *s, size_t i, double *v);
/* Row arrays for 2 nv + np rows. */
int rb_ensure_rows(ref_state *s, tr_error *err);
/* Evaluates every row at the current x; returns the worst violation. */
double rb_eval_rows(ref_state *s, const tr_correct_params *prm);
/* y (rows) -> dx (per vertex, projected), debar (per component). */
void rb_apply_JT(ref_state *s, const tr_correct_params *prm, const double *y);
/* out_r = grad C_r . (dx, debar) + reg y_r on active rows, 0 elsewhere. */
void rb_apply_J(ref_state *s, const tr_correct_params *prm, const double *y, double *out);
/* Solves A y = b (rows, s->b) by preconditioned CG from y = 0 as backend.h
 * specifies; returns the iterations taken. */
int rb_cg_solve(ref_state *s, const tr_correct_params *prm);

/* backend.h's operations, one file each. */
int rb_find_contacts(void *sp, const tr_contact_params *prm, tr_contact_stats *out, tr_error *err);
int rb_tension_step(void *sp, const tr_tension_params *prm, tr_tension_stats *out, tr_error *err);
int rb_correct(void *sp, const tr_correct_params *prm, tr_correct_stats *out, tr_error *err);
int rb_strut_rows(void *sp, tr_strut_rows *r, tr_error *err);

#endif
