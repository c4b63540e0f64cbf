/* From the tree's per-edge partner lists (sorted, both directions; edge a's
 * list starts at list + loff[a] and holds count[a] entries) to the backend's
 * contact list: pairs (a, b), a < b, in (a, b) order, the reference's. Every
 * array is sized by what the list holds, never by its longest row: on a
 * tight curve some points lie within 2 + 3e-4 of a long arc of their partner
 * (on the tight trefoil, arcs of about 6), and a thousand or more partner
 * edges pass the nearly-normal test against 76 on average (N = 10^4 ..
 * 10^5), so N times the longest row is ~15 times the list. */

/* up[a]: partners b > a of edge a; first[a]: index in a's list of the first
 * such b (count is 0 where no edge starts). */
__kernel void pairs_upper(__global const int *count, __global const int *list,
                          __global const int *loff, __global const int *next,
                          const int n, __global int *up, __global int *first)
{
    TR_ITEMS(a, n) {
        if (next[a] < 0) {
            up[a] = 0;
            first[a] = 0;
            continue;
        }
        __global const int *l = list + loff[a];
        int m = count[a], k = 0;
        while (k < m && l[k] < a)
            k++;
        first[a] = k;
        up[a] = m - k;
    }
}

__kernel void pairs_write(__global const int *count, __global const int *list,
                          __global const int *loff, __global const int *first,
                          __global const int *off, const int n, __global int *pa,
                          __global int *pb)
{
    TR_ITEMS(a, n) {
        __global const int *l = list + loff[a];
        int o = off[a];
        for (int k = first[a]; k < count[a]; k++) {
            pa[o] = a;
            pb[o] = l[k];
            o++;
        }
    }
}

/* dmin[item] = the smallest segment distance of the work-item's pairs
 * (INFINITY for none): the list's closest pair, folded by the host. */
__kernel void pairs_min_dist(__global const real *x, __global const int *next,
                             __global const int *pa, __global const int *pb, const int np,
                             __global real *dmin)
{
    real m = INFINITY;
    TR_ITEMS(p, np) {
        int a = pa[p], b = pb[p];
        real s, t;
        m = fmin(m, tr_segment_distance(vload3(a, x), vload3(next[a], x), vload3(b, x),
                                        vload3(next[b], x), &s, &t));
    }
    dmin[get_global_id(0)] = m;
}
