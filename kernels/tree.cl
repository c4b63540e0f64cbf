/* Neighbour search on the device over the reference's tree of edges
 * (host/geometry/neighbour_search.c): a balanced binary tree whose leaves are runs
 * of 8 consecutive edges of one component, so that it never needs sorting
 * and refitting its boxes after a move is one pass per level. Each edge
 * walks the tree with a small private stack and keeps the partners of
 * backend.h's contact list. With a tilt (0 < tilt < 1) a node is skipped
 * when its box misses the edge's normal slab widened by pad = tilt * cutoff,
 * and a leaf when the edge's box misses the slab along the leaf's chord that
 * holds its edges' slabs: both sides must be nearly normal to the strut, so
 * each edge visits a few leaves per nearby strand and the search is linear
 * in N, where a grid of cells as wide as the cutoff would hold O(N) edges
 * each.
 * Pruning is conservative (boxes widened against rounding); the exact tests
 * are the reference's, evaluated lower edge first, so the lists agree bit
 * for bit. */

#define TREE_STACK 128
#define TREE_SLACK 1e-12

/* Box of edge i: centre m, half-widths r, widened so rounding never shrinks it. */
inline void edge_box(__global const real *x, __global const int *next, int i, real3 *m, real3 *r)
{
    real3 p = vload3(i, x), q = vload3(next[i], x);
    real3 lo = fmin(p, q), hi = fmax(p, q);
    *m = 0.5 * (lo + hi);
    *r = 0.5 * (hi - lo);
    *r += 4.0 * DBL_EPSILON * (fabs(*m) + *r);
}

inline real box_dist2(real3 am, real3 ar, real3 bm, real3 br)
{
    real3 g = fmax(fabs(am - bm) - ar - br, (real3)(0.0));
    return tr_dot3(g, g);
}

/* [min, max] of (y - p).u over a box, widened against rounding. */
inline double2 box_project(real3 m, real3 r, real3 p, real3 u)
{
    real3 d = m - p, au = fabs(u);
    real c = tr_dot3(d, u), w = tr_dot3(r, au), scale = tr_dot3(fabs(d), au);
    real slack = 1e-10 * (scale + w);
    return (double2)(c - w - slack, c + w + slack);
}

/* Does the box meet {y : (y - p).t in [-pad |t|, |t|^2 + pad |t|]}? */
inline int box_in_slab(real3 m, real3 r, real3 p, real3 t, real pad)
{
    double2 pr = box_project(m, r, p, t);
    real tl = tr_norm3(t), reach = pad * tl;
    return pr.y >= -reach && pr.x <= tr_dot3(t, t) + reach;
}

/* Leaf boxes: every leaf (leaf_id[k], k < nleaf) over its edges [a, b). */
__kernel void tree_leaf_box(__global const real *x, __global const int *next, __global const int *tedge,
                            __global const int *leaf_id, const int nleaf, __global const int *node_a,
                            __global const int *node_b, __global real *box)
{
    TR_ITEMS(k, nleaf) {
        int id = leaf_id[k];
        real3 lo = (real3)(INFINITY), hi = (real3)(-INFINITY);
        for (int e = node_a[id]; e < node_b[id]; e++) {
            int v = tedge[e];
            real3 p = vload3(v, x), q = vload3(next[v], x);
            lo = fmin(lo, fmin(p, q));
            hi = fmax(hi, fmax(p, q));
        }
        real3 m = 0.5 * (lo + hi), r = 0.5 * (hi - lo);
        r += 4.0 * DBL_EPSILON * (fabs(m) + r);
        vstore3(m, 2 * id, box);
        vstore3(r, 2 * id + 1, box);
    }
}

/* Inner boxes of one level (node ids ids[off .. off + n)), children already fitted. */
__kernel void tree_inner_box(__global const int *ids, const int off, const int n,
                             __global const int *left, __global const int *right, __global real *box)
{
    TR_ITEMS(k, n) {
        int id = ids[off + k], l = left[id], rt = right[id];
        real3 lm = vload3(2 * l, box), lr = vload3(2 * l + 1, box);
        real3 rm = vload3(2 * rt, box), rr = vload3(2 * rt + 1, box);
        real3 lo = fmin(lm - lr, rm - rr), hi = fmax(lm + lr, rm + rr);
        real3 m = 0.5 * (lo + hi), r = 0.5 * (hi - lo);
        r += 4.0 * DBL_EPSILON * (fabs(m) + r);
        vstore3(m, 2 * id, box);
        vstore3(r, 2 * id + 1, box);
    }
}

/* The slab along each leaf's chord u that holds its edges' slabs widened by
 * pad, for partners within D (host/geometry/neighbour_search.c block_setup): slab[id]
 * = (p0, u, lo, hi); lo > hi marks a run that turns too much (no pruning). */
__kernel void tree_leaf_slab(__global const real *x, __global const int *next, __global const int *tedge,
                             __global const int *leaf_id, const int nleaf, __global const int *node_a,
                             __global const int *node_b, const real D, const real pad,
                             __global real *slab)
{
    TR_ITEMS(k, nleaf) {
        int id = leaf_id[k], a = node_a[id], b = node_b[id];
        real3 p0 = vload3(tedge[a], x);
        real3 ch = vload3(next[tedge[b - 1]], x) - p0;
        real L = tr_norm3(ch);
        __global real *out = slab + 8 * id;
        out[6] = 1.0;
        out[7] = -1.0;
        if (!(L > 0.0))
            continue;
        real3 u = ch / L;
        real lo = 0.0, hi = -INFINITY, lmax = 0.0, dmax = 0.0;
        int e = a;
        for (; e < b; e++) { /* a zero edge, or one far from the chord: no slab */
            int v = tedge[e];
            real3 pa = vload3(v, x), t = vload3(next[v], x) - pa;
            real l = tr_norm3(t);
            if (!(l > 0.0))
                break;
            real dn = tr_norm3(t / l - u);
            if (dn > 0.5)
                break;
            dmax = fmax(dmax, dn);
            lmax = fmax(lmax, l);
            real pr = tr_dot3(pa - p0, u);
            lo = fmin(lo, pr);
            hi = fmax(hi, pr + l);
        }
        if (e < b)
            continue;
        real wdt = (D + lmax) * dmax, sl = 1e-10 * (L + lmax + D);
        vstore3(p0, 0, out);
        vstore3(u, 1, out);
        out[6] = lo - wdt - pad - sl;
        out[7] = hi + wdt + pad + sl;
    }
}

inline int leaf_slab_meets(__global const real *slab, int id, real3 m, real3 r)
{
    __global const real *s = slab + 8 * id;
    if (s[6] > s[7])
        return 1;
    double2 pr = box_project(m, r, vload3(0, s), vload3(1, s));
    return pr.y >= s[6] && pr.x <= s[7];
}

/* Index distance of vertices i, j along their component (a closed one
 * wraps) below that component's gap (at least 2); different components are
 * never excluded. */
inline int index_excluded(__global const int *comp, __global const int *pos, __global const int *comp_n,
                          __global const int *comp_closed, int i, int j, __global const int *gap)
{
    int c = comp[i];
    if (comp[j] != c)
        return 0;
    int g = abs(pos[i] - pos[j]);
    if (comp_closed[c])
        g = min(g, comp_n[c] - g);
    return g < max(gap[c], 2);
}

/* Same component, and every pair of tree edges i (one) and [a, b) within
 * index distance < g (or, closed, > m - g): host range_excluded. */
inline int range_excluded(int i, int a, int b, int g, int closed, int m)
{
    long dlo = (long)i - (long)(b - 1), dhi = (long)i - (long)a;
    if (dlo > -g && dhi < g)
        return 1;
    if (!closed)
        return 0;
    if (2 * g > m)
        return 1;
    return dlo > m - g || dhi < -(m - g);
}

/* For the edge of vertex i: partners j (vertices whose edges qualify) in
 * increasing j, as grid_pairs lists them, at list + loff[i] with room for
 * loff[i + 1] - loff[i]; count[i] is the full number even beyond that room
 * (then *overflow = 1); a stack overflow sets *overflow = 2. */
__kernel void tree_pairs(__global const real *x, __global const int *next, const int n,
                         __global const int *comp, __global const int *pos,
                         __global const int *comp_n, __global const int *comp_closed,
                         __global const int *gap, const int min_gap, __global const int *vedge,
                         __global const int *tedge, __global const int *comp_estart,
                         __global const int *node_a, __global const int *node_b,
                         __global const int *node_comp, __global const int *left,
                         __global const int *right, __global const real *box,
                         __global const real *slab, const real cutoff, const real tilt,
                         __global const int *loff, __global int *count, __global int *list,
                         __global int *overflow)
{
    TR_ITEMS(i, n) {
        if (next[i] < 0) {
            count[i] = 0;
            continue;
        }
        int use_slab = tilt > 0.0 && tilt < 1.0;
        real pad = tilt * cutoff;
        real cut = cutoff * (1.0 + TREE_SLACK), cut2 = cut * cut;
        real3 qm, qr;
        edge_box(x, next, i, &qm, &qr);
        real3 a0 = vload3(i, x), a1 = vload3(next[i], x), qt = a1 - a0;
        int ti = vedge[i], k = comp[i];
        int kclosed = comp_closed[k], kedges = comp_estart[k + 1] - comp_estart[k];
        int m = 0;
        __global int *mine = list + loff[i];
        int cap = loff[i + 1] - loff[i];
        int stack[TREE_STACK];
        int sp = 0;
        stack[sp++] = 0;
        while (sp > 0) {
            int id = stack[--sp];
            real3 nm = vload3(2 * id, box), nr = vload3(2 * id + 1, box);
            if (box_dist2(qm, qr, nm, nr) > cut2)
                continue;
            if (node_comp[id] == k && range_excluded(ti, node_a[id], node_b[id], min_gap, kclosed, kedges))
                continue;
            if (use_slab && !box_in_slab(nm, nr, a0, qt, pad))
                continue;
            if (left[id] != 0) {
                if (sp + 2 > TREE_STACK) {
                    atomic_max(overflow, 2);
                    break;
                }
                stack[sp++] = right[id];
                stack[sp++] = left[id];
                continue;
            }
            if (use_slab && !leaf_slab_meets(slab, id, qm, qr))
                continue;
            for (int e = node_a[id]; e < node_b[id]; e++) {
                int j = tedge[e];
                if (j == i || index_excluded(comp, pos, comp_n, comp_closed, i, j, gap))
                    continue;
                real3 em, er;
                edge_box(x, next, j, &em, &er);
                if (box_dist2(qm, qr, em, er) > cut2)
                    continue;
                real3 b0 = vload3(j, x), b1 = vload3(next[j], x);
                if (use_slab && (!box_in_slab(em, er, a0, qt, pad) || !box_in_slab(qm, qr, b0, b1 - b0, pad)))
                    continue;
                real3 l0 = i < j ? a0 : b0, l1 = i < j ? a1 : b1;
                real3 h0 = i < j ? b0 : a0, h1 = i < j ? b1 : a1;
                real ss, tt;
                real d = tr_segment_distance(l0, l1, h0, h1, &ss, &tt);
                if (!(d < cutoff) || (use_slab && !tr_segment_nearly_normal(l0, l1, h0, h1, ss, tt, d, tilt)))
                    continue;
                if (m < cap) {
                    int q = m;
                    while (q > 0 && mine[q - 1] > j) {
                        mine[q] = mine[q - 1];
                        q--;
                    }
                    mine[q] = j;
                } else {
                    atomic_max(overflow, 1);
                }
                m++;
            }
        }
        count[i] = m;
    }
}

/* Room for edge i's partners in the next walk: the last walk's count and a
 * quarter more (partners come and go a few at a time between steps), 0 where
 * no edge starts. Scanned into the list offsets (the host has bounded the
 * counts' sum, so the scan does not wrap). */
__kernel void list_room(__global const int *count, __global const int *next, const int n,
                        __global int *room)
{
    TR_ITEMS(i, n) {
        room[i] = next[i] < 0 ? 0 : count[i] + count[i] / 4 + 4;
    }
}
