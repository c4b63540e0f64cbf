/* Neighbour search on the device: a uniform grid by cell sort (Green 2010).
 * Each item (a vertex, or an edge represented by its midpoint) gets the key
 * (cell << 32 | index); a bitonic sort of the keys groups every cell's items
 * in index order; cell_bounds marks where each cell's run starts and ends;
 * grid_pairs scans the 27 cells around each item and keeps the partners
 * closer than r that the arclength rule does not exclude. Everything is a
 * per-item gather and the sort keys are unique, so the lists are the same
 * bits on every run and device. */

#define TR_NO_KEY 0xffffffffffffffffUL

/* Midpoint of edge i (edges = 1) or vertex i (edges = 0); 0 if item i is no edge. */
inline int grid_item(__global const real *x, __global const int *next, int edges, int i, real3 *p)
{
    if (!edges) {
        *p = vload3(i, x);
        return 1;
    }
    int j = next[i];
    if (j < 0)
        return 0;
    *p = 0.5 * (vload3(i, x) + vload3(j, x));
    return 1;
}

inline int3 grid_cell(real3 p, real3 lo, real inv_h, int3 dims)
{
    int3 c = convert_int3_rtn((p - lo) * inv_h);
    return clamp(c, (int3)(0), dims - 1);
}

/* x[axis] of every vertex into v (for the bounding box reduction). */
__kernel void grid_axis(__global const real *x, const int n, const int axis, __global real *v)
{
    int i = get_global_id(0);
    if (i < n)
        v[i] = x[3 * i + axis];
}

__kernel void grid_keys(__global const real *x, __global const int *next, const int n,
                        const int npad, const int edges, const real lox, const real loy,
                        const real loz, const real inv_h, const int nx, const int ny,
                        const int nz, __global ulong *keys)
{
    int i = get_global_id(0);
    if (i >= npad)
        return;
    real3 p;
    if (i >= n || !grid_item(x, next, edges, i, &p)) {
        keys[i] = TR_NO_KEY;
        return;
    }
    int3 dims = (int3)(nx, ny, nz);
    int3 c = grid_cell(p, (real3)(lox, loy, loz), inv_h, dims);
    uint cell = (uint)((c.z * ny + c.y) * nx + c.x);
    keys[i] = ((ulong)cell << 32) | (uint)i;
}

/* One compare-exchange pass of the bitonic network (stage k, distance j) over a power-of-two array. */
__kernel void bitonic_pass(__global ulong *keys, const int j, const int k, const int npad)
{
    int i = get_global_id(0);
    int l = i ^ j;
    if (i >= npad || l <= i)
        return;
    ulong a = keys[i], b = keys[l];
    int up = (i & k) == 0;
    if ((a > b) == up) {
        keys[i] = b;
        keys[l] = a;
    }
}

__kernel void cell_reset(__global int *cell_start, __global int *cell_end, const int ncell)
{
    int c = get_global_id(0);
    if (c < ncell) {
        cell_start[c] = 0;
        cell_end[c] = 0;
    }
}

__kernel void cell_bounds(__global const ulong *keys, const int npad, __global int *cell_start,
                          __global int *cell_end)
{
    int i = get_global_id(0);
    if (i >= npad || keys[i] == TR_NO_KEY)
        return;
    uint cell = (uint)(keys[i] >> 32);
    if (i == 0 || (uint)(keys[i - 1] >> 32) != cell)
        cell_start[cell] = i;
    if (i + 1 == npad || keys[i + 1] == TR_NO_KEY || (uint)(keys[i + 1] >> 32) != cell)
        cell_end[cell] = i + 1;
}

/* Index distance of items i, j along their component (a closed one wraps)
 * below that component's gap (at least 2); different components are never
 * excluded. */
inline int grid_excluded(__global const int *comp, __global const int *pos,
                         __global const int *comp_n, __global const int *comp_closed, int i,
                         int j, __global const int *gap)
{
    int c = comp[i];
    if (comp[j] != c)
        return 0;
    int g = abs(pos[i] - pos[j]);
    if (comp_closed[c])
        g = min(g, comp_n[c] - g);
    return g < max(gap[c], 2);
}

/* For item i: partners j with distance < r (segment-segment for edges,
 * point-point for vertices), not excluded, in increasing j; count[i] is the
 * full number even when it exceeds cap (then *overflow is set and the host
 * enlarges the lists). For edges with 0 < tilt < 1 only the pairs whose
 * closest-point connector is within tilt of both normal planes
 * (tr_segment_nearly_normal). Edge pairs are evaluated lower index first,
 * as the reference does, so that item i and item j decide alike. */
__kernel void grid_pairs(__global const real *x, __global const int *next, const int n,
                         const int edges, __global const int *comp, __global const int *pos,
                         __global const int *comp_n, __global const int *comp_closed,
                         __global const int *gap, const real r, const real tilt,
                         __global const ulong *keys,
                         __global const int *cell_start, __global const int *cell_end,
                         const real lox, const real loy, const real loz, const real inv_h,
                         const int nx, const int ny, const int nz, const int cap,
                         __global int *count, __global int *list, __global int *overflow)
{
    int i = get_global_id(0);
    if (i >= n)
        return;
    real3 p;
    if (!grid_item(x, next, edges, i, &p)) {
        count[i] = 0;
        return;
    }
    int3 dims = (int3)(nx, ny, nz);
    int3 c = grid_cell(p, (real3)(lox, loy, loz), inv_h, dims);
    real3 a0 = vload3(i, x), a1 = edges ? vload3(next[i], x) : a0;
    int m = 0;
    __global int *mine = list + (size_t)i * (size_t)cap;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int3 q = c + (int3)(dx, dy, dz);
                if (any(q < (int3)(0)) || any(q >= dims))
                    continue;
                int cell = (q.z * ny + q.y) * nx + q.x;
                for (int s = cell_start[cell]; s < cell_end[cell]; s++) {
                    int j = (int)(uint)(keys[s] & 0xffffffffUL);
                    if (j == i || grid_excluded(comp, pos, comp_n, comp_closed, i, j, gap))
                        continue;
                    real3 b0 = vload3(j, x);
                    real d;
                    int keep = 1;
                    if (edges) {
                        real ss, tt;
                        real3 b1 = vload3(next[j], x);
                        real3 l0 = i < j ? a0 : b0, l1 = i < j ? a1 : b1;
                        real3 h0 = i < j ? b0 : a0, h1 = i < j ? b1 : a1;
                        d = tr_segment_distance(l0, l1, h0, h1, &ss, &tt);
                        if (tilt > 0.0 && tilt < 1.0 && d < r)
                            keep = tr_segment_nearly_normal(l0, l1, h0, h1, ss, tt, d, tilt);
                    } else {
                        d = tr_norm3(a0 - b0);
                    }
                    if (d < r && keep) {
                        if (m < cap) {
                            /* insertion keeps the list in increasing j */
                            int k = m;
                            while (k > 0 && mine[k - 1] > j) {
                                mine[k] = mine[k - 1];
                                k--;
                            }
                            mine[k] = j;
                        } else {
                            overflow[0] = 1;
                        }
                        m++;
                    }
                }
            }
    count[i] = m;
}
