/* This file contains the CPU devices' edge-block solve (TIGHTROPE_CL_TRIDIAG=twisted,
 * the default there; tridiag.cl serves GPUs and accelerators). The edge block
 * of the CG preconditioner (backend.h correct (c)) on CPU
 * devices: a twisted factorisation ("burn at both ends"; van der Vorst 1987,
 * Parlett & Dhillon 2000). Thomas's sweep is one dependent chain per
 * component, so precond_edges runs on one core while the others idle; here
 * each component's chain is cut at its middle row m, rows 0 .. m-1 are
 * eliminated downwards and rows m+1 .. n-1 upwards by two work-groups at
 * once, row m is solved from both, and both halves substitute outwards.
 * Same operation count as Thomas; the rounding differs, as PCR's does (the
 * tests hold it to PCR's tolerance against the reference).
 *
 * The block of component k is rows st .. st+n-1 (st = start[k], n = ne[k]),
 * symmetric: diagonal D (pd), off-diagonal o_j = po[st + j] between rows j
 * and j + 1. Closed components use the reference's Sherman-Morrison split
 * (Numerical Recipes 2.7, gamma = -D_first): the factors are of the block
 * with modified first and last diagonal entries, and the correction vector
 * uu is solved once per setup.
 *
 * tw holds 4 nv reals, indexed by row: g (the multiplier of the outward
 * neighbour in the back substitution: o_j / p_j above m, o_{j-1} / p_j
 * below), ip (reciprocal pivots; at row m the middle pivot's), uu, and c
 * (the multiplier of the inward neighbour in the sweep: o_{j-1} / p_j above
 * m, o_j / p_j below).
 *
 * The sweep and the back substitution are each one dependent chain per
 * half, so their speed is the chain's latency per row. Written as
 * y_j = fma(-c_j, y_{j-1}, rhs_j ip_j) and x_j = fma(-g_j, x_{j+1}, y_j),
 * the chain is one fused multiply-add (4 cycles on the CPUs here) instead
 * of a multiply, a subtraction and a multiply: on the loose torus at
 * N = 10^5 (PoCL) twist_sweep_rows fell from 7.0 to 3.8-4.4 ms per step and
 * twist_back_rows from 5.2 to 3.2-4.1. Every GPU with FP64 and every x86
 * CPU since 2013 has FMA units; elsewhere fma() is emulated, slow but
 * right. This is a preconditioner: its rounding only steers the CG, whose
 * result the tests hold to the reference within PCR's tolerance. */

/* The middle row: n / 2 when both halves have rows, else the last row
 * (short blocks are plain Thomas in the upper half). */
inline int twist_row(int n) { return n >= 4 ? n / 2 : n - 1; }

/* Factors of component k's block with first and last diagonal entries
 * b_first, b_last: the upper half downwards (side 0) or the lower half
 * upwards (side 1). */
inline void twist_factor_half(__global const real *po, __global const real *d, real b_first,
                              real b_last, int st, int n, int side, __global real *g,
                              __global real *ip, __global real *c)
{
    int m = twist_row(n);
    if (side == 0) {
        for (int j = 0; j < m; j++) {
            real bj = j == 0 ? b_first : d[j];
            real p = j == 0 ? bj : bj - po[st + j - 1] * g[j - 1];
            ip[j] = 1.0 / p;
            g[j] = po[st + j] * ip[j];
            c[j] = j == 0 ? 0.0 : po[st + j - 1] * ip[j];
        }
    } else {
        for (int j = n - 1; j > m; j--) {
            real bj = j == n - 1 ? b_last : d[j];
            real p = j == n - 1 ? bj : bj - po[st + j] * g[j + 1];
            ip[j] = 1.0 / p;
            g[j] = po[st + j - 1] * ip[j];
            c[j] = j == n - 1 ? 0.0 : po[st + j] * ip[j];
        }
    }
}

/* The middle pivot's reciprocal from both halves' factors. */
inline real twist_middle(__global const real *po, __global const real *d, real b_first,
                         real b_last, int st, int n, __global const real *g)
{
    int m = twist_row(n);
    real p = m == 0 ? b_first : m == n - 1 ? b_last : d[m];
    if (m > 0)
        p -= po[st + m - 1] * g[m - 1];
    if (m + 1 < n)
        p -= po[st + m] * g[m + 1];
    return 1.0 / p;
}

/* Elimination sweep of rhs into y (upper half: y_j = (rhs_j - o_{j-1}
 * y_{j-1}) ip_j; lower half: y_j = (rhs_j - o_j y_{j+1}) ip_j, as
 * rhs_j ip_j - c_j y_{j-1} and rhs_j ip_j - c_j y_{j+1}), then the middle
 * row's solution once both are known (twist_solve_mid). Returns sum0 plus
 * rhs . w over the swept rows (the CG's r . uu, twist_sweep_rows: the sum's
 * loads and adds fit in the chain's latency). */
inline real twist_sweep(int n, int side, __global const real *ip, __global const real *c,
                        __global const real *rhs, __global real *y, __global const real *w,
                        real sum0)
{
    /* the chain's last value stays in a register, and rhs_j is loaded once
     * before y_j is stored: y may alias rhs (uu is swept in place), so the
     * compiler would otherwise reload them from memory behind the store,
     * one store-to-load latency per row */
    int m = twist_row(n);
    int first = side == 0 ? 0 : n - 1, stop = m, step = side == 0 ? 1 : -1;
    if (first == stop)
        return sum0;
    real a = rhs[first], sum = sum0 + a * w[first];
    real prev = y[first] = a * ip[first];
    for (int j = first + step; j != stop; j += step) {
        a = rhs[j];
        sum += a * w[j];
        prev = y[j] = fma(-c[j], prev, a * ip[j]);
    }
    return sum;
}

/* x_m from the swept sides' neighbours of row m (ym1 = y_{m-1}, yp1 =
 * y_{m+1}, 0 where absent). */
inline real twist_solve_mid(__global const real *po, int st, int n, __global const real *ip,
                            real rm, real ym1, real yp1)
{
    int m = twist_row(n);
    real v = rm;
    if (m > 0)
        v -= po[st + m - 1] * ym1;
    if (m + 1 < n)
        v -= po[st + m] * yp1;
    return v * ip[m];
}

/* Back substitution of one half outwards from the middle row's xm (y[m]
 * itself is not read: the other side's items may be writing it). Returns
 * sum0 plus w . x over the half's rows (the CG's r . z, twist_back_rows;
 * w_j is loaded before x_j is stored, as in twist_sweep). */
inline real twist_back(int n, int side, __global const real *g, real xm, __global real *y,
                       __global const real *w, real sum0)
{
    int m = twist_row(n);
    real prev = xm, sum = sum0;
    if (side == 0) {
        for (int j = m - 1; j >= 0; j--) {
            real wj = w[j];
            prev = y[j] = fma(-g[j], prev, y[j]);
            sum += wj * prev;
        }
    } else {
        for (int j = m + 1; j < n; j++) {
            real wj = w[j];
            prev = y[j] = fma(-g[j], prev, y[j]);
            sum += wj * prev;
        }
    }
    return sum;
}

/* The swept value beside row m on a half's side (0 where that half has no
 * rows): what the middle row's solve needs from it. */
inline real twist_beside(int n, int side, __global const real *y)
{
    int m = twist_row(n);
    return side == 0 ? (m > 0 ? y[m - 1] : 0.0) : (m + 1 < n ? y[m + 1] : 0.0);
}

/* Item 2k + side of the per-half kernels: its component k and side, and
 * the block's first row and size; 0 when there is nothing to solve. */
inline int twist_item(int ncomp, __global const int *start, __global const int *ne, int *k,
                      int *side, int *st, int *n)
{
    *k = get_global_id(0) / 2;
    *side = get_global_id(0) % 2;
    if (*k >= ncomp)
        return 0;
    *st = start[*k];
    *n = ne[*k];
    return *n > 0;
}

/* The diagonal of the factored block's first and last rows (closed blocks:
 * Sherman-Morrison's modification). */
inline void twist_ends(__global const real *pd, __global const real *po, int st, int n, int cyc,
                       real *b_first, real *b_last)
{
    __global const real *d = pd + st;
    *b_first = d[0];
    *b_last = d[n - 1];
    if (cyc) {
        real alpha = po[st + n - 1], gamma = -d[0];
        *b_first = d[0] - gamma;
        *b_last = d[n - 1] - alpha * alpha / gamma;
    }
}

/* Setup, step 1 (items 2k + side, one per work-group): each half's factors,
 * and for closed blocks its half of uu's sweep (right-hand side gamma at the
 * first row, alpha at the last). uu is zero on every other edge row, open
 * blocks' and dead ones (an open rope's last vertex), so that twist_ring_fix
 * needs no branch; the dead rows of z are zeroed here, once per solve,
 * since no sweep writes them. mid: 2 ncomp reals of scratch. */
__kernel void twist_factor(__global const real *pd, __global const real *po,
                           __global const int *start, __global const int *ne,
                           __global const int *closed, const int ncomp, const int nv,
                           __global real *tw, __global real *mid, __global real *z)
{
    int k = get_global_id(0) / 2, side = get_global_id(0) % 2;
    if (k >= ncomp)
        return;
    int st = start[k], n = ne[k], cyc = closed[k] && n >= 3, m = twist_row(n);
    __global real *g = tw + st, *ip = tw + nv + st, *uu = tw + 2 * nv + st, *c = tw + 3 * nv + st;
    if (side == 1)
        for (int j = n; j < start[k + 1] - st; j++) {
            uu[j] = 0.0;
            z[st + j] = 0.0;
        }
    if (n == 0)
        return;
    for (int j = side == 0 ? 0 : m + 1; j < (side == 0 ? m : n); j++)
        uu[j] = 0.0;
    real bf, bl;
    twist_ends(pd, po, st, n, cyc, &bf, &bl);
    twist_factor_half(po, pd + st, bf, bl, st, n, side, g, ip, c);
    if (!cyc)
        return;
    if (side == 0)
        uu[0] = -pd[st];
    else
        uu[n - 1] = po[st + n - 1];
    /* the right-hand side is zero but at the two ends: sweep it in place */
    twist_sweep(n, side, ip, c, uu, uu, uu, 0.0);
    mid[2 * k + side] = twist_beside(n, side, uu);
}

/* Setup, step 2 (one item per component): the middle pivot, and uu's
 * middle row and back substitution (short: run by one item, once per
 * solve). */
__kernel void twist_factor_mid(__global const real *pd, __global const real *po,
                               __global const int *start, __global const int *ne,
                               __global const int *closed, const int ncomp, const int nv,
                               __global real *tw, __global const real *mid)
{
    int k = get_global_id(0);
    if (k >= ncomp)
        return;
    int st = start[k], n = ne[k], cyc = closed[k] && n >= 3;
    if (n == 0)
        return;
    __global real *g = tw + st, *ip = tw + nv + st, *uu = tw + 2 * nv + st;
    real bf, bl;
    twist_ends(pd, po, st, n, cyc, &bf, &bl);
    int m = twist_row(n);
    ip[m] = twist_middle(po, pd + st, bf, bl, st, n, g);
    uu[m] = 0.0;
    if (!cyc)
        return;
    real rm = m == 0 ? -pd[st] : m == n - 1 ? po[st + n - 1] : 0.0;
    real um = twist_solve_mid(po, st, n, ip, rm, mid[2 * k], mid[2 * k + 1]);
    uu[m] = um;
    twist_back(n, 0, g, um, uu, uu, 0.0);
    twist_back(n, 1, g, um, uu, uu, 0.0);
}

/* Apply, step 1 (items 2k + side): sweep r into z; each half leaves its
 * neighbour of row m in mid (the other side may already be overwriting z
 * in step 2), and its share of r . uu (side 0 with row m) in
 * ends[5 ncomp + 2k + side] for twist_ring_fact's r . z (the sweep is one
 * dependent chain: the sum's loads and adds fit in its latency). */
__kernel void twist_sweep_rows(__global const real *r, __global const real *po,
                               __global const int *start, __global const int *ne,
                               const int ncomp, const int nv, __global const real *tw,
                               __global real *mid, __global real *ends, __global real *z)
{
    int k, side, st, n;
    if (!twist_item(ncomp, start, ne, &k, &side, &st, &n)) {
        if (k < ncomp)
            ends[5 * ncomp + 2 * k + side] = 0.0;
        return;
    }
    __global const real *rhs = r + st, *uu = tw + 2 * nv + st;
    __global real *y = z + st;
    int m = twist_row(n);
    real ru = twist_sweep(n, side, tw + nv + st, tw + 3 * nv + st, rhs, y, uu,
                          side == 0 ? rhs[m] * uu[m] : 0.0);
    mid[2 * k + side] = twist_beside(n, side, y);
    ends[5 * ncomp + 2 * k + side] = ru;
}

/* Apply, step 2 (items 2k + side): x_m (each half computes it), then the
 * side's back substitution; the half that holds row 0 or row n-1 leaves it
 * in ends for step 3's Sherman-Morrison factor, and its share of r . z
 * (side 0 with row m) in ends[3 ncomp + 2k + side]. */
__kernel void twist_back_rows(__global const real *r, __global const real *po,
                              __global const int *start, __global const int *ne,
                              const int ncomp, const int nv, __global const real *tw,
                              __global const real *mid, __global real *ends, __global real *z)
{
    int k, side, st, n;
    if (!twist_item(ncomp, start, ne, &k, &side, &st, &n)) {
        if (k < ncomp)
            ends[3 * ncomp + 2 * k + side] = 0.0;
        return;
    }
    int m = twist_row(n);
    __global real *x = z + st;
    __global const real *g = tw + st, *rr = r + st;
    real xm = twist_solve_mid(po, st, n, tw + nv + st, r[st + m], mid[2 * k], mid[2 * k + 1]);
    if (side == 0)
        x[m] = xm;
    real rz = twist_back(n, side, g, xm, x, rr, side == 0 ? rr[m] * xm : 0.0);
    /* the sweep of a half without rows leaves x_m as its end */
    ends[2 * k + side] = side == 0 ? (m > 0 ? x[0] : xm) : (m + 1 < n ? x[n - 1] : xm);
    ends[3 * ncomp + 2 * k + side] = rz;
}

/* Apply, step 3 (one item per component): Sherman-Morrison's factor of
 * closed blocks from their first and last rows, 0 for the others; and the
 * block's share of r . z as it is once step 4 has run, r . z - fact r . uu
 * from steps 1 and 2's sums, into rz[rz_off + k] (the CG loop skips step 4:
 * correct.cl cg_p_ring applies it where it reads z). */
__kernel void twist_ring_fact(__global const real *pd, __global const real *po,
                              __global const int *start, __global const int *ne,
                              __global const int *closed, const int ncomp, const int nv,
                              __global const real *tw, __global real *ends, __global real *rz,
                              const int rz_off)
{
    int k = get_global_id(0);
    if (k >= ncomp)
        return;
    int st = start[k], n = ne[k];
    real fact = 0.0;
    if (closed[k] && n >= 3) {
        __global const real *uu = tw + 2 * nv + st;
        real beta = po[st + n - 1], gamma = -pd[st];
        fact = (ends[2 * k] + beta * ends[2 * k + 1] / gamma) /
               (1.0 + uu[0] + beta * uu[n - 1] / gamma);
    }
    ends[2 * ncomp + k] = fact;
    rz[rz_off + k] = (ends[3 * ncomp + 2 * k] + ends[3 * ncomp + 2 * k + 1]) -
                     fact * (ends[5 * ncomp + 2 * k] + ends[5 * ncomp + 2 * k + 1]);
}

/* Apply, step 4 (one item per edge row, only when some block is closed):
 * z -= fact uu, exact no-op on rows whose uu is zero. The curvature and
 * strut rows are precond_diag's (cg_r's inside the CG loop). */
__kernel void twist_ring_fix(__global const int *comp, const int ncomp, const int nv,
                             __global const real *tw, __global const real *ends,
                             __global real *z)
{
    TR_ITEMS(q, nv)
        z[q] -= ends[2 * ncomp + comp[q]] * tw[2 * nv + q];
}

