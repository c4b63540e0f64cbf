/* This file contains the layout that the host and the OpenCL kernels share:
 * the work-group size, the constraint record and the slots of the scalar
 * buffer. It is valid C and valid OpenCL C (preprocessor definitions only):
 * the host includes it ("layout.h"; kernels/ is on the include path) and
 * every program gets it as its first source string (tr_cl_build), so the
 * compiler, not a comment, keeps both sides in step. */
#ifndef TR_LAYOUT_H
#define TR_LAYOUT_H

/* Work-group size of every kernel that uses local memory, and the one size
 * all Tightrope kernels are launched with: fixed, because PoCL compiles a
 * kernel anew for every local size it meets. Kernels declare it with
 * reqd_work_group_size, so a launch at another size fails, loudly. */
#define TR_LOCAL_SIZE 64

/* Constraint record, TR_CST_STRIDE reals: unit normal/direction u
 * (TR_CST_U .. + 2), point p (TR_CST_P .. + 2), plane offset d (TR_CST_D),
 * kind (TR_CST_KIND: TR_CST_REC_PLANE, _LINE or _FIXED; these codes are the
 * record's, not curve.h's tr_constraint_kind); vertex i obeys record
 * cidx[i], none where cidx[i] < 0. A record per vertex (8 reals each, read
 * by every per-vertex kernel) made the CG's vectors fall out of the cache:
 * 6.4 MB at N = 10^5, where the index is 0.4 MB; the PoCL step on the loose
 * torus went from 119 to 89 ms without it. */
#define TR_CST_STRIDE 8
#define TR_CST_U 0
#define TR_CST_P 3
#define TR_CST_D 6
#define TR_CST_KIND 7
#define TR_CST_REC_PLANE 1
#define TR_CST_REC_LINE 2
#define TR_CST_REC_FIXED 3

/* Slots of the scalar buffer `sc` (doubles) that the reductions write and
 * the kernels read (kernels/correct.cl), so the host reads nothing inside
 * the CG loop but the done flag. A min/max pair (tr_cl_reduce_minmax)
 * takes two slots: the minimum at the slot named, the maximum at the next.
 * Slots 3 and 5 (once alpha and beta) and 31 are free. */
#define SC_RR 0       /* r . r */
#define SC_RR0 1      /* r . r at the CG's start */
#define SC_PQ 2       /* p . J M^-1 J^T p */
#define SC_RR1 4      /* the next r . z */
#define SC_DONE 6     /* nonzero once the CG has converged */
#define SC_ITERS 7    /* CG iterations */
#define SC_TOL2 8     /* the CG's relative tolerance, squared */
#define SC_VIOL 9     /* min/max pair (9, 10): row violations */
#define SC_MAXDX 11   /* min/max pair (11, 12): vertex displacement |dx| */
#define SC_SCALE 13   /* the step's scale, min(1, max_step / max |dx|) */
#define SC_NACT 14    /* active rows */
#define SC_RZ 15      /* r . z */
#define SC_F2 16      /* tension: |F|^2 */
#define SC_PRED 17    /* tension: predicted decrease */
#define SC_MOVE 18    /* min/max pair (18, 19): tension motion */
#define SC_DEV 20     /* min/max pair (20, 21): edge-length deviation */
#define SC_STRUT 22   /* min/max pair (22, 23): listed pair distance */
#define SC_MINRAD 24  /* min/max pair (24, 25): MinRad */
#define SC_DISP 26    /* min/max pair (26, 27): displacement since the list */
#define SC_SMOOTH2 28 /* tension: |smoothed F|^2 */
#define SC_FREE2 29   /* tension: |projected F|^2 */
#define SC_LISTED 30  /* listed contact pairs */
#define SC_COMP 32    /* the components' lengths from here, one slot each */

#endif
