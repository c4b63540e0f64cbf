/* Reductions the driver reads back each step: polygon length, sums and dot
 * products, largest and smallest values. Two stages, both deterministic for
 * a given N on a given device (the split into work-groups and items follows
 * the launch shape): in stage 1 each work-group takes a contiguous slice of
 * the input, each of its items folds its share of that slice (GROUP_SLICE_FOR;
 * compensated, Neumaier) and the work-group of TR_LOCAL_SIZE items folds
 * those by a fixed tree in local memory; stage 2 (one work-group) folds the
 * partials the same way. The host launches at most TR_RED_GROUPS groups for
 * stage 1: few groups with long slices, because on a CPU device every
 * work-group with barriers costs far more than the arithmetic. No atomics,
 * so the same input always gives the same bits. */

/* Neumaier: s + c carries the sum of everything added so far. */
#define KAHAN_ADD(s, c, v)                                                      \
    do {                                                                        \
        real v_ = (v), t_ = (s) + v_;                                           \
        (c) += fabs(s) >= fabs(v_) ? ((s) - t_) + v_ : (v_ - t_) + (s);         \
        (s) = t_;                                                               \
    } while (0)

/* This item's indices of [0, n): work-group g takes the g-th of the
 * groups' contiguous slices and its items share that slice
 * (GROUP_SLICE_FOR). Interleaving the groups over the whole range (a stride
 * of the global size) streamed memory about half as fast on PoCL once the
 * vectors outgrow the cache (N = 10^6). */
#define SLICE_FOR(i, n)                                                                    \
    GROUP_SLICE_FOR(i, (int)((long)(n) * get_group_id(0) / get_num_groups(0)),              \
                    (int)((long)(n) * (get_group_id(0) + 1) / get_num_groups(0)))

/* Length of the edge from vertex i to next[i] (0 where next[i] < 0: the end of an open rope). */
inline real edge_len(__global const real *x, __global const int *next, int i)
{
    int j = next[i];
    if (j < 0)
        return 0.0;
    real3 d = vload3(j, x) - vload3(i, x);
    return sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void length_partial(__global const real *x, __global const int *next, const int n,
                    __global real *partial)
{
    __local real s[TR_LOCAL_SIZE];
    int l = get_local_id(0);
    real sum = 0.0, c = 0.0;
    SLICE_FOR(i, n)
        KAHAN_ADD(sum, c, edge_len(x, next, i));
    s[l] = sum + c;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(tr_add, s, l)
    if (l == 0)
        partial[get_group_id(0)] = s[0];
}

/* Largest and smallest of v[0..n) per work-group (padding items repeat v[0]). */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void minmax_partial(__global const real *v, const int n, __global real *pmin, __global real *pmax)
{
    __local real lo[TR_LOCAL_SIZE], hi[TR_LOCAL_SIZE];
    int l = get_local_id(0), n4 = n / 4;
    /* four entries at a time in explicit vectors, as dot_slice4 (the rows'
     * violations run to millions of entries on a tight curve) */
    real4 a4 = (real4)(v[0]), b4 = a4;
    SLICE_FOR(q, n4) {
        real4 w = vload4(q, v);
        a4 = fmin(a4, w);
        b4 = fmax(b4, w);
    }
    real a = fmin(fmin(a4.s0, a4.s1), fmin(a4.s2, a4.s3));
    real b = fmax(fmax(b4.s0, b4.s1), fmax(b4.s2, b4.s3));
    if (get_global_id(0) == 0)
        for (int i = 4 * n4; i < n; i++) {
            a = fmin(a, v[i]);
            b = fmax(b, v[i]);
        }
    lo[l] = a;
    hi[l] = b;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(fmin, lo, l)
    TREE(fmax, hi, l)
    if (l == 0) {
        pmin[get_group_id(0)] = lo[0];
        pmax[get_group_id(0)] = hi[0];
    }
}

/* Stage 2: out[slot] = sum of partial[0..m), compensated then tree-folded. */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void sum_final(__global const real *partial, const int m, __global real *out, const int slot)
{
    __local real s[TR_LOCAL_SIZE];
    int l = get_local_id(0);
    real sum = 0.0, c = 0.0;
    for (int k = l; k < m; k += TR_LOCAL_SIZE) {
        real v = partial[k], t = sum + v;
        c += fabs(sum) >= fabs(v) ? (sum - t) + v : (v - t) + sum; /* Neumaier */
        sum = t;
    }
    s[l] = sum + c;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(tr_add, s, l)
    if (l == 0)
        out[slot] = s[0];
}

/* Stage 2 of minmax_partial: out[slot] = min, out[slot + 1] = max. */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void minmax_final(__global const real *pmin, __global const real *pmax, const int m,
                  __global real *out, const int slot)
{
    __local real lo[TR_LOCAL_SIZE], hi[TR_LOCAL_SIZE];
    int l = get_local_id(0);
    real a = pmin[0], b = pmax[0];
    for (int k = l; k < m; k += TR_LOCAL_SIZE) {
        a = fmin(a, pmin[k]);
        b = fmax(b, pmax[k]);
    }
    lo[l] = a;
    hi[l] = b;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(fmin, lo, l)
    TREE(fmax, hi, l)
    if (l == 0) {
        out[slot] = lo[0];
        out[slot + 1] = hi[0];
    }
}

/* len[i] = |x[next[i]] - x[i]|, or 0 where vertex i starts no edge. */
__kernel void edge_lengths(__global const real *x, __global const int *next, const int n,
                           __global real *len)
{
    TR_ITEMS(i, n) {
        len[i] = edge_len(x, next, i);
    }
}

/* Stage 1 of a plain sum of v[0..n) (then sum_final). */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void sum_partial(__global const real *v, const int n, __global real *partial)
{
    __local real s[TR_LOCAL_SIZE];
    int l = get_local_id(0);
    real sum = 0.0, c = 0.0;
    SLICE_FOR(i, n)
        KAHAN_ADD(sum, c, v[i]);
    s[l] = sum + c;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(tr_add, s, l)
    if (l == 0)
        partial[get_group_id(0)] = s[0];
}

/* One item's share of a . b over the first n entries (SLICE_FOR over quads)
 * four entries at a time in explicit vectors (Neumaier per lane), since a
 * CPU device runs an item's loop as scalar code otherwise; item 0 adds the
 * n mod 4 entries at the end. */
inline real dot_slice4(__global const real *a, __global const real *b, int n)
{
    int n4 = n / 4;
    real4 sum = (real4)(0.0), c = (real4)(0.0);
    SLICE_FOR(q, n4) {
        real4 v = vload4(q, a) * vload4(q, b), t = sum + v;
        c += select((v - t) + sum, (sum - t) + v, isgreaterequal(fabs(sum), fabs(v)));
        sum = t;
    }
    real r = ((sum.s0 + c.s0) + (sum.s1 + c.s1)) + ((sum.s2 + c.s2) + (sum.s3 + c.s3));
    if (get_global_id(0) == 0)
        for (int i = 4 * n4; i < n; i++)
            r += a[i] * b[i];
    return r;
}

/* Stage 1 of a dot product a . b over n entries (then sum_final); the CG
 * takes three per iteration, so it is the hottest reduction. */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void dot_partial(__global const real *a, __global const real *b, const int n,
                 __global real *partial)
{
    __local real s[TR_LOCAL_SIZE];
    int l = get_local_id(0);
    s[l] = dot_slice4(a, b, n);
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(tr_add, s, l)
    if (l == 0)
        partial[get_group_id(0)] = s[0];
}

/* Stage 1 of a count: the sum of int flags (exact in double below 2^53). */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void isum_partial(__global const int *v, const int n, __global real *partial)
{
    __local real s[TR_LOCAL_SIZE];
    int l = get_local_id(0);
    real sum = 0.0;
    SLICE_FOR(i, n)
        sum += (real)v[i];
    s[l] = sum;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(tr_add, s, l)
    if (l == 0)
        partial[get_group_id(0)] = s[0];
}

/* Per-component sums: work-group k adds v[start[k] .. start[k+1]) into
 * out[slot + k] (Neumaier sums over GROUP_SLICE_FOR, then the tree). */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void comp_sum(__global const real *v, __global const int *start, __global real *out,
              const int slot)
{
    __local real s[TR_LOCAL_SIZE];
    int k = get_group_id(0), l = get_local_id(0);
    real sum = 0.0, c = 0.0;
    GROUP_SLICE_FOR(i, start[k], start[k + 1]) {
        real v1 = v[i], t = sum + v1;
        c += fabs(sum) >= fabs(v1) ? (sum - t) + v1 : (v1 - t) + sum;
        sum = t;
    }
    s[l] = sum + c;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(tr_add, s, l)
    if (l == 0)
        out[slot + k] = s[0];
}

/* Exclusive prefix sums in three passes: scan_local scans each work-group
 * and leaves its total in sums[group]; scan_sums scans those totals in one
 * work-group (a loop over blocks); scan_add adds each group's offset.
 * out has n + 1 entries (out[n] = total). */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void scan_local(__global const int *in, const int n, __global int *out, __global int *sums)
{
    __local int s[TR_LOCAL_SIZE];
    int i = get_global_id(0), l = get_local_id(0);
    int v = i < n ? in[i] : 0;
    s[l] = v;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int w = 1; w < TR_LOCAL_SIZE; w <<= 1) { /* Hillis-Steele inclusive scan */
        int t = l >= w ? s[l - w] : 0;
        barrier(CLK_LOCAL_MEM_FENCE);
        s[l] += t;
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (i < n)
        out[i] = s[l] - v;
    if (l == TR_LOCAL_SIZE - 1)
        sums[get_group_id(0)] = s[l];
}

__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void scan_sums(__global int *sums, const int m, __global int *out, const int n)
{
    __local int s[TR_LOCAL_SIZE];
    __local int carry;
    int l = get_local_id(0);
    if (l == 0)
        carry = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int base = 0; base < m; base += TR_LOCAL_SIZE) {
        int v = base + l < m ? sums[base + l] : 0;
        s[l] = v;
        barrier(CLK_LOCAL_MEM_FENCE);
        for (int w = 1; w < TR_LOCAL_SIZE; w <<= 1) {
            int t = l >= w ? s[l - w] : 0;
            barrier(CLK_LOCAL_MEM_FENCE);
            s[l] += t;
            barrier(CLK_LOCAL_MEM_FENCE);
        }
        if (base + l < m)
            sums[base + l] = carry + s[l] - v;
        barrier(CLK_LOCAL_MEM_FENCE);
        if (l == TR_LOCAL_SIZE - 1)
            carry += s[l];
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (l == 0)
        out[n] = carry;
}

__kernel void scan_add(__global int *out, const int n, __global const int *sums)
{
    TR_ITEMS(i, n) {
        out[i] += sums[i / TR_LOCAL_SIZE];
    }
}
