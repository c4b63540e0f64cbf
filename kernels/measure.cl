/* Per-item terms of backend.h measure(); the reductions in reduce.cl fold them. */

/* len[a] = |e_a| (0 without an edge), dev[a] = ||e_a| - ebar_k| / ebar_k. */
__kernel void measure_edges(__global const real *x, __global const int *next,
                            __global const int *comp, __global const real *ebar, const int nv,
                            __global real *len, __global real *dev)
{
    TR_ITEMS(a, nv) {
        if (next[a] < 0) {
            len[a] = 0.0;
            dev[a] = 0.0;
            continue;
        }
        real3 d = vload3(a, x) - vload3(next[a], x);
        real l = sqrt(tr_dot3(d, d));
        real e = ebar[comp[a]];
        len[a] = l;
        dev[a] = fabs(l - e) / e;
    }
}

/* Rawdon's MinRad at vertex i: min(|a|,|b|) (|a||b| + a.b) / (2 |a x b|);
 * INFINITY where there is no turn or no two edges. */
__kernel void measure_minrad(__global const real *x, __global const int *next,
                             __global const int *prev, const int nv, __global real *mr)
{
    TR_ITEMS(i, nv) {
        mr[i] = INFINITY;
        if (prev[i] < 0 || next[i] < 0)
            continue;
        real3 xi = vload3(i, x);
        real3 a = xi - vload3(prev[i], x), b = vload3(next[i], x) - xi;
        real cn = tr_norm3(tr_cross3(a, b));
        if (cn == 0.0)
            continue;
        real la = tr_norm3(a), lb = tr_norm3(b);
        mr[i] = fmin(la, lb) * (la * lb + tr_dot3(a, b)) / (2.0 * cn);
    }
}

/* |x_i - saved_i| */
__kernel void measure_disp(__global const real *x, __global const real *xs, const int nv,
                           __global real *d)
{
    TR_ITEMS(i, nv) {
        real3 w = vload3(i, x) - vload3(i, xs);
        d[i] = sqrt(tr_dot3(w, w));
    }
}
