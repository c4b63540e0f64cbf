/* From the tree's per-edge partner lists (sorted, both directions; edge a's
 * list starts at list + loff[a] and holds count[a] entries) to the backend's
 * contact list: pairs (a, b), a < b, in (a, b) order, and the per-vertex
 * adjacency (CSR: vertex v's row starts at adj + aoff[v]) that the force and
 * projection gathers walk. Every array is sized by what the list holds, never
 * by its longest row: on a tight curve some points lie within 2 + 3e-4 of a
 * long arc of their partner (on the tight trefoil, arcs of about 6), and a
 * thousand or more partner edges pass the nearly-normal test against 76 on
 * average (N = 10^4 .. 10^5), so N times the longest row is ~15 times the
 * list. The order of every list is fixed by the indices alone, so the
 * gathers sum in the reference's order. */

/* up[a]: partners b > a of edge a; first[a]: index in a's list of the first
 * such b; adjc[a]: adjacency entries of vertex a (the partners of the edges
 * starting and ending at a; count is 0 where no edge starts). */
__kernel void pairs_upper(__global const int *count, __global const int *list,
                          __global const int *loff, __global const int *next,
                          __global const int *prev, const int n, __global int *up,
                          __global int *first, __global int *adjc)
{
    int a = get_global_id(0);
    if (a >= n)
        return;
    adjc[a] = count[a] + (prev[a] >= 0 ? count[prev[a]] : 0);
    if (next[a] < 0) {
        up[a] = 0;
        first[a] = 0;
        return;
    }
    __global const int *l = list + loff[a];
    int m = count[a], k = 0;
    while (k < m && l[k] < a)
        k++;
    first[a] = k;
    up[a] = m - k;
}

__kernel void pairs_write(__global const int *count, __global const int *list,
                          __global const int *loff, __global const int *first, __global const int *off, const int n,
                          __global int *pa, __global int *pb)
{
    int a = get_global_id(0);
    if (a >= n)
        return;
    __global const int *l = list + loff[a];
    int o = off[a];
    for (int k = first[a]; k < count[a]; k++) {
        pa[o] = a;
        pb[o] = l[k];
        o++;
    }
}

/* Index of pair (a, b), a < b: a's offset plus b's rank among a's upper partners. */
inline int pair_index(__global const int *list, __global const int *loff,
                      __global const int *count, __global const int *first,
                      __global const int *off, int a, int b)
{
    __global const int *l = list + loff[a];
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
__kernel void contacts_csr(__global const int *count, __global const int *list,
                           __global const int *loff, __global const int *first,
                           __global const int *off, __global const int *next,
                           __global const int *prev, const int n, __global const int *aoff,
                           __global int *adj, __global int *adjn)
{
    int v = get_global_id(0);
    if (v >= n)
        return;
    __global int *row = adj + aoff[v];
    int m = 0;
    for (int side = 0; side < 2; side++) {
        int e = side == 0 ? v : prev[v]; /* edge whose first (side 0) or second vertex is v */
        if (e < 0 || next[e] < 0)
            continue;
        __global const int *l = list + loff[e];
        for (int k = 0; k < count[e]; k++) {
            int o = l[k], code;
            if (o > e) /* pair (e, o): v is a or next a */
                code = 4 * (off[e] + k - first[e]) + side;
            else /* pair (o, e): v is b or next b */
                code = 4 * pair_index(list, loff, count, first, off, o, e) + 2 + side;
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
