/* From the grid's per-edge partner lists (sorted, both directions) to the
 * backend's contact list: pairs (a, b), a < b, in (a, b) order, and the
 * per-vertex adjacency (CSR with a fixed row capacity) that the force and
 * projection gathers walk. The order of every list is fixed by the indices
 * alone, so the gathers sum in the reference's order. */

/* up[a]: partners b > a of edge a; first[a]: index in a's list of the first such b. */
__kernel void pairs_upper(__global const int *count, __global const int *list, const int cap,
                          __global const int *next, const int n, __global int *up,
                          __global int *first)
{
    int a = get_global_id(0);
    if (a >= n)
        return;
    if (next[a] < 0) {
        up[a] = 0;
        first[a] = 0;
        return;
    }
    __global const int *l = list + (size_t)a * (size_t)cap;
    int m = count[a], k = 0;
    while (k < m && l[k] < a)
        k++;
    first[a] = k;
    up[a] = m - k;
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
    int i = get_global_id(0);
    if (i < n)
        out[i] += sums[i / TR_LOCAL_SIZE];
}

__kernel void pairs_write(__global const int *count, __global const int *list, const int cap,
                          __global const int *first, __global const int *off, const int n,
                          __global int *pa, __global int *pb)
{
    int a = get_global_id(0);
    if (a >= n)
        return;
    __global const int *l = list + (size_t)a * (size_t)cap;
    int o = off[a];
    for (int k = first[a]; k < count[a]; k++) {
        pa[o] = a;
        pb[o] = l[k];
        o++;
    }
}

/* Index of pair (a, b), a < b: a's offset plus b's rank among a's upper partners. */
inline int pair_index(__global const int *list, const int cap, __global const int *count,
                      __global const int *first, __global const int *off, int a, int b)
{
    __global const int *l = list + (size_t)a * (size_t)cap;
    int lo = first[a], hi = count[a] - 1;
    while (lo < hi) { /* b is in the list: binary search */
        int mid = (lo + hi) / 2;
        if (l[mid] < b)
            lo = mid + 1;
        else
            hi = mid;
    }
    return off[a] + lo - first[a];
}

/* adj row of vertex v: codes 4 p + slot for every pair p touching v (slot 0:
 * v = a, 1: v = next a, 2: v = b, 3: v = next b), ascending, as the
 * reference's CSR (pairs in list order, slots in order within a pair). */
__kernel void contacts_csr(__global const int *count, __global const int *list, const int cap,
                           __global const int *first, __global const int *off,
                           __global const int *next, __global const int *prev, const int n,
                           const int acap, __global int *adj, __global int *adjn)
{
    int v = get_global_id(0);
    if (v >= n)
        return;
    __global int *row = adj + (size_t)v * (size_t)acap;
    int m = 0;
    for (int side = 0; side < 2; side++) {
        int e = side == 0 ? v : prev[v]; /* edge whose first (side 0) or second vertex is v */
        if (e < 0 || next[e] < 0)
            continue;
        __global const int *l = list + (size_t)e * (size_t)cap;
        for (int k = 0; k < count[e]; k++) {
            int o = l[k], code;
            if (o > e) /* pair (e, o): v is a or next a */
                code = 4 * (off[e] + k - first[e]) + side;
            else /* pair (o, e): v is b or next b */
                code = 4 * pair_index(list, cap, count, first, off, o, e) + 2 + side;
            int j = m++;
            while (j > 0 && row[j - 1] > code) {
                row[j] = row[j - 1];
                j--;
            }
            row[j] = code;
        }
    }
    adjn[v] = m;
}

/* d[p] = segment distance of pair p (for the list's statistics). */
__kernel void pairs_dist(__global const real *x, __global const int *next,
                         __global const int *pa, __global const int *pb, const int np,
                         __global real *d)
{
    int p = get_global_id(0);
    if (p >= np)
        return;
    int a = pa[p], b = pb[p];
    real s, t;
    d[p] = tr_segment_distance(vload3(a, x), vload3(next[a], x), vload3(b, x), vload3(next[b], x),
                               &s, &t);
}
