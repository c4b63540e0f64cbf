/* Force evaluation (backend.h tension_step): the negative length gradient
 * (rope tension pulling each vertex along its two edges), Jacobi low-pass
 * passes, and the capped, constraint-projected motion. One item per vertex;
 * every output is a gather over the vertex's own chain neighbours. */

inline real3 tension_unit(__global const real *x, int a, int b)
{
    real3 u = vload3(b, x) - vload3(a, x);
    real l = tr_norm3(u);
    return u * (1.0 / l);
}

__kernel void tension_force(__global const real *x, __global const int *next,
                            __global const int *prev, const int n, __global real *F)
{
    TR_ITEMS(i, n) {
        real3 f = (real3)(0.0);
        if (next[i] >= 0)
            f = f + tension_unit(x, i, next[i]);
        if (prev[i] >= 0)
            f = f - tension_unit(x, prev[i], i);
        vstore3(f, i, F);
    }
}

/* H = S G: (G_prev + 2 G_i + G_next)/4 inside, (3 G_i + G_nb)/4 at an open end. */
__kernel void tension_smooth(__global const real *G, __global const int *next,
                             __global const int *prev, const int n, __global real *H)
{
    TR_ITEMS(i, n) {
        int pv = prev[i], nx = next[i];
        real3 g = vload3(i, G), h;
        if (pv >= 0 && nx >= 0)
            h = (vload3(pv, G) + 2.0 * g + vload3(nx, G)) / 4.0;
        else if (pv >= 0 || nx >= 0)
            h = (3.0 * g + vload3(pv >= 0 ? pv : nx, G)) / 4.0;
        else
            h = g;
        vstore3(h, i, H);
    }
}

/* dx = h P G capped at max_move; x += dx; snap. Per-vertex terms of the
 * stats go to f2 (|P F|^2), pred (F . dx) and mv (|dx|) for the reductions. */
__kernel void tension_move(__global real *x, __global const real *F, __global const real *G,
                           __global const int *cidx, __global const real *cst, const int n, const real h,
                           const real max_move, __global real *f2, __global real *pred,
                           __global real *mv)
{
    TR_ITEMS(i, n) {
        real3 Fi = vload3(i, F);
        real3 f = tr_project_motion(cidx, cst, i, Fi);
        f2[i] = tr_dot3(f, f);
        real3 d = tr_project_motion(cidx, cst, i, h * vload3(i, G));
        real m = tr_norm3(d);
        if (m > max_move) {
            d = (max_move / m) * d;
            m = max_move;
        }
        mv[i] = m;
        pred[i] = tr_dot3(Fi, d);
        vstore3(tr_snap(cidx, cst, i, vload3(i, x) + d), i, x);
    }
}

/* s2[i] = |P_i G_i|^2 (the smoothed force's share of the KKT residual). */
__kernel void tension_smooth2(__global const real *G, __global const int *cidx, __global const real *cst, const int n,
                              __global real *s2)
{
    TR_ITEMS(i, n) {
        real3 g = tr_project_motion(cidx, cst, i, vload3(i, G));
        s2[i] = tr_dot3(g, g);
    }
}

/* ---- the tangent-cone projection of the force (backend.h tension_step 2b),
 * around the correction's rows and CG (correct.cl, whose release_pulling
 * frees the rows that pull) ---- */

/* G_i <- P_i G_i (before the tangent projection). */
__kernel void project_field(__global real *G, __global const int *cidx, __global const real *cst, const int nv)
{
    TR_ITEMS(i, nv) {
        vstore3(tr_project_motion(cidx, cst, i, vload3(i, G)), i, G);
    }
}

/* G -= dx (flat), and debar <- -debar (the ebar velocity). */
__kernel void tangent_finish(__global real *G, __global const real *dx, const int n3)
{
    TR_ITEMS(k, n3) {
        G[k] -= dx[k];
    }
}

__kernel void ebar_velocity(__global real *ebar, __global real *debar, const real h,
                            const int ncomp)
{
    TR_ITEMS(k, ncomp) {
        ebar[k] += h * (-debar[k]);
    }
}
