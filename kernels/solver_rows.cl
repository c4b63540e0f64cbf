/* The second-order solver's strut rows (backend.h strut_rows; host/solver/newton.h):
 * per pair of the solver's list, the exact segment distance and, for the
 * pairs the Newton matrix takes, its gradient and 12 x 12 Hessian block.
 * Every kernel is a per-pair gather over the list (TR_ITEMS): each pair's
 * outputs are written by the one item that owns it, at places fixed by the
 * list order (the blocks at the exclusive scan of the selection flags), so
 * nothing is scattered and nothing needs atomics. The arithmetic is
 * kernels/segment_distance.h's tr_strut_row_derivs and tr_phr_ineq_term,
 * which the reference backend and the solver's serial path run too.
 * quad holds the pair's four vertices (a, next a, b, next b). */

/* The pair's four vertices' coordinates p0 p1 q0 q1 into x12 (private). */
inline void sr_gather(__global const real *x, __global const int *quad, int p, real *x12)
{
    for (int j = 0; j < 4; j++) {
        int v = quad[4 * p + j];
        x12[3 * j] = x[3 * v];
        x12[3 * j + 1] = x[3 * v + 1];
        x12[3 * j + 2] = x[3 * v + 2];
    }
}

/* The line search's value: per work-item the sum of its pairs' PHR terms
 * (in list order along its run) and their smallest distance (INFINITY for
 * none), folded by the reductions (tr_cl_reduce_sum, _minmax). */
__kernel void strut_rows_value(__global const real *x, __global const int *quad,
                               __global const real *lam, const int np, const real mu,
                               const real dist, __global real *part_sum, __global real *part_min)
{
    real f = 0.0, m = INFINITY;
    TR_ITEMS(p, np) {
        real x12[12], pi;
        sr_gather(x, quad, p, x12);
        real d = tr_strut_row_derivs(x12, 0, 0, 0, 0);
        m = fmin(m, d);
        f += tr_phr_ineq_term(d - dist, lam[p], mu, &pi);
    }
    part_sum[get_global_id(0)] = f;
    part_min[get_global_id(0)] = m;
}

/* Every pair's distance, and whether the Newton matrix takes its block
 * (pi > 0, or within band of the bound): flag[p] 1 or 0, scanned into the
 * blocks' places. And the partials of strut_rows_value, summed in the same
 * order over the same items (the launch depends on np only), so that the
 * value here and at the line search's points is the same sum: the solver
 * compares them to rounding at the bottom of a solve. */
__kernel void strut_rows_select(__global const real *x, __global const int *quad,
                                __global const real *lam, const int np, const real mu,
                                const real dist, const real band, __global real *dout,
                                __global int *flag, __global real *part_sum,
                                __global real *part_min)
{
    real f = 0.0, m = INFINITY;
    TR_ITEMS(p, np) {
        real x12[12], pi;
        sr_gather(x, quad, p, x12);
        real d = tr_strut_row_derivs(x12, 0, 0, 0, 0);
        dout[p] = d;
        m = fmin(m, d);
        f += tr_phr_ineq_term(d - dist, lam[p], mu, &pi);
        flag[p] = pi > 0.0 || d - dist < band;
    }
    part_sum[get_global_id(0)] = f;
    part_min[get_global_id(0)] = m;
}

/* The selected pairs' blocks: pair p, selected when off[p + 1] > off[p],
 * writes its gradient at g + 12 off[p] and (hess) its Hessian at
 * h + 144 off[p], row major. */
__kernel void strut_rows_blocks(__global const real *x, __global const int *quad, const int np,
                                __global const int *off, const int hess, __global real *g,
                                __global real *h)
{
    TR_ITEMS(p, np) {
        int k = off[p];
        if (off[p + 1] == k)
            continue;
        real x12[12];
        sr_gather(x, quad, p, x12);
        tr_strut_row_derivs(x12, g + 12 * (long)k, hess ? h + 144 * (long)k : 0, 1, hess);
    }
}
