/* This file contains the GPU and accelerator edge-block solve (TIGHTROPE_CL_TRIDIAG=pcr,
 * the default there; twisted.cl serves CPU devices). The edge block of the CG
 * preconditioner (backend.h correct (c)) solved in
 * parallel: parallel cyclic reduction (PCR, Hockney & Jesshope; Zhang, Cohen &
 * Owens 2010 for GPUs) instead of the sequential Thomas sweep of
 * precond_edges, which runs on one work-item and, on a GPU, costs more than
 * the rest of the step together (0.55 ms per solve at N = 10^3, 74 ms at
 * N = 10^5 on an H100).
 *
 * Rows are the edge rows 0 .. nv-1; edge row j of component k couples only
 * to rows in [start[k], start[k] + ne[k]) ("live"; an open rope's last vertex
 * has no edge, its row is dead and gets z = 0). Closed components use the
 * same Sherman-Morrison split as the reference (Numerical Recipes 2.7): a
 * plain tridiagonal matrix with a modified diagonal, and the correction
 * vector uu solved once per preconditioner setup.
 *
 * Each level of stride s eliminates rows j - s and j + s from row j; after
 * ceil(log2(max ne)) levels every row stands alone and x_j = d_j / b_j.
 * The arithmetic differs from Thomas in its rounding only; the matrix is
 * symmetric positive definite and diagonally dominant up to the projection of
 * the constraints, where PCR without pivoting is stable.
 *
 * A set is one buffer of 4 nv reals: sub-diagonal a, diagonal b,
 * super-diagonal c, right-hand side d, in that order. */

inline void tri_bounds(int j, __global const int *comp, __global const int *start,
                       __global const int *ne, int *lo, int *hi)
{
    int k = comp[j];
    *lo = start[k];
    *hi = start[k] + ne[k];
}

/* One PCR elimination of row j at stride s, from set src into set dst. */
inline void pcr_row(int j, int s, int lo, int hi, int nv, __global const real *src,
                    __global real *dst)
{
    __global const real *a = src, *b = src + nv, *c = src + 2 * nv, *d = src + 3 * nv;
    real aj = a[j], bj = b[j], cj = c[j], dj = d[j], an = 0.0, cn = 0.0;
    if (j >= hi) { /* dead row: stays the identity with a zero right-hand side */
        aj = 0.0;
        bj = 1.0;
        cj = 0.0;
        dj = 0.0;
    } else {
        if (j - s >= lo) {
            real k1 = aj / b[j - s];
            bj -= c[j - s] * k1;
            dj -= d[j - s] * k1;
            an = -a[j - s] * k1;
        }
        if (j + s < hi) {
            real k2 = cj / b[j + s];
            bj -= a[j + s] * k2;
            dj -= d[j + s] * k2;
            cn = -c[j + s] * k2;
        }
    }
    dst[j] = an;
    dst[nv + j] = bj;
    dst[2 * nv + j] = cn;
    dst[3 * nv + j] = dj;
}

/* z_j from the fully reduced set: d_j / b_j, and for closed components
 * (when sm) minus the Sherman-Morrison multiple of uu. */
inline real pcr_finish(int j, int nv, __global const real *set, __global const real *pd,
                       __global const real *po, __global const int *comp,
                       __global const int *start, __global const int *ne,
                       __global const int *closed, __global const real *uu, int sm)
{
    int k = comp[j], st = start[k], n = ne[k];
    if (j >= st + n)
        return 0.0;
    __global const real *b = set + nv, *d = set + 3 * nv;
    real x = d[j] / b[j];
    if (!sm || !closed[k] || n < 3)
        return x;
    real beta = po[st + n - 1], gamma = -pd[st];
    real x0 = d[st] / b[st], x1 = d[st + n - 1] / b[st + n - 1];
    real fact = (x0 + beta * x1 / gamma) / (1.0 + uu[st] + beta * uu[st + n - 1] / gamma);
    return x - fact * uu[j];
}

/* The level-0 set from the preconditioner (pd, po): the reference's sub and
 * sup, the Sherman-Morrison diagonal of closed components, and as right-hand
 * side the vector whose solve is uu (gamma at the first row, alpha at the
 * last, of each closed component; zero elsewhere). One item per edge row. */
__kernel void tridiag_matrix(__global const real *pd, __global const real *po,
                             __global const int *comp, __global const int *start,
                             __global const int *ne, __global const int *closed, const int nv,
                             __global real *set)
{
    TR_ITEMS(j, nv) {
        int k = comp[j], st = start[k], n = ne[k];
        real a = 0.0, b = 1.0, c = 0.0, d = 0.0;
        if (j < st + n) {
            a = j > st ? po[j - 1] : 0.0;
            c = j + 1 < st + n ? po[j] : 0.0;
            b = pd[j];
            if (closed[k] && n >= 3) {
                real alpha = po[st + n - 1], gamma = -pd[st];
                if (j == st) {
                    b = pd[j] - gamma;
                    d = gamma;
                }
                if (j == st + n - 1) {
                    b = pd[j] - alpha * alpha / gamma;
                    d = alpha;
                }
            }
        }
        set[j] = a;
        set[nv + j] = b;
        set[2 * nv + j] = c;
        set[3 * nv + j] = d;
    }
}

/* One level over every row (large systems: one launch per level). */
__kernel void tridiag_level(const int s, __global const int *comp, __global const int *start,
                            __global const int *ne, const int nv, __global const real *src,
                            __global real *dst)
{
    TR_ITEMS(j, nv) {
        int lo, hi;
        tri_bounds(j, comp, start, ne, &lo, &hi);
        pcr_row(j, s, lo, hi, nv, src, dst);
    }
}

__kernel void tridiag_finish(__global const real *set, __global const real *pd,
                             __global const real *po, __global const int *comp,
                             __global const int *start, __global const int *ne,
                             __global const int *closed, __global const real *uu, const int sm,
                             const int nv, __global real *z)
{
    TR_ITEMS(j, nv) {
        z[j] = pcr_finish(j, nv, set, pd, po, comp, start, ne, closed, uu, sm);
    }
}

/* Small systems: every level and the finish in one work-group (global-memory
 * barriers between levels), one launch instead of levels + 1. set0 is read,
 * p and q alternate as destinations. */
__kernel void tridiag_group(const int levels, __global const real *set0, __global real *p,
                            __global real *q, __global const real *pd, __global const real *po,
                            __global const int *comp, __global const int *start,
                            __global const int *ne, __global const int *closed,
                            __global const real *uu, const int sm, const int nv,
                            __global real *z)
{
    int lid = get_local_id(0), ls = get_local_size(0);
    __global const real *src = set0;
    __global real *dst = p;
    for (int l = 0, s = 1; l < levels; l++, s *= 2) {
        for (int j = lid; j < nv; j += ls) {
            int lo, hi;
            tri_bounds(j, comp, start, ne, &lo, &hi);
            pcr_row(j, s, lo, hi, nv, src, dst);
        }
        barrier(CLK_GLOBAL_MEM_FENCE);
        src = dst;
        dst = dst == p ? q : p;
    }
    for (int j = lid; j < nv; j += ls)
        z[j] = pcr_finish(j, nv, src, pd, po, comp, start, ne, closed, uu, sm);
}
