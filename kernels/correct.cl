/* Distance-constraint projection and curvature moments (backend.h correct):
 * Gauss-Newton on the active rows (edges, curvature chords, struts), each
 * step solved by CG on J M^-1 J^T. Rows: [0, nv) edge rows, [nv, 2 nv)
 * curvature rows, [2 nv, 2 nv + np) strut rows. J^T y is a per-vertex gather
 * (chain neighbours, then the vertex's contact adjacency in list order);
 * J dx is per row. The CG scalars live in a small device array `sc` so the
 * host reads nothing inside the CG loop but the `done` flag, every fourth
 * iteration (slots: kernels/layout.h). */

/* Per component k: the largest turning angle MinRad >= minrad allows,
 * 2 atan(ebar / (2 minrad)), and its ebar derivative times ebar; rows_chain
 * reads them instead of taking an arc tangent per vertex. */
__kernel void curv_limits(__global const real *ebar, const int ncomp, const real minrad,
                          __global real *lim)
{
    TR_ITEMS(k, ncomp) {
        real eb = ebar[k], rr = minrad;
        lim[2 * k] = 2.0 * atan(eb / (2.0 * rr));
        lim[2 * k + 1] = eb * (1.0 / rr) / (1.0 + eb * eb / (4.0 * rr * rr));
    }
}

/* Vertices i .. i + 3 lie inside one run of the chain (each one's next is
 * the one after it; with prev, also each one's prev the one before). */
inline bool chain_run4(int i, __global const int *next, __global const int *prev)
{
    int4 ids = (int4)(i, i + 1, i + 2, i + 3);
    int4 ok = vload4(0, next + i) == ids + 1;
    if (prev) {
        if (i == 0) /* an open chain's first vertex has prev -1 = i - 1 */
            return false;
        ok &= vload4(0, prev + i) == ids - 1;
    }
    return all(ok);
}

/* Rows r .. r + 3 are all active. */
inline bool active4(__global const int *ract, int r)
{
    return all(vload4(0, ract + r) != 0);
}

#ifdef TR_BLOCK_ITEMS
/* Four consecutive rows a .. a + 3 of an n x 3 array as x, y and z lanes. */
typedef struct {
    real4 x, y, z;
} rows4;

inline rows4 load_rows4(__global const real *p, int a)
{
    __global const real *q = p + 3 * (long)a;
    real4 u = vload4(0, q), v = vload4(1, q), w = vload4(2, q);
    rows4 r;
    r.x = (real4)(u.s0, u.s3, v.s2, w.s1);
    r.y = (real4)(u.s1, v.s0, v.s3, w.s2);
    r.z = (real4)(u.s2, v.s1, w.s0, w.s3);
    return r;
}

inline void store_rows4(rows4 r, __global real *p, int a)
{
    __global real *q = p + 3 * (long)a;
    vstore4((real4)(r.x.s0, r.y.s0, r.z.s0, r.x.s1), 0, q);
    vstore4((real4)(r.y.s1, r.z.s1, r.x.s2, r.y.s2), 1, q);
    vstore4((real4)(r.z.s2, r.x.s3, r.y.s3, r.z.s3), 2, q);
}
#endif

/* rows_chain's two rows at vertex i, one at a time; returns their largest
 * violation. */
inline real chain_rows_at(int i, __global const real *x, __global const int *next,
                          __global const int *prev, __global const int *comp,
                          __global const real *ebar, __global const real *lim, const int nv,
                          const real active_curv, __global real *rC, __global real *rgrad,
                          __global int *ract, __global real *cgq, __global real *cdeb)
{
    real vm = 0.0;
    int nx = next[i], pv = prev[i];
    ract[i] = 0;
    if (nx >= 0) {
        real3 u = vload3(nx, x) - vload3(i, x);
        real l = tr_norm3(u);
        u = u * (1.0 / l);
        vstore3(u, i, rgrad);
        real C = l - ebar[comp[i]];
        rC[i] = C;
        ract[i] = 1;
        vm = fabs(C);
    }
    int r = nv + i;
    ract[r] = 0;
    if (pv >= 0 && nx >= 0) {
        real3 xi = vload3(i, x);
        real3 pe = xi - vload3(pv, x), qe = vload3(nx, x) - xi;
        real3 cr = tr_cross3(pe, qe);
        real lp = tr_norm3(pe), lq = tr_norm3(qe), sn = tr_norm3(cr), cs = tr_dot3(pe, qe);
        real theta = tr_turning_angle(sn, cs);
        int k = comp[i];
        real eb = ebar[k], tmax = lim[2 * k];
        real C = eb * (tmax - theta);
        rC[r] = C;
        cdeb[i] = (tmax - theta) + lim[2 * k + 1];
        real3 ga = (real3)(0.0), gb = (real3)(0.0);
        if (!(sn < 1e-12 * lp * lq)) {
            real c = cs / (lp * lq), sinv = lp * lq / sn;
            real3 ph = pe / lp, qh = qe / lq;
            ga = eb * (c * ph - qh) / lp * sinv;
            gb = eb * (c * qh - ph) / lq * sinv;
            ract[r] = C < active_curv;
        }
        vstore3(ga, r, rgrad);
        vstore3(gb, i, cgq);
        vm = fmax(vm, -C > 0.0 ? -C : 0.0);
    }
    return vm;
}

/* Edge row i and curvature row nv + i; vmax[item] is the largest violation
 * (>= 0) of the work-item's rows (rows_strut: vmax[voff + item]), which the
 * host folds into the largest of all: each row's violation written out and
 * read back ran 13 ms a call over the 2 x 10^7 strut rows of a tight
 * trefoil at N = 10^6 on PoCL.
 * The curvature row is the turning-angle form of MinRad >= minrad:
 * C = ebar (theta_max - theta), theta = atan2(|p x q|, p.q) (tr_turning_angle) for the edges p,
 * q at vertex i; its gradient is ga (stored with the row) on the incoming
 * edge and gb (cgq) on the outgoing one, cdeb its ebar derivative;
 * theta_max per component from curv_limits. */
__kernel void rows_chain(__global const real *x, __global const int *next,
                         __global const int *prev, __global const int *comp,
                         __global const real *ebar, __global const real *lim, const int nv,
                         const real active_curv, __global real *rC, __global real *rgrad,
                         __global int *ract, __global real *vmax, __global real *cgq,
                         __global real *cdeb)
{
    real vm = 0.0;
    int i = tr_items_first(nv), end = tr_items_end(nv);
#ifdef TR_BLOCK_ITEMS
    /* four vertices inside one run of the chain at once, the scalar path's
     * operations per lane (the same bits); the divisions and square roots
     * that set its pace go four to an instruction */
    real4 vm4 = (real4)(0.0);
    while (i < end) {
        if (!(i + 4 <= end && chain_run4(i, next, prev))) {
            vm = fmax(vm, chain_rows_at(i, x, next, prev, comp, ebar, lim, nv, active_curv, rC, rgrad,
                                        ract, cgq, cdeb));
            i++;
            continue;
        }
        int k = comp[i];
        real eb = ebar[k], tmax = lim[2 * k];
        rows4 xp = load_rows4(x, i - 1), xi = load_rows4(x, i), xn = load_rows4(x, i + 1);
        rows4 qe = {xn.x - xi.x, xn.y - xi.y, xn.z - xi.z}, pe = {xi.x - xp.x, xi.y - xp.y, xi.z - xp.z};
        real4 lq = sqrt(qe.x * qe.x + qe.y * qe.y + qe.z * qe.z);
        real4 il = 1.0 / lq;
        rows4 u = {qe.x * il, qe.y * il, qe.z * il};
        store_rows4(u, rgrad, i);
        real4 C = lq - eb;
        vstore4(C, 0, rC + i);
        vstore4((int4)(1), 0, ract + i);
        vm4 = fmax(vm4, fabs(C));
        rows4 cr = {pe.y * qe.z - pe.z * qe.y, pe.z * qe.x - pe.x * qe.z, pe.x * qe.y - pe.y * qe.x};
        real4 lp = sqrt(pe.x * pe.x + pe.y * pe.y + pe.z * pe.z);
        real4 sn = sqrt(cr.x * cr.x + cr.y * cr.y + cr.z * cr.z);
        real4 cs = pe.x * qe.x + pe.y * qe.y + pe.z * qe.z;
        real4 theta = tr_turning_angle4(sn, cs);
        real4 Cc = eb * (tmax - theta);
        vstore4(Cc, 0, rC + nv + i);
        vstore4((tmax - theta) + lim[2 * k + 1], 0, cdeb + i);
        long4 ok = !(sn < 1e-12 * lp * lq);
        real4 c = cs / (lp * lq), sinv = lp * lq / sn;
        rows4 ph = {pe.x / lp, pe.y / lp, pe.z / lp}, qh = {qe.x / lq, qe.y / lq, qe.z / lq};
        rows4 ga, gb;
#define CURV_GRAD(a)                                                                              \
    ga.a = select((real4)(0.0), eb * (c * ph.a - qh.a) / lp * sinv, ok);                          \
    gb.a = select((real4)(0.0), eb * (c * qh.a - ph.a) / lq * sinv, ok);
        CURV_GRAD(x)
        CURV_GRAD(y)
        CURV_GRAD(z)
#undef CURV_GRAD
        vstore4(convert_int4(ok & (Cc < active_curv)) & (int4)(1), 0, ract + nv + i);
        store_rows4(ga, rgrad, nv + i);
        store_rows4(gb, cgq, i);
        vm4 = fmax(vm4, select((real4)(0.0), -Cc, -Cc > 0.0));
        i += 4;
    }
    vm = fmax(vm, fmax(fmax(vm4.s0, vm4.s1), fmax(vm4.s2, vm4.s3)));
#else
    for (; i < end; i++)
        vm = fmax(vm, chain_rows_at(i, x, next, prev, comp, ebar, lim, nv, active_curv, rC, rgrad, ract,
                                    cgq, cdeb));
#endif
    vmax[get_global_id(0)] = vm;
}

inline real pair_distance(__global const real *x, __global const int *next, int a, int b)
{
    real ss, tt;
    return tr_segment_distance(vload3(a, x), vload3(next[a], x), vload3(b, x), vload3(next[b], x),
                               &ss, &tt);
}

/* The pair is a local minimum of the distance along both strands (backend.h):
 * no neighbouring edge pair, sharing no vertex, is strictly closer. The
 * neighbours are k = 0, 1: (prev a, b), (next a, b); k = 2, 3: (a, prev b),
 * (a, next b), measured in that argument order as the reference does. Where
 * that neighbour is itself a listed pair in the same order (nbr[4 p + k],
 * pairs_neighbours) its distance is the one rows_strut has just stored in
 * dist, the same bits; else it is measured here. Measuring all four each
 * time was half of rows_strut's time (PoCL, tight trefoil, N = 10^5). */
inline int strut_local_min(__global const real *x, __global const int *next,
                           __global const int *prev, __global const real *dist,
                           __global const int *nbr, int p, int a, int b, real d)
{
    for (int k = 0; k < 4; k++) {
        int me = k < 2 ? a : b, other = k < 2 ? b : a;
        int nb = (k & 1) == 0 ? prev[me] : next[me];
        if (nb < 0 || next[nb] < 0 || nb == other)
            continue;
        if (next[nb] == other || next[other] == nb)
            continue;
        int q = nbr[4 * p + k];
        real dn = q >= 0  ? dist[q]
                  : k < 2 ? pair_distance(x, next, nb, other)
                          : pair_distance(x, next, other, nb);
        if (dn < d)
            return 0;
    }
    return 1;
}

/* The pairs' neighbours in the list (strut_local_min): nbr[4 p + k] = the
 * index of pair (prev a, b), (next a, b), (a, prev b) or (a, next b) for
 * k = 0 .. 3 where the list holds it in that order, else -1. Fixed while the
 * list is, so built once per search and used by every row evaluation. One
 * item per edge a walks a's partners b > a in ascending order and, beside
 * them, the partner lists of edges prev a and next a (sorted too, so each
 * pointer only moves forward); (a, b +- 1) is next to b in a's own list
 * unless b's ring wraps there, then a binary search finds it. */
inline int partner_at(__global const int *l, int i, int j, int want)
{
    while (i < j) { /* the first entry >= want in l[i .. j) */
        int mid = (i + j) / 2;
        if (l[mid] < want)
            i = mid + 1;
        else
            j = mid;
    }
    return i;
}

__kernel void pairs_neighbours(__global const int *list, __global const int *loff,
                               __global const int *count, __global const int *first,
                               __global const int *off, __global const int *next,
                               __global const int *prev, const int nv, __global int *nbr)
{
    TR_ITEMS(a, nv) {
        __global const int *l = list + loff[a];
        int f = first[a], m = count[a];
        int na[2] = {prev[a], next[a]}, at[2];
        for (int k = 0; k < 2; k++)
            at[k] = na[k] >= 0 ? first[na[k]] : 0;
        for (int j = f; j < m; j++) {
            int b = l[j], p = off[a] + j - f;
            for (int k = 0; k < 2; k++) { /* (nb, b), nb = prev a, next a */
                int nb = na[k], q = -1;
                if (nb >= 0 && nb < b) {
                    __global const int *ln = list + loff[nb];
                    while (at[k] < count[nb] && ln[at[k]] < b)
                        at[k]++;
                    if (at[k] < count[nb] && ln[at[k]] == b)
                        q = off[nb] + at[k] - first[nb];
                }
                nbr[4 * p + k] = q;
            }
            for (int k = 2; k < 4; k++) { /* (a, nb), nb = prev b, next b */
                int nb = k == 2 ? prev[b] : next[b], q = -1;
                if (nb > a) {
                    int i = nb < b ? j - 1 : j + 1;
                    if (!(i >= f && i < m && l[i] == nb))
                        i = partner_at(l, f, m, nb);
                    if (i < m && l[i] == nb)
                        q = off[a] + i - f;
                }
                nbr[4 * p + k] = q;
            }
        }
    }
}

/* Strut rows in the band that are not local minima become inactive (after
 * rows_strut has stored every pair's distance). */
__kernel void rows_strut_min(__global const real *x, __global const int *next,
                             __global const int *prev, __global const int *pa,
                             __global const int *pb, __global const real *dist,
                             __global const int *nbr, const int nv, const int np,
                             __global int *ract)
{
    TR_ITEMS(p, np) {
        int r = 2 * nv + p;
        if (ract[r] && !strut_local_min(x, next, prev, dist, nbr, p, pa[p], pb[p], dist[p]))
            ract[r] = 0;
    }
}

/* Strut row 2 nv + p for candidate pair p = (a, b): C = d - strut_dist,
 * gradient n split over the four vertices by the closest-point parameters;
 * active in the band (and, after rows_strut_min, only at local distance
 * minima); dist[p] = d. */
__kernel void rows_strut(__global const real *x, __global const int *next,
                         __global const int *prev, __global const int *pa,
                         __global const int *pb, const int nv, const int np,
                         const real strut_dist, const real active_strut, __global real *rC,
                         __global real *rgrad, __global int *ract, __global real *rs,
                         __global real *rt, __global real *dist, __global real *vmax,
                         const int voff)
{
    real vm = 0.0;
    TR_ITEMS(p, np) {
        int r = 2 * nv + p, a = pa[p], b = pb[p];
        real3 p0 = vload3(a, x), p1 = vload3(next[a], x), q0 = vload3(b, x), q1 = vload3(next[b], x);
        real ss, tt;
        real d = tr_segment_distance(p0, p1, q0, q1, &ss, &tt);
        real3 n = ((p0 + ss * (p1 - p0)) - (q0 + tt * (q1 - q0))) / d;
        vstore3(n, r, rgrad);
        rs[p] = ss;
        rt[p] = tt;
        real C = d - strut_dist;
        rC[r] = C;
        dist[p] = d;
        ract[r] = C < active_strut; /* and a local minimum: rows_strut_min */
        vm = fmax(vm, -C > 0.0 ? -C : 0.0);
    }
    vmax[voff + get_global_id(0)] = vm;
}

/* The CG's row list (backend.h: its sums skip inactive rows, which hold
 * exact zeros): positions l < nfix (= 2 nv, the edge and curvature rows)
 * are those rows, then the active strut rows in list order (act, built
 * once per solve by act_count / act_scan / act_write). The CG's vectors
 * (y, r, p, q, z, b) are stored by position l, compactly: on a tight curve
 * most listed struts are inactive (3.7 million rows, ~10^5 active, at
 * N = 10^5), and every CG iteration's vector operations would otherwise
 * touch a cache line per active strut scattered over the whole list. The
 * rows' own data (rgrad, ract, rC, pdiag; rs, rt, pa, pb by pair) stay
 * indexed by row r = row_of(l). */
inline int row_of(int l, int nfix, __global const int *act)
{
    return l < nfix ? l : nfix + act[l - nfix];
}

/* b, and the CG start y = 0, r = p = b, over the row list. */
__kernel void cg_init(__global const real *rC, __global const int *ract, const int nv,
                      __global const int *act, const int nl, __global real *b, __global real *y,
                      __global real *r, __global real *p)
{
    TR_ITEMS(l, nl) {
        int k = row_of(l, 2 * nv, act);
        real v = !ract[k] ? 0.0 : (k < nv ? -rC[k] : -fmin(rC[k], 0.0));
        b[l] = v;
        y[l] = 0.0;
        r[l] = v;
        p[l] = v;
    }
}

/* Each vertex's active strut entries, taken once per CG solve (the active
 * set is fixed during it), with what jt_vertex needs of each: the strut's
 * position in the row list, the weight c of the vertex in the strut and the
 * strut's direction n. jt_vertex then reads them in sequence instead of
 * gathering rs, rt and rgrad out of arrays over all listed pairs.
 *
 * They are built from the active struts alone (nact of them in the row list,
 * about 10^5 against 3.7 million listed pairs on a tight trefoil at
 * N = 10^5), not by walking every vertex's adjacency over all listed pairs:
 * adj_active_count counts the four entries of each active strut per vertex
 * (atomic increments on ints), a scan gives the offsets aaoff, and
 * adj_active_write puts each entry in a free slot of its vertex's row
 * (atomic again, so in no fixed order); adj_active_sort then orders every row
 * by row list position, which is the order of the pairs in the list and so
 * the reference's order of summation (a vertex is in a strut only once: the
 * index gap keeps a strut's four vertices apart). Rows are short, a few
 * active struts per vertex, so the insertion sort costs little. */
__kernel void adj_active_count(__global const int *act, __global const int *pa,
                               __global const int *pb, __global const int *next,
                               const int nact, __global int *aadjn)
{
    TR_ITEMS(m, nact) {
        int p = act[m], a = pa[p], b = pb[p];
        atomic_inc(aadjn + a);
        atomic_inc(aadjn + next[a]);
        atomic_inc(aadjn + b);
        atomic_inc(aadjn + next[b]);
    }
}

/* fill: zeros on entry, the rows' lengths on exit. */
__kernel void adj_active_write(__global const int *act, __global const int *pa,
                               __global const int *pb, __global const int *next,
                               __global const real *rs, __global const real *rt,
                               __global const real *rgrad, const int nv, const int nact,
                               __global const int *aaoff, __global int *fill,
                               __global int *aadj, __global real *acoef, __global real *agrad)
{
    TR_ITEMS(m, nact) {
        int p = act[m], a = pa[p], b = pb[p];
        real ss = rs[p], tt = rt[p];
        real3 n = vload3(2 * nv + p, rgrad);
        int v[4] = {a, next[a], b, next[b]};
        real c[4] = {1.0 - ss, ss, -(1.0 - tt), -tt};
        for (int k = 0; k < 4; k++) {
            int o = aaoff[v[k]] + atomic_inc(fill + v[k]);
            aadj[o] = 2 * nv + m;
            acoef[o] = c[k];
            vstore3(n, o, agrad);
        }
    }
}

__kernel void adj_active_sort(__global const int *aaoff, const int nv, __global int *aadj,
                              __global real *acoef, __global real *agrad)
{
    TR_ITEMS(i, nv) {
        for (int k = aaoff[i] + 1; k < aaoff[i + 1]; k++) {
            int key = aadj[k], q = k;
            real c = acoef[k];
            real3 n = vload3(k, agrad);
            while (q > aaoff[i] && aadj[q - 1] > key) {
                aadj[q] = aadj[q - 1];
                acoef[q] = acoef[q - 1];
                vstore3(vload3(q - 1, agrad), q, agrad);
                q--;
            }
            aadj[q] = key;
            acoef[q] = c;
            vstore3(n, q, agrad);
        }
    }
}


/* What the four-at-a-time paths of jt_vertex and j_rows need of vertices
 * 4b .. 4b + 3, fixed for a solve (the active set and the contact
 * adjacency are): JT_RUN, they lie inside one run of the chain (chain_run4
 * with prev) with their edge rows and the curvature rows of 4b - 1 .. 4b + 4
 * active and no active struts; JT_FREE, none is constrained (cidx < 0);
 * JR_RUN, inside one run with their own edge and curvature rows active.
 * One byte per block read instead of five ints per vertex in every CG
 * iteration. Run once per solve (solve_rows), on CPU devices only. */
#define JT_RUN 1
#define JT_FREE 2
#define JR_RUN 4
__kernel void block_flags(__global const int *ract, __global const int *next,
                          __global const int *prev, __global const int *aadjn,
                          __global const int *cidx, const int nv, __global uchar *flags)
{
    TR_ITEMS(b, nv / 4) {
        int i = 4 * b;
        uchar f = 0;
        if (chain_run4(i, next, prev)) {
            bool edges = active4(ract, i), curv = active4(ract, nv + i);
            if (edges && curv && ract[nv + i - 1] && ract[nv + i + 4] &&
                all(vload4(0, aadjn + i) == 0))
                f |= JT_RUN;
            if (edges && curv)
                f |= JR_RUN;
        }
        if (all(vload4(0, cidx + i) < 0))
            f |= JT_FREE;
        flags[b] = f;
    }
}

/* dx_i = P_i (sum over rows y_r dC_r/dx_i) at one vertex, in the order
 * backend.h fixes; y by row list position (the chain rows' positions are
 * their rows). jt_vertex's and jjt_rows' scalar path. */
inline real3 jt_at(int i, __global const real *y, __global const real *rgrad,
                   __global const real *cgq, __global const int *ract, __global const int *next,
                   __global const int *prev, __global const int *aadj, __global const int *aadjn,
                   __global const int *aaoff, __global const real *acoef,
                   __global const real *agrad, __global const int *cidx, __global const real *cst,
                   const int nv)
{
    real3 g = (real3)(0.0);
    int pv = prev[i], nx = next[i];
    if (pv >= 0)
        g = g + y[pv] * vload3(pv, rgrad);
    if (nx >= 0)
        g = g + (-y[i]) * vload3(i, rgrad);
    if (pv >= 0 && ract[nv + pv])
        g = g + (-y[nv + pv]) * vload3(pv, cgq);
    if (ract[nv + i]) {
        g = g + y[nv + i] * vload3(i, cgq);
        g = g + (-y[nv + i]) * vload3(nv + i, rgrad);
    }
    if (nx >= 0 && ract[nv + nx])
        g = g + y[nv + nx] * vload3(nv + nx, rgrad);
    for (int k = aaoff[i], e = aaoff[i] + aadjn[i]; k < e; k++)
        g = g + (acoef[k] * y[aadj[k]]) * vload3(k, agrad);
    return tr_project_motion(cidx, cst, i, g);
}
#define JT_AT(i) jt_at(i, y, rgrad, cgq, ract, next, prev, aadj, aadjn, aaoff, acoef, agrad, cidx, cst, nv)

#ifdef TR_BLOCK_ITEMS
/* The unprojected sums of jt_at at the vertices i .. i + 3 of a JT_RUN
 * block (block_flags), in double4 lanes: jt_at's terms in jt_at's order,
 * so the same bits. */
inline rows4 jt_run4(int i, __global const real *y, __global const real *rgrad,
                     __global const real *cgq, const int nv)
{
    real4 yp = vload4(0, y + i - 1), yi = vload4(0, y + i);
    real4 cp = vload4(0, y + nv + i - 1), ci = vload4(0, y + nv + i), cn = vload4(0, y + nv + i + 1);
    rows4 rp = load_rows4(rgrad, i - 1), ri = load_rows4(rgrad, i);
    rows4 qp = load_rows4(cgq, i - 1), qi = load_rows4(cgq, i);
    rows4 ki = load_rows4(rgrad, nv + i), kn = load_rows4(rgrad, nv + i + 1);
    rows4 g;
#define JT_LANES(c)                                                                        \
    g.c = (real4)(0.0) + yp * rp.c;                                                       \
    g.c = g.c + (-yi) * ri.c;                                                             \
    g.c = g.c + (-cp) * qp.c;                                                             \
    g.c = g.c + ci * qi.c;                                                                \
    g.c = g.c + (-ci) * ki.c;                                                             \
    g.c = g.c + cn * kn.c;
    JT_LANES(x)
    JT_LANES(y)
    JT_LANES(z)
#undef JT_LANES
    return g;
}

inline real lane4(real4 v, int k) { return k == 0 ? v.s0 : k == 1 ? v.s1 : k == 2 ? v.s2 : v.s3; }

/* Lane k of g, projected (a constrained vertex's P_i). */
inline real3 jt_lane_projected(rows4 g, int k, __global const int *cidx, __global const real *cst,
                               int i)
{
    return tr_project_motion(cidx, cst, i + k, (real3)(lane4(g.x, k), lane4(g.y, k), lane4(g.z, k)));
}
#endif

#ifdef TR_BLOCK_ITEMS
/* The ebar sums' running state of a jjt_rows or jt_vertex item. */
typedef struct {
    real esum;
    real4 esum4;
    int kc;
} ebar_run;

/* An item's running sums over its vertices [i0, i1), and 0 as its share of
 * the components it has no vertex of. */
inline ebar_run ebar_open(int i0, int i1, __global const int *comp, int ncomp, __global real *ebar_part,
                          int G, int item)
{
    ebar_run e = {0.0, (real4)(0.0), i0 < i1 ? comp[i0] : ncomp};
    int klast = i0 < i1 ? comp[i1 - 1] : -1;
    for (int k = 0; k < ncomp; k++)
        if (k < e.kc || k > klast)
            ebar_part[k * G + item] = 0.0;
    return e;
}

/* Before adding vertex i's terms: close the item's share of component kc
 * when i starts another. */
inline void ebar_next(ebar_run *e, int i, __global const int *comp, __global real *ebar_part, int G,
                      int item)
{
    if (comp[i] != e->kc) {
        ebar_part[e->kc * G + item] = e->esum + ((e->esum4.s0 + e->esum4.s1) + (e->esum4.s2 + e->esum4.s3));
        e->esum = 0.0;
        e->esum4 = (real4)(0.0);
        e->kc = comp[i];
    }
}

/* Vertex i's terms, off the lanes: its edge row's -y_i and its curvature
 * row's cdeb_i y_(nv+i), each if active (jt_ebar_partial's terms). */
inline void ebar_add(ebar_run *e, int i, __global const int *ract, __global const real *cdeb,
                     __global const real *y, int nv)
{
    if (ract[i])
        e->esum += -y[i];
    if (ract[nv + i])
        e->esum += cdeb[i] * y[nv + i];
}

/* The same for the four vertices of a JT_RUN block, in lanes (their rows
 * are active). */
inline void ebar_add4(ebar_run *e, int i, __global const real *cdeb, __global const real *y, int nv)
{
    e->esum4 += -vload4(0, y + i);
    e->esum4 += vload4(0, cdeb + i) * vload4(0, y + nv + i);
}

/* The item's share of its last component. */
inline void ebar_close(ebar_run *e, int ncomp, __global real *ebar_part, int G, int item)
{
    if (e->kc < ncomp)
        ebar_part[e->kc * G + item] = e->esum + ((e->esum4.s0 + e->esum4.s1) + (e->esum4.s2 + e->esum4.s3));
}

#endif

/* dx_i = jt_at for every vertex. On CPU devices four consecutive vertices
 * inside a run of the chain, with all their curvature rows active and no
 * struts, go at once in double4 lanes (jt_run4); and the
 * items also sum jt_ebar_partial's terms of their vertices' edge and
 * curvature rows, which they read anyway, into ebar_part[k G + g] for
 * component k and item g of G (0 for components the item has no vertex
 * of), so that the ebar sums cost no pass of their own. */
__kernel void jt_vertex(__global const real *y, __global const real *rgrad,
                        __global const real *cgq, __global const int *ract, __global const int *next,
                        __global const int *prev, __global const int *aadj,
                        __global const int *aadjn, __global const int *aaoff,
                        __global const real *acoef, __global const real *agrad,
                        __global const int *cidx, __global const real *cst, const int nv, __global real *dx,
                        __global const real *cdeb, __global const int *comp, const int ncomp,
                        __global real *ebar_part, __global const uchar *flags)
{
#ifdef TR_BLOCK_ITEMS
    int i = tr_items_first4(nv), end = tr_items_end4(nv);
    int G = get_global_size(0), item = get_global_id(0);
    ebar_run e = ebar_open(i, end, comp, ncomp, ebar_part, G, item);
#else
    int i = tr_items_first(nv), end = tr_items_end(nv);
#endif
    while (i < end) {
#ifdef TR_BLOCK_ITEMS
        ebar_next(&e, i, comp, ebar_part, G, item);
        uchar f = (i & 3) == 0 && i + 4 <= end ? flags[i >> 2] : 0;
        if (f & JT_RUN) {
            rows4 g = jt_run4(i, y, rgrad, cgq, nv);
            ebar_add4(&e, i, cdeb, y, nv);
            if (f & JT_FREE) {
                store_rows4(g, dx, i);
            } else {
                for (int k = 0; k < 4; k++)
                    vstore3(jt_lane_projected(g, k, cidx, cst, i), i + k, dx);
            }
            i += 4;
            continue;
        }
#endif
        vstore3(JT_AT(i), i, dx);
#ifdef TR_BLOCK_ITEMS
        ebar_add(&e, i, ract, cdeb, y, nv);
#endif
        i++;
    }
#ifdef TR_BLOCK_ITEMS
    ebar_close(&e, ncomp, ebar_part, G, item);
#endif
}

/* debar_k = (sum over rows of component k of y_r dC_r/debar_k) / (w ne_k),
 * in two stages so that a long component is summed by many work-groups (one
 * work-group per component took 14 ms per call at N = 10^6 on an H100, a
 * tenth of the step): work-group k G + g sums slice g of component k's rows
 * (partial sums over GROUP_SLICE_FOR, then a tree) into part[k G + g]
 * (a GPU's first stage: on CPU devices the items of jt_vertex and jjt_rows
 * sum their own vertices' terms instead) ... */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void jt_ebar_partial(__global const real *y, __global const int *ract,
                     __global const int *start, __global const real *cdeb, const int nv,
                     const int groups_per_comp, __global real *part)
{
    __local real s[TR_LOCAL_SIZE];
    int G = groups_per_comp, k = get_group_id(0) / G, g = get_group_id(0) % G,
        l = get_local_id(0);
    /* group g takes the g-th of G contiguous slices of the component, its
     * items sharing it (GROUP_SLICE_FOR): interleaving the groups' items over the
     * whole component (a stride of G x 64) ran 3.5 ms a call at N = 10^6 on
     * PoCL, where the rows no longer fit in cache */
    int st = start[k], len = start[k + 1] - st;
    int lo = st + (int)((long)len * g / G), hi = st + (int)((long)len * (g + 1) / G);
    real sum = 0.0;
    GROUP_SLICE_FOR(a, lo, hi) {
        if (ract[a])
            sum += -y[a];
        if (ract[nv + a])
            sum += cdeb[a] * y[nv + a];
    }
    s[l] = sum;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(tr_add, s, l)
    if (l == 0)
        part[get_group_id(0)] = s[0];
}

/* ... and work-group k adds component k's G partial sums. With pq (jjt_rows'
 * CG, else NULL) it also puts debar_k times that sum, the debar term's share
 * of p . q, at pq[pq_off + k]. */
__kernel __attribute__((reqd_work_group_size(TR_LOCAL_SIZE, 1, 1)))
void jt_ebar(__global const real *part, __global const int *ne, const int groups_per_comp,
             const real ebar_weight, __global real *debar, __global real *pq, const int pq_off)
{
    __local real s[TR_LOCAL_SIZE];
    int G = groups_per_comp, k = get_group_id(0), l = get_local_id(0);
    real sum = 0.0;
    for (int g = l; g < G; g += TR_LOCAL_SIZE)
        sum += part[k * G + g];
    s[l] = sum;
    barrier(CLK_LOCAL_MEM_FENCE);
    TREE(tr_add, s, l)
    if (l == 0) {
        real d = ne[k] ? s[0] / (ebar_weight * (real)ne[k]) : 0.0;
        debar[k] = d;
        if (pq)
            pq[pq_off + k] = d * s[0];
    }
}

/* Active strut rows per block of bsize list entries. */
__kernel void act_count(__global const int *ract, const int nv, const int np, const int bsize,
                        const int nblocks, __global int *counts)
{
    TR_ITEMS(b, nblocks) {
        int c = 0, hi = min(np, (b + 1) * bsize);
        for (int p = b * bsize; p < hi; p++)
            c += ract[2 * nv + p] != 0;
        counts[b] = c;
    }
}

/* One item: exclusive prefix sums of the block counts; counts[nblocks] = total. */
__kernel void act_scan(const int nblocks, __global int *counts)
{
    int sum = 0;
    for (int b = 0; b < nblocks; b++) {
        int c = counts[b];
        counts[b] = sum;
        sum += c;
    }
    counts[nblocks] = sum;
}

/* act[l] = the l-th active strut row's pair index, in list order. */
__kernel void act_write(__global const int *ract, const int nv, const int np, const int bsize,
                        const int nblocks, __global const int *counts, __global int *act)
{
    TR_ITEMS(b, nblocks) {
        int o = counts[b], hi = min(np, (b + 1) * bsize);
        for (int p = b * bsize; p < hi; p++)
            if (ract[2 * nv + p])
                act[o++] = p;
    }
}

/* What j_rows needs of the l-th active strut row (pair p = act[l]), in row
 * list order: its vertices a, b (sab[2 l], sab[2 l + 1]) and s, t and the
 * strut direction n (sw[5 l ..]). Gathered once per solve, so that j_rows,
 * run in every CG iteration, reads them in sequence instead of from arrays
 * over all listed pairs (millions on a tight curve, a cache miss each). */
__kernel void act_gather(__global const int *act, __global const int *pa, __global const int *pb,
                         __global const real *rs, __global const real *rt,
                         __global const real *rgrad, const int nv, const int nact,
                         __global int *sab, __global real *sw)
{
    TR_ITEMS(l, nact) {
        int p = act[l];
        real3 n = vload3(2 * nv + p, rgrad);
        sab[2 * l] = pa[p];
        sab[2 * l + 1] = pb[p];
        sw[5 * l] = rs[p];
        sw[5 * l + 1] = rt[p];
        sw[5 * l + 2] = n.x;
        sw[5 * l + 3] = n.y;
        sw[5 * l + 4] = n.z;
    }
}

/* dC_r/dx . dx of vertex i's edge row (dx at i and next i) and of its
 * curvature row (dx at prev i, i and next i): the operator's rows without
 * their reg and debar terms, for j_row and for jjt_rows, which takes dx
 * from its window instead of global memory. */
inline real edge_row_dx(int i, __global const real *rgrad, real3 di, real3 dn)
{
    return tr_dot3(vload3(i, rgrad), dn - di);
}

inline real curv_row_dx(int i, __global const real *rgrad, __global const real *cgq, int nv,
                        real3 dp, real3 di, real3 dn)
{
    real3 ga = vload3(nv + i, rgrad), gb = vload3(i, cgq);
    real3 t = ga * dp + (gb - ga) * di - gb * dn;
    real v = 0.0;
    v += t.x;
    v += t.y;
    v += t.z;
    return v;
}

#ifdef TR_BLOCK_ITEMS
/* The same for the vertices i .. i + 3 of a JR_RUN block in double4 lanes
 * (dx at i - 1 .., i .. and i + 1 .. as dp, di, dn): the same arithmetic
 * per lane, so the same bits. */
inline void chain_rows4_dx(int i, __global const real *rgrad, __global const real *cgq, int nv,
                           rows4 dp, rows4 di, rows4 dn, real4 *edge, real4 *curv)
{
    rows4 g = load_rows4(rgrad, i);
    *edge = g.x * (dn.x - di.x) + g.y * (dn.y - di.y) + g.z * (dn.z - di.z);
    rows4 ga = load_rows4(rgrad, nv + i), gb = load_rows4(cgq, i);
    real4 v = (real4)(0.0);
    v += ga.x * dp.x + (gb.x - ga.x) * di.x - gb.x * dn.x;
    v += ga.y * dp.y + (gb.y - ga.y) * di.y - gb.y * dn.y;
    v += ga.z * dp.z + (gb.z - ga.z) * di.z - gb.z * dn.z;
    *curv = v;
}
#endif

/* Row-list position l of J (dx, debar) + reg y (j_rows): out[l], and
 * y_l out_l for the p . q sum. */
inline real j_row(int l, __global const real *dx, __global const real *debar,
                  __global const real *cdeb, __global const real *rgrad,
                  __global const real *cgq, __global const int *ract,
                  __global const int *next, __global const int *prev,
                  __global const int *comp, __global const int *sab,
                  __global const real *sw, __global const real *y, const int nv,
                  const real reg, __global const int *act, __global real *out)
{
    int r = row_of(l, 2 * nv, act);
    real o = 0.0;
    if (!ract[r]) {
        out[l] = 0.0;
    } else if (r < nv) {
        real e = edge_row_dx(r, rgrad, vload3(r, dx), vload3(next[r], dx));
        out[l] = o = (e + reg * y[l]) - debar[comp[r]];
    } else if (r < 2 * nv) {
        int i = r - nv;
        real v = curv_row_dx(i, rgrad, cgq, nv, vload3(prev[i], dx), vload3(i, dx), vload3(next[i], dx));
        out[l] = o = (v + reg * y[l]) + cdeb[i] * debar[comp[i]];
    } else { /* an active strut row: act_gather's copy */
        int m = l - 2 * nv, a = sab[2 * m], b = sab[2 * m + 1];
        real ss = sw[5 * m], tt = sw[5 * m + 1];
        real3 n = (real3)(sw[5 * m + 2], sw[5 * m + 3], sw[5 * m + 4]);
        real3 d = (1.0 - ss) * vload3(a, dx) + ss * vload3(next[a], dx) -
                  (1.0 - tt) * vload3(b, dx) - tt * vload3(next[b], dx);
        out[l] = o = tr_dot3(n, d) + reg * y[l];
    }
    return y[l] * o;
}

/* out_r = (dC_r/dx . dx + reg y_r) + dC_r/debar . debar on active rows, else 0,
 * y and out by row list position l (row_of); the item's share of y . out to
 * yout (TR_ITEM_PARTIAL: the CG's p . q).
 * On a GPU one item per position l. On CPU devices (TR_BLOCK_ITEMS) the
 * items walk units instead: unit i < nv is vertex i's edge row and
 * curvature row, both of which read dx at i and its neighbours, so that
 * dx is read once (taking the edge rows, then the curvature rows, read it
 * twice, and at N = 10^6, where it is not in the cache, from memory both
 * times); unit nv + m is strut row 2 nv + m. Four consecutive vertices
 * inside one run of the chain with all eight rows active go at once in
 * double4 lanes: the same arithmetic per lane as j_row, so the same out;
 * p . q is summed in four lanes, whose order differs from the scalar sum's
 * in the last bits. jrows_units (host) is the unit count. */
__kernel void j_rows(__global const real *dx, __global const real *debar,
                     __global const real *cdeb, __global const real *rgrad,
                     __global const real *cgq, __global const int *ract,
                     __global const int *next, __global const int *prev,
                     __global const int *comp, __global const int *sab,
                     __global const real *sw, __global const real *y, const int nv,
                     const real reg, __global const int *act, const int nl,
                     __global real *out, __global real *yout, __global const uchar *flags)
{
    real sum = 0.0;
#define J_ROW(l) j_row(l, dx, debar, cdeb, rgrad, cgq, ract, next, prev, comp, sab, sw, y, nv, reg, act, out)
#ifdef TR_BLOCK_ITEMS
    int nu = nl - nv, u = tr_items_first4(nu), end = tr_items_end4(nu);
    real4 sum4 = (real4)(0.0);
    while (u < end) {
        if ((u & 3) == 0 && u + 4 <= min(end, nv) && (flags[u >> 2] & JR_RUN)) {
            int i = u;
            real4 e, v;
            chain_rows4_dx(i, rgrad, cgq, nv, load_rows4(dx, i - 1), load_rows4(dx, i),
                           load_rows4(dx, i + 1), &e, &v);
            real4 ye = vload4(0, y + i);
            real4 oe = (e + reg * ye) - debar[comp[i]];
            vstore4(oe, 0, out + i);
            real4 yc = vload4(0, y + nv + i);
            real4 oc = (v + reg * yc) + vload4(0, cdeb + i) * debar[comp[i]];
            vstore4(oc, 0, out + nv + i);
            sum4 += ye * oe;
            sum4 += yc * oc;
            u += 4;
            continue;
        }
        if (u < nv) {
            sum += J_ROW(u);
            sum += J_ROW(nv + u);
        } else {
            sum += J_ROW(nv + u);
        }
        u++;
    }
    sum += (sum4.s0 + sum4.s1) + (sum4.s2 + sum4.s3);
#else
    TR_ITEMS(l, nl)
        sum += J_ROW(l);
#endif
#undef J_ROW
    TR_ITEM_PARTIAL(yout, sum);
}

/* jjt_rows' private window: the dx of a tile of JJ_TILE vertices, the
 * four before it and the four after it, as x, y and z arrays (the lanes
 * load them as they are, without load_rows4's shuffles). Small tiles keep
 * the two halves' loads and arithmetic interleaved: at N = 10^6 (rows not in
 * cache) 64-vertex tiles ran the pass at 4.4 ms, 16-vertex ones at 3.1. */
#define JJ_TILE 16
#define JJ_WINDOW (JJ_TILE + 8)

#ifdef TR_BLOCK_ITEMS
/* dx of the item's own vertices [a, b) into the window (w: the window's
 * first vertex), with their ebar terms: jt_vertex's loop, four at a time on
 * JT_RUN blocks that end by i1 (jt_vertex's blocks), and dx to global
 * memory at the ends of active struts, which j_struts reads. */
inline void jjt_span(int a, int b, int i1, int w, real *tx, real *ty, real *tz, ebar_run *e,
                     __global const real *y, __global const real *rgrad, __global const real *cgq,
                     __global const int *ract, __global const int *next, __global const int *prev,
                     __global const int *aadj, __global const int *aadjn, __global const int *aaoff,
                     __global const real *acoef, __global const real *agrad,
                     __global const int *cidx, __global const real *cst, const int nv,
                     __global real *dx, __global const real *cdeb, __global const int *comp,
                     __global real *ebar_part, __global const uchar *flags, int G, int item)
{
    for (int i = a; i < b;) {
        ebar_next(e, i, comp, ebar_part, G, item);
        uchar f = (i & 3) == 0 && i + 4 <= i1 ? flags[i >> 2] : 0;
        if (f & JT_RUN) {
            rows4 g = jt_run4(i, y, rgrad, cgq, nv);
            ebar_add4(e, i, cdeb, y, nv);
            if (!(f & JT_FREE)) {
                for (int k = 0; k < 4; k++) {
                    real3 v = jt_lane_projected(g, k, cidx, cst, i);
                    tx[i + k - w] = v.x;
                    ty[i + k - w] = v.y;
                    tz[i + k - w] = v.z;
                }
            } else {
                vstore4(g.x, 0, tx + i - w);
                vstore4(g.y, 0, ty + i - w);
                vstore4(g.z, 0, tz + i - w);
            }
            i += 4;
            continue;
        }
        real3 g = JT_AT(i);
        tx[i - w] = g.x;
        ty[i - w] = g.y;
        tz[i - w] = g.z;
        if (aadjn[i])
            vstore3(g, i, dx);
        ebar_add(e, i, ract, cdeb, y, nv);
        i++;
    }
}
#endif

/* One CG iteration's q = J (J^T p) + reg p on the chain rows, for CPU
 * devices: jt_vertex and j_rows' vertex units in one pass. Why: at
 * N = 10^6 the CG is bound by memory, and the two kernels moved dx out and
 * back (72 bytes a vertex) and read the rows' gradients twice (80 more).
 * Each item walks its vertices (jt_vertex's partition) a tile at a time:
 * dx up to the fourth vertex after the tile (the window holds the rest from
 * the tile before; jt_run4 on JT_RUN blocks, jt_at elsewhere: the same bits
 * as jt_vertex, and jt_vertex's ebar partial sums), then the tile's edge
 * and curvature rows from the window
 * (a neighbour outside it, across a closed component's seam, is worked out
 * again by jt_at); the window then slides by the tile. What cannot be done
 * in the pass:
 * - the debar term, which needs every item's ebar sums: out holds
 *   dC_r/dx . dx + reg p_r, and cg_r adds dC_r/debar . debar (backend.h
 *   puts that term last for this), while jt_ebar puts the debar term's
 *   share of p . q, debar_k (sum_k), in yout after the items' shares;
 * - the strut rows, which read dx anywhere: j_struts, after this pass, from
 *   dx written here at the vertices with active struts (the only ones they
 *   read; a JT_RUN block has none). */
__kernel void jjt_rows(__global const real *y, __global const real *rgrad,
                       __global const real *cgq, __global const int *ract, __global const int *next,
                       __global const int *prev, __global const int *aadj,
                       __global const int *aadjn, __global const int *aaoff,
                       __global const real *acoef, __global const real *agrad,
                       __global const int *cidx, __global const real *cst, const int nv,
                       __global real *dx, __global const real *cdeb, __global const int *comp,
                       const int ncomp, __global real *ebar_part, __global const uchar *flags,
                       const real reg, __global real *out, __global real *yout)
{
#ifdef TR_BLOCK_ITEMS
    real tx[JJ_WINDOW], ty[JJ_WINDOW], tz[JJ_WINDOW];
    int i0 = tr_items_first4(nv), i1 = tr_items_end4(nv);
    int G = get_global_size(0), item = get_global_id(0);
    ebar_run e = ebar_open(i0, i1, comp, ncomp, ebar_part, G, item);
    real sum = 0.0;
    real4 sum4 = (real4)(0.0);
#define JJ_SPAN(a, b)                                                                           \
    jjt_span(a, b, i1, w, tx, ty, tz, &e, y, rgrad, cgq, ract, next, prev, aadj, aadjn, aaoff,  \
             acoef, agrad, cidx, cst, nv, dx, cdeb, comp, ebar_part, flags, G, item)
#define JJ_HALO(i)                                                                              \
    do {                                                                                        \
        real3 h_ = JT_AT(i);                                                                    \
        tx[(i) - w] = h_.x;                                                                     \
        ty[(i) - w] = h_.y;                                                                     \
        tz[(i) - w] = h_.z;                                                                     \
    } while (0)
    int w = i0 - 4; /* the window's first vertex: the tile's start less four */
    if (i0 < i1) {
        if (i0 > 0)
            JJ_HALO(i0 - 1);
        JJ_SPAN(i0, min(i0 + 4, i1));
    }
    for (int t0 = i0; t0 < i1; t0 += JJ_TILE) {
        int t1 = min(t0 + JJ_TILE, i1);
        /* dx on [t0 + 4, t1 + 4), the window's tail, so far as the item
         * owns it, and the next item's first vertex after the last tile */
        JJ_SPAN(min(t0 + 4, i1), min(t1 + 4, i1));
        if (t1 == i1 && i1 < nv)
            JJ_HALO(i1);
        /* the rows of [t0, t1): j_row's arithmetic less the debar term; the
         * window holds dx on [t0 - 1, t1] */
#define JJ_DX(v) ((v) >= t0 - 1 && (v) <= t1 ? (real3)(tx[(v) - w], ty[(v) - w], tz[(v) - w]) : JT_AT(v))
#define JJ_ROWS4(a) ((rows4){vload4(0, tx + (a) - w), vload4(0, ty + (a) - w), vload4(0, tz + (a) - w)})
        for (int i = t0; i < t1;) {
            if ((i & 3) == 0 && i + 4 <= t1 && (flags[i >> 2] & JR_RUN)) {
                real4 e, v;
                chain_rows4_dx(i, rgrad, cgq, nv, JJ_ROWS4(i - 1), JJ_ROWS4(i), JJ_ROWS4(i + 1), &e, &v);
                real4 ye = vload4(0, y + i);
                real4 oe = e + reg * ye;
                vstore4(oe, 0, out + i);
                real4 yc = vload4(0, y + nv + i);
                real4 oc = v + reg * yc;
                vstore4(oc, 0, out + nv + i);
                sum4 += ye * oe;
                sum4 += yc * oc;
                i += 4;
                continue;
            }
            real o = 0.0;
            if (ract[i])
                o = edge_row_dx(i, rgrad, JJ_DX(i), JJ_DX(next[i])) + reg * y[i];
            out[i] = o;
            sum += y[i] * o;
            o = 0.0;
            if (ract[nv + i])
                o = curv_row_dx(i, rgrad, cgq, nv, JJ_DX(prev[i]), JJ_DX(i), JJ_DX(next[i])) +
                    reg * y[nv + i];
            out[nv + i] = o;
            sum += y[nv + i] * o;
            i++;
        }
#undef JJ_DX
#undef JJ_ROWS4
        /* slide: [t1 - 4, t1 + 4) to the front, for the next tile (only a
         * full tile has one) */
        for (int k = 0; k < 8; k++) {
            tx[k] = tx[k + JJ_TILE];
            ty[k] = ty[k + JJ_TILE];
            tz[k] = tz[k + JJ_TILE];
        }
        w += JJ_TILE;
    }
#undef JJ_SPAN
#undef JJ_HALO
    ebar_close(&e, ncomp, ebar_part, G, item);
    yout[item] = sum + ((sum4.s0 + sum4.s1) + (sum4.s2 + sum4.s3));
#endif
}

/* The strut rows of j_rows after jjt_rows: row list positions 2 nv ..
 * nl - 1, the items' shares of p . q at yout[yoff + item]. */
__kernel void j_struts(__global const real *dx, __global const real *debar,
                       __global const real *cdeb, __global const real *rgrad,
                       __global const real *cgq, __global const int *ract,
                       __global const int *next, __global const int *prev,
                       __global const int *comp, __global const int *sab,
                       __global const real *sw, __global const real *y, const int nv,
                       const real reg, __global const int *act, const int nl,
                       __global real *out, __global real *yout, const int yoff)
{
    real sum = 0.0;
    TR_ITEMS(m, nl - 2 * nv)
        sum += j_row(2 * nv + m, dx, debar, cdeb, rgrad, cgq, ract, next, prev, comp, sab, sw, y, nv,
                     reg, act, out);
    yout[yoff + get_global_id(0)] = sum;
}

/* CG scalar updates: one item each. `done` turns the rest into no-ops.
 * alpha and beta are not kept: cg_r and cg_p work them out from the
 * dot products (every item the same quotient), and the bookkeeping of an
 * iteration waits for the next one's cg_top, so an iteration launches no
 * kernel of its own for them (on a CPU device or a GPU at N ~ 10^3 a step is
 * some hundreds of launches, and their cost, not the arithmetic, sets its
 * time). */
__kernel void cg_start(__global real *sc)
{
    sc[SC_RR0] = sc[SC_RR];
    sc[SC_DONE] = 0.0;
    sc[SC_ITERS] = 0.0;
}

/* Before iteration k (and once after the loop, with the loop's last k): the
 * end of iteration k - 1 (its r . z is the one the next beta divides by, and
 * it is counted), then the convergence test. */
__kernel void cg_top(__global real *sc, const int k)
{
    if (sc[SC_DONE] != 0.0)
        return;
    if (k > 0) {
        sc[SC_RZ] = sc[SC_RR1];
        sc[SC_ITERS] += 1.0;
    }
    if (sc[SC_RR] <= sc[SC_TOL2] * sc[SC_RR0])
        sc[SC_DONE] = 1.0;
}

/* The preconditioner's diagonal part at row-list position l >= nv (a
 * curvature or strut row) with residual rl: rl / pd, 0 when the row is
 * inactive (precond_diag, and cg_r inside the CG loop). */
inline real precond_diag_at(real rl, int l, int nv, __global const int *act,
                            __global const int *ract, __global const real *pd)
{
    int q = row_of(l, 2 * nv, act);
    return ract[q] ? rl / pd[q] : 0.0;
}

#ifdef TR_BLOCK_ITEMS
/* cg_r at row-list position l on a CPU device, where q lacks the chain
 * rows' debar term (jjt_rows): it is added here, in j_row's order. */
inline void cg_r_at(int l, __global real *r, __global const real *q, real alpha, __global const real *pd,
                    __global const int *ract, int nv, __global const int *act, __global real *z,
                    __global const real *debar, __global const real *cdeb,
                    __global const int *comp, real *rr, real *rz)
{
    real ql = q[l];
    if (l < nv && ract[l])
        ql = ql - debar[comp[l]];
    else if (l >= nv && l < 2 * nv && ract[l])
        ql = ql + cdeb[l - nv] * debar[comp[l - nv]];
    real v = r[l] - alpha * ql;
    r[l] = v;
    *rr += v * v;
    if (l >= nv) {
        real zl = precond_diag_at(v, l, nv, act, ract, pd);
        z[l] = zl;
        *rz += v * zl;
    }
}
#endif

/* r -= alpha q (alpha = r.z / p.q; y's alpha p is cg_p's, which reads p
 * anyway), the item's share of r . r
 * (0 once done: nothing reads it then), and z = r / pd on the curvature and
 * strut rows (precond_diag's part of the preconditioner, done here while r
 * is at hand; the edge rows' z is the edge block's), with those rows' share
 * of r . z in rz[item] (with the twisted edge block, whose kernels sum the
 * edge rows' share; rz is NULL otherwise).
 * On a GPU one item per row. On CPU devices q comes from jjt_rows and
 * j_struts, and the chain rows' debar term (debar, cdeb, comp) is added
 * here; the items walk j_rows' units (a vertex's edge and curvature row, or
 * a strut row), JR_RUN blocks (flags) four vertices at a time, the sums in
 * four lanes: with one running sum the loop waited on the adder (as
 * dot_slice4). */
__kernel void cg_r(__global real *r, __global const real *q, __global const real *sc, const int nl,
                    __global real *rr, __global const real *pd, __global const int *ract,
                    const int nv, __global const int *act, __global real *z, __global real *rz,
                    __global const real *debar, __global const real *cdeb,
                    __global const int *comp, __global const uchar *flags)
{
    real sum = 0.0, sumz = 0.0;
    if (sc[SC_DONE] == 0.0) {
        real alpha = sc[SC_RZ] / sc[SC_PQ];
#ifdef TR_BLOCK_ITEMS
        int nu = nl - nv, u = tr_items_first4(nu), end = tr_items_end4(nu);
        real4 sum4 = (real4)(0.0), sumz4 = (real4)(0.0);
        while (u < end) {
            if ((u & 3) == 0 && u + 4 <= min(end, nv) && (flags[u >> 2] & JR_RUN)) {
                real db = debar[comp[u]];
                real4 ve = vload4(0, r + u) - alpha * (vload4(0, q + u) - db);
                vstore4(ve, 0, r + u);
                real4 vc = vload4(0, r + nv + u) -
                           alpha * (vload4(0, q + nv + u) + vload4(0, cdeb + u) * db);
                vstore4(vc, 0, r + nv + u);
                real4 zc = vc / vload4(0, pd + nv + u);
                vstore4(zc, 0, z + nv + u);
                sum4 += ve * ve;
                sum4 += vc * vc;
                sumz4 += vc * zc;
                u += 4;
                continue;
            }
            if (u < nv)
                cg_r_at(u, r, q, alpha, pd, ract, nv, act, z, debar, cdeb, comp, &sum, &sumz);
            cg_r_at(nv + u, r, q, alpha, pd, ract, nv, act, z, debar, cdeb, comp, &sum, &sumz);
            u++;
        }
        sum += (sum4.s0 + sum4.s1) + (sum4.s2 + sum4.s3);
        sumz += (sumz4.s0 + sumz4.s1) + (sumz4.s2 + sumz4.s3);
#else
        TR_ITEMS(l, nl) {
            real v = r[l] - alpha * q[l];
            r[l] = v;
            sum += v * v;
            if (l >= nv) {
                real zl = precond_diag_at(v, l, nv, act, ract, pd);
                z[l] = zl;
                sumz += v * zl;
            }
        }
#endif
    }
    TR_ITEM_PARTIAL(rr, sum);
    if (rz) /* NULL where the edge block is not twisted */
        TR_ITEM_PARTIAL(rz, sumz);
}

/* y += alpha p (alpha = r.z (old) / p.q, as cg_r's), then p = z + beta p,
 * beta = r.z (new) / r.z (old). */
__kernel void cg_p(__global real *y, __global real *p, __global const real *z,
                   __global const real *sc, const int nl)
{
    if (sc[SC_DONE] != 0.0)
        return;
    real alpha = sc[SC_RZ] / sc[SC_PQ], beta = sc[SC_RR1] / sc[SC_RZ];
    TR_ITEMS(l, nl) {
        real pl = p[l];
        y[l] += alpha * pl;
        p[l] = z[l] + beta * pl;
    }
}

/* Edge row l's z with twisted.cl's step 4 (twist_ring_fix) applied; other
 * rows' z as it is. */
inline real ring_fixed(int l, int nv, __global const real *z, __global const int *comp,
                       __global const real *fact, __global const real *uu)
{
    return l < nv ? z[l] - fact[comp[l]] * uu[l] : z[l];
}

/* cg_p with twisted.cl's step 4 (twist_ring_fix) applied to the edge
 * rows' z as it is read (z itself keeps the unfixed values; nothing else
 * reads it before the next sweep overwrites it): one pass over the rows
 * instead of two. */
__kernel void cg_p_ring(__global real *y, __global real *p, __global const real *z,
                        __global const real *sc, const int nl, __global const int *comp,
                        const int ncomp, const int nv, __global const real *tw,
                        __global const real *ends)
{
    if (sc[SC_DONE] != 0.0)
        return;
    real alpha = sc[SC_RZ] / sc[SC_PQ], beta = sc[SC_RR1] / sc[SC_RZ];
    __global const real *fact = ends + 2 * ncomp, *uu = tw + 2 * nv;
    int l = tr_items_first(nl), end = tr_items_end(nl);
#ifdef TR_BLOCK_ITEMS
    /* four rows at a time, the fix in lanes where they are edge rows of one
     * component: a gather and a branch per row kept PoCL's loop scalar, at
     * twice cg_p's time */
    for (; l + 4 <= end; l += 4) {
        real4 zl;
        if (l >= nv)
            zl = vload4(0, z + l);
        else if (l + 4 <= nv && comp[l] == comp[l + 3])
            zl = vload4(0, z + l) - fact[comp[l]] * vload4(0, uu + l);
        else
            zl = (real4)(ring_fixed(l, nv, z, comp, fact, uu), ring_fixed(l + 1, nv, z, comp, fact, uu),
                         ring_fixed(l + 2, nv, z, comp, fact, uu), ring_fixed(l + 3, nv, z, comp, fact, uu));
        real4 pl = vload4(0, p + l);
        vstore4(vload4(0, y + l) + alpha * pl, 0, y + l);
        vstore4(zl + beta * pl, 0, p + l);
    }
#endif
    for (; l < end; l++) {
        real pl = p[l];
        y[l] += alpha * pl;
        p[l] = ring_fixed(l, nv, z, comp, fact, uu) + beta * pl;
    }
}

/* |dx_i| for the damping cap. */
__kernel void dx_norm(__global const real *dx, const int nv, __global real *m)
{
    TR_ITEMS(i, nv) {
        m[i] = tr_norm3(vload3(i, dx));
    }
}

__kernel void step_scale(__global real *sc, const real max_step)
{
    real m = sc[SC_MAXDX + 1]; /* the max of the min/max pair */
    sc[SC_SCALE] = m > max_step ? max_step / m : 1.0;
}

__kernel void apply_dx(__global real *x, __global const real *dx, __global const int *cidx, __global const real *cst,
                       __global const real *sc, const int nv)
{
    TR_ITEMS(i, nv) {
        real scale = sc[SC_SCALE];
        real3 d = vload3(i, dx);
        if (scale != 1.0)
            d = scale * d;
        vstore3(tr_snap(cidx, cst, i, vload3(i, x) + d), i, x);
    }
}

__kernel void apply_debar(__global real *ebar, __global const real *debar,
                          __global const real *sc, const int ncomp)
{
    TR_ITEMS(k, ncomp) {
        ebar[k] += sc[SC_SCALE] * debar[k];
    }
}

/* CG start from a given right-hand side: y = 0, r = p = b. */
__kernel void cg_reset(__global const real *b, __global real *y, __global real *r,
                       __global real *p, const int nr)
{
    TR_ITEMS(k, nr) {
        y[k] = 0.0;
        r[k] = b[k];
        p[k] = b[k];
    }
}

/* Tangent projection: release the inequality rows whose multiplier pulls
 * (y_r > 0: the force would separate them); *changed = 1 if any. */
__kernel void release_pulling(__global int *ract, __global const real *y, const int nv,
                              __global const int *act, const int nl, __global int *changed)
{
    TR_ITEMS(l_, nl - nv) {
        int l = l_ + nv;
        int r = row_of(l, 2 * nv, act);
        if (ract[r] && y[l] > 0.0) {
            ract[r] = 0;
            changed[0] = 1;
        }
    }
}

/* ---- preconditioner (backend.h correct (c)) ---- */

inline real proj_norm2(__global const int *cidx, __global const real *cst, int v, real3 g, real c)
{
    real3 t = tr_project_motion(cidx, cst, v, c * g);
    return tr_dot3(t, t);
}

/* pd[r]: diagonal of A on every active row (1 elsewhere); po[a]: the entry
 * between edge rows a and next(a). One item per row. */
__kernel void precond_setup(__global const real *rgrad, __global const real *cgq,
                            __global const real *cdeb, __global const int *ract,
                            __global const int *next, __global const int *prev,
                            __global const int *comp, __global const int *ne,
                            __global const int *pa, __global const int *pb,
                            __global const real *rs, __global const real *rt,
                            __global const int *cidx, __global const real *cst, const int nv, __global const int *act,
                            const int nl, const real ebar_weight, const real reg,
                            __global real *pd, __global real *po)
{
    TR_ITEMS(l, nl) {
        int r = row_of(l, 2 * nv, act);
        pd[r] = 1.0;
        if (!ract[r])
            continue;
        if (r < nv) {
            int a = r, k = comp[a], nx = next[a];
            real3 u = vload3(a, rgrad);
            pd[r] = proj_norm2(cidx, cst, a, u, 1.0) + proj_norm2(cidx, cst, nx, u, 1.0) +
                    1.0 / (ebar_weight * (real)ne[k]) + reg;
            real o = 0.0;
            if (next[nx] >= 0 && ract[nx]) {
                real3 t = tr_project_motion(cidx, cst, nx, u);
                o = -tr_dot3(t, vload3(nx, rgrad));
            }
            po[a] = o;
        } else if (r < 2 * nv) {
            int i = r - nv, k = comp[i];
            real3 ga = vload3(r, rgrad), gb = vload3(i, cgq);
            real3 gm = gb - ga;
            pd[r] = proj_norm2(cidx, cst, prev[i], ga, 1.0) + proj_norm2(cidx, cst, i, gm, 1.0) +
                    proj_norm2(cidx, cst, next[i], gb, 1.0) +
                    cdeb[i] * cdeb[i] / (ebar_weight * (real)ne[k]) + reg;
        } else {
            int p = r - 2 * nv, a = pa[p], b = pb[p];
            real3 n = vload3(r, rgrad);
            pd[r] = proj_norm2(cidx, cst, a, n, 1.0 - rs[p]) + proj_norm2(cidx, cst, next[a], n, rs[p]) +
                    proj_norm2(cidx, cst, b, n, 1.0 - rt[p]) + proj_norm2(cidx, cst, next[b], n, rt[p]) + reg;
        }
    }
}

/* z = r / pd on curvature and strut rows (0 when inactive). */
__kernel void precond_diag(__global const real *r, __global const real *pd,
                           __global const int *ract, const int nv, __global const int *act,
                           const int nl, __global real *z)
{
    TR_ITEMS(m, nl - nv) {
        int l = m + nv;
        z[l] = precond_diag_at(r[l], l, nv, act, ract, pd);
    }
}

/* The edge block of one component as Thomas factors (the reference's
 * tridiag_factor, same arithmetic): multipliers w and reciprocal pivots ib
 * of the rows st .. st+n-1, diagonal b with its first and last entries
 * replaced by b_first, b_last. */
inline void thomas_factor(__global const real *po, __global const real *b, real b_first,
                          real b_last, int st, int n, __global real *w, __global real *ib)
{
    ib[0] = 1.0 / (n > 1 ? b_first : b_last);
    for (int j = 1; j < n; j++) {
        w[j] = po[st + j - 1] * ib[j - 1];
        ib[j] = 1.0 / ((j + 1 < n ? b[j] : b_last) - po[st + j - 1] * w[j]);
    }
}

/* x = T^-1 rr from thomas_factor's factors (the reference's tridiag_subst). */
inline void thomas_subst(__global const real *po, int st, int n, __global const real *w,
                         __global const real *ib, __global const real *rr, __global real *x)
{
    x[0] = rr[0] * ib[0];
    for (int j = 1; j < n; j++)
        x[j] = (rr[j] - po[st + j - 1] * x[j - 1]) * ib[j];
    for (int j = n - 1; j-- > 0;)
        x[j] -= w[j + 1] * x[j + 1];
}

/* Factors the edge block of component k once per solve (one item per
 * component; the reference's precond_factor). It uses 3 nv of tw's reals:
 * multipliers, reciprocal pivots, and for closed components the
 * Sherman-Morrison vector uu (Numerical Recipes 2.7, gamma = -D_first). */
__kernel void precond_edges_factor(__global const real *pd, __global const real *po,
                                   __global const int *start, __global const int *ne,
                                   __global const int *closed, const int ncomp, const int nv,
                                   __global real *tw)
{
    TR_ITEMS(k, ncomp) {
        int st = start[k], n = ne[k];
        __global real *w = tw + st, *ib = tw + nv + st, *uu = tw + 2 * nv + st;
        __global const real *d = pd + st;
        if (n == 0)
            continue;
        if (!closed[k] || n < 3) {
            thomas_factor(po, d, d[0], d[n - 1], st, n, w, ib);
            continue;
        }
        real alpha = po[st + n - 1], beta = alpha, gamma = -d[0];
        thomas_factor(po, d, d[0] - gamma, d[n - 1] - alpha * beta / gamma, st, n, w, ib);
        for (int j = 0; j < n; j++)
            uu[j] = 0.0;
        uu[0] = gamma;
        uu[n - 1] = alpha;
        thomas_subst(po, st, n, w, ib, uu, uu);
    }
}

/* Edge block of component k from precond_edges_factor's factors (one item
 * per component: the substitution sweeps are sequential, as in the
 * reference). */
__kernel void precond_edges(__global const real *r, __global const real *pd,
                            __global const real *po, __global const int *start,
                            __global const int *ne, __global const int *closed, const int ncomp,
                            const int nv, __global const real *tw, __global real *z)
{
    TR_ITEMS(k, ncomp) {
        int st = start[k], n = ne[k];
        __global const real *w = tw + st, *ib = tw + nv + st, *uu = tw + 2 * nv + st;
        __global real *x = z + st;
        /* the row of an open rope's last vertex has no edge: keep it out of the dot products */
        for (int j = n; j < start[k + 1] - st; j++)
            x[j] = 0.0;
        if (n == 0)
            continue;
        thomas_subst(po, st, n, w, ib, r + st, x);
        if (!closed[k] || n < 3)
            continue;
        real beta = po[st + n - 1], gamma = -pd[st];
        real fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + uu[0] + beta * uu[n - 1] / gamma);
        for (int j = 0; j < n; j++)
            x[j] -= fact * uu[j];
    }
}

/* p = z */
__kernel void copy_rows(__global const real *z, __global real *p, const int nl)
{
    TR_ITEMS(l, nl)
        p[l] = z[l];
}
