/* The backend interface: the one narrow seam between the tightening engine
 * (host/engine/engine.c: step control, guards, refinement, certificates) and where
 * the arithmetic runs (host/backend/reference/backend_reference.c, serial C; the OpenCL
 * backend, device memory). The engine knows nothing of the device.
 *
 * The backend owns the state: positions, topology, per-vertex constraints,
 * per-component target edge length ebar_k, the candidate contact list and
 * every per-vertex / per-row work buffer. Per step the host reads back only
 * the small stats structs below; coordinates move only at upload/download
 * (start, checkpoints, refinement, output).
 *
 * Every operation is specified exactly below so that a data-parallel port
 * reproduces the reference to ~1e-12 relative: everything is a per-vertex
 * or per-row gather over fixed-order lists (no scatter, no FP64 atomics,
 * no order-dependent sequential sweeps). The reference sums in the order
 * written here; a port may reorder sums (then agreement is ~1e-14 per op,
 * growing mildly over CG iterations), nothing else.
 *
 * ---------------------------------------------------------------------------
 * NOTATION
 *   Vertices i = 0..nv-1, flat over components (tr_curve layout). comp(i) = k.
 *   next(i): i+1, or start[k] if i is the last vertex of a closed component;
 *            none for the last vertex of an open component.
 *   prev(i): likewise backwards.
 *   Edge a (global index = index of its first vertex) joins a and next(a);
 *   it exists iff next(a) exists. e_a = x[next(a)] - x[a], u_a = e_a/|e_a|.
 *   P_i: per-vertex motion projector from the curve's constraints (curve.h):
 *        none -> I; PLANE (unit normal n) -> I - n n^T; LINE (unit u) -> u u^T;
 *        FIXED -> 0. Every displacement applied to vertex i is P_i(dx_i), and
 *        after every position update a constrained vertex is additionally
 *        snapped with tr_constraint_project (removes drift; exact on planes).
 *   ebar_k: target (common) edge length of component k; part of the state.
 *   rope radius 1, so non-local distances must be >= 2 (strut_dist) and
 *   Rawdon MinRad >= 1 (minrad).
 *
 * CONSTRAINT ROWS (used by correct; "rows" = Lagrange multipliers)
 *   edge row a (every existing edge, always active):
 *       C = |e_a| - ebar_k
 *       dC/dx[a] = -u_a, dC/dx[next a] = +u_a, dC/debar_k = -1
 *   curvature row i ("curvature beam", every vertex with prev and next):
 *   MinRad >= r for equal edges, in turning-angle form (docs/physics.md 1.2(c):
 *   tan(theta/2) <= e/(2r)), scaled by ebar so its gradient is O(1) and
 *   orthogonal to the two edge rows at i (the chord form is nearly their
 *   sum, which made the CG crawl):
 *       p = x[i] - x[prev i], q = x[next i] - x[i],
 *       theta = atan2(|p x q|, p . q), tmax = 2 atan(ebar_k / (2 r))
 *       C = ebar_k (tmax - theta)
 *       A = (cos(theta) p^ - q^) / (|p| sin theta),  B = (cos(theta) q^ - p^) / (|q| sin theta)
 *       (computed as c = p.q/(|p||q|), 1/sin = |p||q|/|p x q|, p^ = p/|p|, q^ = q/|q|)
 *       ga = ebar_k A, gb = ebar_k B:
 *       dC/dx[prev i] = ga, dC/dx[i] = gb - ga, dC/dx[next i] = -gb,
 *       dC/debar_k = (tmax - theta) + ebar_k (1/r) / (1 + ebar_k^2 / (4 r^2))
 *       active iff C < active_curv and |p x q| >= 1e-12 |p| |q| (else ga =
 *       gb = 0 and the row is inactive: a straight vertex is far from the bound).
 *   strut row p (every candidate pair p = (a, b), a < b, in list order):
 *       d, s, t = tr_segment_distance(x[a], x[next a], x[b], x[next b])
 *       (kernels/segment_distance.h, the exact algorithm), n = (P(s) - Q(t)) / d
 *       C = d - strut_dist
 *       dC/dx[a] = (1-s) n, dC/dx[next a] = s n,
 *       dC/dx[b] = -(1-t) n, dC/dx[next b] = -t n
 *       active iff C < active_strut AND the pair is a local minimum of
 *       the distance along both strands: d <= d(a', b) for a' = prev(a),
 *       next(a) and d <= d(a, b') for b' = prev(b), next(b), over those
 *       neighbour edges that exist and share no vertex with the other edge
 *       (distances by tr_segment_distance, same argument order: the a-side
 *       edge first). Neighbouring pairs of one contact carry nearly the same
 *       row; keeping them all makes the system singular in all but name.
 *   Inactive rows have multiplier 0 and contribute exactly nothing.
 *
 * CANDIDATE CONTACTS (find_contacts)
 *   The list holds exactly the edge pairs (a, b), a < b, both existing, with
 *       not excluded(a, b)  and  d = tr_segment_distance(x[a], x[next a],
 *       x[b], x[next b], &s, &t) < cutoff  and, when 0 < tilt < 1,
 *       tr_segment_nearly_normal(the same four points, s, t, d, tilt)
 *   (kernels/segment_distance.h: the connector within tilt of both edges' normal
 *   planes), sorted by (a, b) ascending. Why the tilt: at large N every
 *   vertex has ~cutoff/ebar partners on each strand it runs beside, so the
 *   plain cutoff list grows like N^2 (docs/physics.md 7.4); the struts that
 *   matter are local minima of the distance along both strands, whose
 *   connector lies in the normal slab or wedge of each edge, and those pass
 *   once tilt >= sin(largest turning angle). Pairs a step may slide into
 *   are covered by the engine's allowance and its check after the step. excluded(a, b): same component k and
 *   g < exclude_gap[k], where g = |a - b| on an open component and
 *   min(|a - b|, n_k - |a - b|) on a closed one (n_k = vertices of k);
 *   exclude_gap[k] >= 2 always (edges sharing a vertex are excluded).
 *   Pairs on different components are never excluded. The engine passes
 *   exclude_gap[k] = ceil(pi * 1 / ebar_k) (docs/physics.md 1.2(b)).
 *   Per-vertex gathers over struts visit, for vertex v, the pairs that touch
 *   v (as a, next a, b or next b) in ascending list order (a per-vertex CSR
 *   built from the sorted list); a pair touching v twice contributes both
 *   terms, the a-side first.
 *
 * ---------------------------------------------------------------------------
 * OPERATIONS (all return TR_OK or a negative tr_status with err filled)
 *
 * tension_step(h, max_move, smooth_passes)  -- "force evaluation"
 *   1. Tension force, the negative length gradient: for every vertex i,
 *        F_i = (next(i) exists ? u_i : 0) - (prev(i) exists ? u_prev(i) : 0)
 *   2. Low-pass (lets h exceed the explicit limit ~ebar/2): smooth_passes
 *      Jacobi passes G <- S G starting from G = F, where
 *        (S G)_i = (G_prev + 2 G_i + G_next) / 4 for vertices with both
 *        neighbours, (3 G_i + G_nb) / 4 for an open end (nb its neighbour).
 *   2b. Tangent projection (only if project != NULL; q = *project): evaluate
 *      every row at x as in correct (a); G_i <- P_i G_i; then up to
 *      q.max_newton passes: b = J (G, debar = 0) (the apply-J of correct (b)
 *      with y = 0, reg term 0), solve A y = b by the CG of correct (c);
 *      if another pass is allowed and some active strut/curvature row has
 *      y_r > 0 (the force pulls it apart), deactivate all such rows and
 *      repeat, else stop. Finally G_i <- G_i - dx_i(y) and the ebar
 *      velocity vbar_k = -debar_k(y) (dx, debar as in correct (b)).
 *   3. Motion: dx_i = h P_i(G_i); if |dx_i| > max_move, dx_i *= max_move/|dx_i|
 *      (per vertex). x_i += dx_i, then snap constrained vertices.
 *   With projection, ebar_k += h vbar_k after the motion.
 *   Stats: force2 = sum_i |P_i F_i|^2, predicted = sum_i F_i . dx_i (the
 *   first-order length decrease), max_move = max_i |dx_i|, smooth2 =
 *   sum_i |P_i G_i|^2 before 2b, free2 = sum_i |G_i|^2 after 2b.
 *
 * correct(params)  -- "distance-constraint projection" + "curvature moments",
 *   solved coupled (Gauss-Newton on the active set, CG on J M^-1 J^T):
 *   for it = 0 .. max_newton-1:
 *     a. Evaluate every row (values and gradients at the current x).
 *        viol = max( max_edge |C|, max_active-or-not curv max(0,-C),
 *                    max_strut max(0,-C) ). If it == 0, viol_before = viol.
 *        If viol <= viol_tol: stop (newton_iters = it).
 *     b. Unknowns: dx (3 nv) and debar (ncomp), metric M = diag(1 for x,
 *        ebar_weight * ne_k for debar_k; ne_k = edges of k).
 *        Operator on a row vector y (active rows only, inactive y_r = 0):
 *          g_i     = sum_rows y_r dC_r/dx_i   (a per-vertex gather, order below)
 *          dx_i    = P_i g_i
 *          debar_k = (sum_{rows r of comp k} y_r dC_r/debar_k) / (ebar_weight ne_k)
 *          (A y)_r = (dC_r/dx . dx + reg * y_r) + dC_r/debar . debar   (active r;
 *                    the debar term last: a device may add it after
 *                    the sum over components that debar needs)
 *        Gather order for g_i: edge row prev(i) (+u_prev), edge row i (-u_i),
 *        curvature row prev(i) (-gb_prev: i is its next), curvature row i
 *        (+gb_i, then -ga_i), curvature row next(i) (+ga_next: i is its
 *        prev), then strut rows in list order (CSR above); each term only if
 *        the row exists and is active.
 *        Row vector order (for dot products and debar sums): edge rows by
 *        a, curvature rows by i, strut rows by list index.
 *     c. Solve A y = b by preconditioned CG from y = 0, where b_r = -C_r on
 *        edge rows and b_r = -min(C_r, 0) on active strut and curvature rows
 *        (rows inside the active band are held where they are, violated ones
 *        pushed to 0; this keeps the active set from chattering), b_r = 0 on
 *        inactive rows:
 *          r = b, z = M^-1 r, p = z, rz = r.z, rr0 = r.r, rr = rr0
 *          repeat up to max_cg times, stopping first if rr <= cg_rtol^2 rr0:
 *            q = A p; alpha = rz / (p.q); y += alpha p; r -= alpha q;
 *            rr = r.r; z = M^-1 r; rz' = r.z; p = z + (rz'/rz) p; rz = rz'
 *        (a port may run a fixed count with the stop test turning the
 *        remaining iterations into no-ops, and may run the vector
 *        operations over the active rows only, stored compactly: y, r and
 *        p are exact zeros on the others, and no sum reads their q or z.)
 *        Preconditioner M (set up once per solve from the evaluated rows):
 *          diagonal of every active row: D_r = sum over its vertices v of
 *          |P_v dC_r/dx_v|^2 + (dC_r/debar)^2 / (ebar_weight ne_k) + reg;
 *          edge rows of component k form a tridiagonal block (cyclic when
 *          closed, corner entry between its last and first edge) with
 *          diagonal D_a and off-diagonal between a and next(a) (when that
 *          edge exists) o_a = -(P_v u_a) . u_next(a), v = next(a);
 *          M^-1 on curvature and strut rows: z_r = r_r / D_r (0 inactive);
 *          on the edge block: exact solve (Thomas, factored once per
 *          solve with reciprocal pivots; cyclic via Sherman-Morrison with
 *          gamma = -D_first, as Numerical Recipes 2.7, its correction
 *          vector solved with the factors). Ports may solve the block
 *          exactly in another order (twisted factorisation, PCR): the
 *          rounding differs, the operator does not.
 *          The debar coupling enters M only through D (rank-1 part dropped).
 *     d. Apply: dx, debar from y as in (b); m = max_i |dx_i|; if m > max_step,
 *        scale dx and debar by max_step / m (damped Newton: keeps the
 *        linearisation honest and strands from jumping); x += dx,
 *        ebar += debar; snap.
 *   After the loop (or the stop) evaluate once more: viol_after.
 *   Stats: newton_iters, cg_iters (total), active_rows (last iteration),
 *   viol_before, viol_after.
 *
 * strut_rows(r)  -- the second-order solver's strut rows (host/solver/newton.h)
 *   Reads only what the call brings (the solver's positions and pair list,
 *   not the uploaded curve; the backend's state is only where it computes):
 *   for every pair p, in list order, with vertices quad[4p .. 4p+3] = (a,
 *   next a, b, next b) of the positions x (3 nv):
 *       d_p = tr_strut_row_derivs(x[a], x[next a], x[b], x[next b])
 *             (kernels/segment_distance.h, the one body all backends share)
 *       c_p = d_p - dist,  term_p = tr_phr_ineq_term(c_p, lam[p], mu, &pi_p)
 *   TR_ROWS_VALUE (the line search's trial points): sum = sum0 + term_0 +
 *     term_1 + ... (the reference adds in list order onto sum0, so a caller
 *     that summed its other rows first gets its own serial sum back; a port
 *     sums the terms in its order, then adds sum0), dmin = min_p d_p
 *     (INFINITY for no pairs). Nothing per pair.
 *   TR_ROWS_GRAD / TR_ROWS_HESS (the Newton matrix): d[p] for every pair;
 *     p is selected iff lam[p] - mu c_p > 0 (pi_p > 0) or c_p < band;
 *     sel[p] = its number k among the selected in list order, or -1;
 *     g + 12 k = grad d_p (the four vertices' coordinates in quad order) and,
 *     for TR_ROWS_HESS, h + 144 k = its Hessian, row major (the body above,
 *     so the reference's blocks are the serial solver's to the bit);
 *     nsel = the number selected. sum and dmin as in VALUE, summed as
 *     there: a solver compares the value at its point with those at the
 *     line search's trial points, and at the bottom of a solve the
 *     difference is rounding, so both must come from the same sum (a
 *     device's order for one and the serial order for the other stalled
 *     the PoCL solve at N = 2400). The selection keeps the output to the rows the Newton
 *     matrix takes (a tenth of the list on a tight knot) and a port decides
 *     it itself, so it needs no second launch; where its rounding puts a
 *     pair on the other side of the test, the caller computes that block.
 *   d, sel, g and h point into the backend's memory, valid until its next
 *   strut_rows or destroy.
 *
 * measure()  -- the reductions
 *   length = sum over edges |e_a| (per component into comp_length[k] when
 *   given, ebar_k into comp_ebar[k]); edge_dev = max_a | |e_a| - ebar_k | / ebar_k;
 *   min_strut = min over the candidate list of the segment distance (INFINITY
 *   if the list is empty); min_minrad = min over vertices with prev and next
 *   of Rawdon's MinRad min(|a|,|b|) (|a||b| + a.b) / (2 |a x b|), a = e_prev,
 *   b = e_i, skipping |a x b| == 0 (INFINITY if all skipped);
 *   max_disp = max_i |x_i - saved_i| (0 if never saved).
 *
 * save() / restore(): copy x and ebar to / from a saved slot (device-side);
 *   used by the engine's step control to reject a step.
 * upload(x, ebar): replace positions (same topology); ebar NULL -> ebar_k =
 *   mean edge length of component k. The contact list is emptied.
 * download(x, ebar): positions (3 nv) and, if ebar != NULL, ebar (ncomp).
 */
#ifndef TR_BACKEND_H
#define TR_BACKEND_H

#include <stddef.h>

#include "curve/curve.h"
#include "util/error.h"

typedef struct tr_contact_params {
    double cutoff;          /* list pairs with segment distance < cutoff (2 + skin) */
    double tilt;            /* and, if 0 < tilt < 1, nearly normal to both edges
                               (see CANDIDATE CONTACTS); 0 or >= 1: no such test */
    const int *exclude_gap; /* ncomp entries, each >= 2 */
} tr_contact_params;

typedef struct tr_contact_stats {
    size_t pairs;    /* number of candidate pairs listed */
    double min_dist; /* smallest segment distance among them (INFINITY if none) */
} tr_contact_stats;

struct tr_correct_params;

typedef struct tr_tension_params {
    double h;          /* step length per unit force */
    double max_move;   /* per-vertex cap on |dx| */
    int smooth_passes; /* low-pass passes on the force, >= 0 */
    /* NULL: move along the smoothed force. Else project it first onto the
     * tangent cone of the rows in the active band (see tension_step 2b);
     * uses max_newton (= solve passes), max_cg, cg_rtol, the bands,
     * strut_dist, minrad, ebar_weight, reg. */
    const struct tr_correct_params *project;
} tr_tension_params;

typedef struct tr_tension_stats {
    double force2;    /* sum |P F|^2 */
    double predicted; /* sum F . dx: first-order length decrease */
    double max_move;  /* max |dx| */
    double smooth2;   /* sum |P G|^2 after smoothing, before projection */
    double free2;     /* sum |G|^2 after projection (= smooth2 without): the
                         resolved force; sqrt(free2/smooth2) is the KKT residual */
} tr_tension_stats;

typedef struct tr_correct_params {
    int max_newton;      /* Gauss-Newton iterations */
    int max_cg;          /* CG iterations per Newton iteration */
    double cg_rtol;      /* CG stop: |r| <= cg_rtol |b| */
    double viol_tol;     /* stop Newton when the worst violation is below this */
    double active_strut; /* strut row active iff d - strut_dist < active_strut */
    double active_curv;  /* curvature row active iff C < active_curv */
    double strut_dist;   /* 2 (rope diameter) */
    double minrad;       /* 1 (rope radius; MinRad bound) */
    double ebar_weight;  /* metric weight of debar_k per edge (>0) */
    double reg;          /* Tikhonov term on the rows (> 0, tiny) */
    double max_step;     /* cap on max_i |dx_i| per Newton iteration */
} tr_correct_params;

typedef struct tr_correct_stats {
    int newton_iters;
    int cg_iters;
    size_t active_rows;
    double viol_before;
    double viol_after;
} tr_correct_stats;

typedef struct tr_measure {
    double length;
    double edge_dev;   /* relative */
    double min_strut;  /* over the candidate list */
    double min_minrad; /* Rawdon MinRad, polygon vertices */
    double max_disp;   /* since save() */
} tr_measure;

/* The second-order solver's strut rows (strut_rows above). */
enum { TR_ROWS_VALUE = 0, TR_ROWS_GRAD = 1, TR_ROWS_HESS = 2 };
typedef struct tr_strut_rows {
    /* in */
    int mode;           /* TR_ROWS_VALUE, _GRAD or _HESS */
    size_t nv, np;      /* positions, pairs */
    const double *x;    /* 3 nv */
    const size_t *quad; /* 4 np vertex indices: a, next a, b, next b */
    const double *lam;  /* np multipliers */
    double mu, dist;    /* penalty; the bound (2) */
    double band;        /* GRAD / HESS: also select rows with c < band (-INFINITY: none) */
    double sum0;        /* VALUE: the sum starts here */
    /* out */
    double sum, dmin;   /* VALUE */
    size_t nsel;        /* GRAD / HESS */
    const double *d, *g, *h;
    const int *sel;
} tr_strut_rows;

/* Device time per kernel function of a profiled backend (profile). */
#define TR_BACKEND_PROFILE_MAX 128
typedef struct tr_kernel_time {
    char kernel[48]; /* kernel function name */
    long launches;
    double seconds;  /* summed device execution time (profiling events) */
} tr_kernel_time;

typedef struct tr_backend_ops {
    const char *name; /* "reference", "opencl" */
    /* 1 for a backend that runs serially on the host with no cost per
     * launch (the reference): the engine keeps it at coarse levels instead
     * of moving them to the reference (engine.h device_min_n) */
    int serial;
    /* Releases everything; state may be NULL. */
    void (*destroy)(void *state);
    int (*upload)(void *state, const double *x, const double *ebar, tr_error *err);
    int (*download)(void *state, double *x, double *ebar, tr_error *err);
    int (*save)(void *state, tr_error *err);
    int (*restore)(void *state, tr_error *err);
    /* neighbour search */
    int (*find_contacts)(void *state, const tr_contact_params *p, tr_contact_stats *out,
                         tr_error *err);
    /* force evaluation and motion */
    int (*tension_step)(void *state, const tr_tension_params *p, tr_tension_stats *out,
                        tr_error *err);
    /* coupled edge / strut / curvature constraint correction */
    int (*correct)(void *state, const tr_correct_params *p, tr_correct_stats *out, tr_error *err);
    /* reductions; comp_length, comp_ebar may be NULL (else ncomp entries) */
    int (*measure)(void *state, tr_measure *out, double *comp_length, double *comp_ebar,
                   tr_error *err);
    /* the second-order solver's strut rows (tr_strut_rows); may be NULL
     * (the solver then evaluates them itself) */
    int (*strut_rows)(void *state, tr_strut_rows *r, tr_error *err);
    /* What the description does not say and a benchmark should: how this
     * instance solves (e.g. "edge block twisted"); writes "" when nothing. */
    void (*describe)(void *state, char *out, size_t size);
    /* Per-kernel device times since open, for a backend opened with
     * profiling (tr_backend_open_device); at most max entries; returns their
     * number, 0 for a backend that does not profile. May be NULL. */
    int (*profile)(void *state, tr_kernel_time *out, int max);
} tr_backend_ops;

/* An open backend: its operations, its opaque state, and what it is. */
typedef struct tr_backend {
    const tr_backend_ops *ops;
    void *state;
    char description[256]; /* e.g. "serial reference" or "OpenCL: pthread-... (PoCL)" */
    char warning[256];     /* non-empty if "auto" fell back; the CLI prints it */
} tr_backend;

/* Opens a backend for the curve (copies topology, constraints and positions;
 * ebar = mean edge length per component). spec: "reference", "auto", or a
 * device selector a registered backend understands ("opencl", "P:D",
 * a name substring); NULL or "" means $TIGHTROPE_DEVICE or else "auto".
 * "auto" tries the accelerated backends in registry order and falls back to
 * the reference, recording why in out->warning.
 * The registry is the table in host/backend/backend.c: one line per backend. */
int tr_backend_open(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err);
void tr_backend_close(tr_backend *b);

/* Opens exactly the device spec names, never falling back: the reference
 * for its names (util/device_spec.h), else the first accelerated backend
 * that takes the spec; with profiling, one that records per-kernel times
 * (profile), synchronising after every launch (so time whole steps without
 * it). For bench, which measures the device asked for. */
int tr_backend_open_device(const char *spec, const tr_curve *c, int profiling, tr_backend *out,
                           tr_error *err);

/* b->ops->describe and b->ops->profile, or "" and 0 where the backend has none. */
void tr_backend_describe(const tr_backend *b, char *out, size_t size);
int tr_backend_profile(const tr_backend *b, tr_kernel_time *out, int max);

/* One device a spec can name, as `tightrope devices` lists it. */
typedef struct tr_device_desc {
    char id[32];               /* "P:D" */
    char platform[128];
    char platform_vendor[128]; /* "The pocl project", "NVIDIA Corporation" */
    char name[256];
    char vendor[128];
    char version[128];
    char driver[64];
    const char *type;          /* "gpu", "accelerator", "cpu" or "other" */
    unsigned compute_units, clock_mhz;
    unsigned long long global_mem; /* bytes */
    int fp64, usable;
    char reason[512];          /* why unusable; "" when usable */
} tr_device_desc;

typedef struct tr_device_list {
    tr_device_desc *dev; /* the accelerated backends' devices (not the reference) */
    int n;
    char none_reason[256];  /* when n == 0: why there are none */
    char default_spec[128]; /* what no --device means: $TIGHTROPE_DEVICE or "auto" */
    int picked;             /* the default spec resolves ... */
    char selected[32];      /* ... to this id ("reference" or "P:D") */
    char warning[512];      /* why it fell back to the reference ("" if not) */
    char pick_error[1024];  /* why it does not resolve (when !picked) */
} tr_device_list;

/* Every device and what the default spec picks. */
int tr_backend_list_devices(tr_device_list *out, tr_error *err);
void tr_backend_device_list_free(tr_device_list *l);

/* Whether spec names a usable device (the reference, or one that
 * tr_backend_open_device could open), without opening it: TR_EINVAL for a
 * spec that names nothing, another status for a device that cannot be used. */
int tr_backend_check_spec(const char *spec, tr_error *err);

/* Per-backend constructors the registry calls. Each returns TR_EUNSUPPORTED
 * when spec is not for it (so the next one may try), another status when it
 * is but fails. */
int tr_backend_reference_open(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err);

#endif
