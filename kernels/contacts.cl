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
                          __global const int *loff, __global const int *first,
                          __global const int *off, const int n, __global int *pa,
                          __global int *pb)
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

/* The adjacency code of entry k of edge e's list, for the vertex at the
 * edge's start (side 0) or end (side 1). */
inline int adj_code(__global const int *list, __global const int *loff, __global const int *count,
                    __global const int *first, __global const int *off, int e, int k, int side)
{
    int o = list[loff[e] + k];
    if (o > e) /* pair (e, o): the vertex is a or next a */
        return 4 * (off[e] + k - first[e]) + side;
    /* pair (o, e): the vertex is b or next b */
    return 4 * pair_index(list, loff, count, first, off, o, e) + 2 + side;
}

/* adj row of vertex v: codes 4 p + slot for every pair p touching v (slot 0:
 * v = a, 1: v = next a, 2: v = b, 3: v = next b), ascending, as the
 * reference's CSR (pairs in list order, slots in order within a pair).
 * Along one edge's sorted partner list the codes ascend already (pairs are
 * ordered by their lower edge, then the higher), so the row is the merge of
 * two ascending runs: the edge starting at v and the edge ending there. A
 * row can hold thousands of entries on a tight curve (see the top), where
 * sorting by insertion took 440 ms per search at N = 10^5 on PoCL. */
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
    int e0 = next[v] >= 0 ? v : -1, e1 = prev[v]; /* the edges starting and ending at v */
    int n0 = e0 >= 0 ? count[e0] : 0, n1 = e1 >= 0 ? count[e1] : 0;
    int k0 = 0, k1 = 0, m = 0;
    int c0 = n0 > 0 ? adj_code(list, loff, count, first, off, e0, 0, 0) : 0;
    int c1 = n1 > 0 ? adj_code(list, loff, count, first, off, e1, 0, 1) : 0;
    while (k0 < n0 || k1 < n1) {
        if (k1 >= n1 || (k0 < n0 && c0 < c1)) {
            row[m++] = c0;
            if (++k0 < n0)
                c0 = adj_code(list, loff, count, first, off, e0, k0, 0);
        } else {
            row[m++] = c1;
            if (++k1 < n1)
                c1 = adj_code(list, loff, count, first, off, e1, k1, 1);
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
