/* Device neighbour search (the tree walk) against an independent
 * brute-force O(N^2) scan: the same partner lists (segment-segment distance,
 * arclength exclusion, and with a tilt only struts nearly normal to both
 * edges) on a trefoil, a two-component link and two hooked open ropes, at
 * the smallest sizes, at sizes that are and are not multiples of the
 * work-group size, and after a list overflow. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/cl_reduce.h"
#include "backend/opencl/cl_tree.h"
#include "curve/curve.h"
#include "segment_distance.h"
#include "testlib.h"

#define TR_PI 3.14159265358979323846

/* kind 0: trefoil scaled by s; 1: two linked circles radius 2.2; 2: two hooked U ropes */
static int make_curve(tr_curve *c, int kind, size_t n, tr_error *err)
{
    if (kind == 0) {
        unsigned char closed = 1;
        int rc = tr_curve_alloc(c, 1, &n, &closed, err);
        for (size_t i = 0; rc == TR_OK && i < n; i++) {
            double t = 2.0 * TR_PI * (double)i / (double)n;
            c->x[3 * i] = 1.2 * (sin(t) + 2 * sin(2 * t));
            c->x[3 * i + 1] = 1.2 * (cos(t) - 2 * cos(2 * t));
            c->x[3 * i + 2] = -1.2 * sin(3 * t);
        }
        return rc;
    }
    size_t nv[2] = {n / 2, n - n / 2};
    unsigned char closed[2] = {kind == 1, kind == 1};
    int rc = tr_curve_alloc(c, 2, nv, closed, err);
    if (rc != TR_OK)
        return rc;
    for (size_t i = 0; i < nv[0]; i++) {
        double *p = c->x + 3 * i;
        if (kind == 1) {
            double t = 2 * TR_PI * (double)i / (double)nv[0];
            p[0] = 2.2 * cos(t), p[1] = 2.2 * sin(t), p[2] = 0;
        } else {
            double a = TR_PI + TR_PI * (double)i / (double)(nv[0] - 1);
            p[0] = 2.5 * cos(a), p[1] = 0, p[2] = 2.5 * sin(a);
        }
    }
    for (size_t i = 0; i < nv[1]; i++) {
        double *p = c->x + 3 * (nv[0] + i);
        if (kind == 1) {
            double t = 2 * TR_PI * (double)i / (double)nv[1];
            p[0] = 2.2 + 2.2 * cos(t), p[1] = 0, p[2] = 2.2 * sin(t);
        } else {
            double a = TR_PI * (double)i / (double)(nv[1] - 1);
            p[0] = 0, p[1] = 2.5 * cos(a), p[2] = -2.5 + 2.5 * sin(a);
        }
    }
    return TR_OK;
}

/* Segment distance by minimising over a fine parameter grid and then
 * refining with golden sections: slow and independent of the device's closed
 * form; accurate to ~1e-10, enough to classify pairs away from the cutoff. */
static double point_seg(const double *p, const double *a, const double *b)
{
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double w[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double t = dd > 0 ? (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    double q[3] = {a[0] + t * d[0] - p[0], a[1] + t * d[1] - p[1], a[2] + t * d[2] - p[2]};
    return sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
}

static double seg_dist_slow(const double *p0, const double *p1, const double *q0, const double *q1)
{
    /* distance from a point of segment P to segment Q is convex in P's parameter */
    double lo = 0, hi = 1;
    for (int it = 0; it < 100; it++) {
        double m1 = lo + (hi - lo) * 0.381966, m2 = lo + (hi - lo) * 0.618034;
        double a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = p0[k] + m1 * (p1[k] - p0[k]);
            b[k] = p0[k] + m2 * (p1[k] - p0[k]);
        }
        if (point_seg(a, q0, q1) < point_seg(b, q0, q1))
            hi = m2;
        else
            lo = m1;
    }
    double best = fmin(point_seg(p0, q0, q1), point_seg(p1, q0, q1));
    double m[3];
    for (int k = 0; k < 3; k++)
        m[k] = p0[k] + 0.5 * (lo + hi) * (p1[k] - p0[k]);
    return fmin(best, point_seg(m, q0, q1));
}

/* Brute force: the partners of edge i, increasing (backend.h's list). */
static int brute_partners(const tr_curve *c, const int *next, const int *comp, const int *pos, int i,
                          double r, double tilt, int K, int *want)
{
    int nv = (int)c->nv;
    int m = 0;
    if (next[i] >= 0)
        for (int j = 0; j < nv; j++) {
            if (j == i || next[j] < 0)
                continue;
            if (comp[i] == comp[j]) {
                int g = abs(pos[i] - pos[j]), cn = (int)tr_comp_nv(c, comp[i]);
                if (c->closed[comp[i]] && cn - g < g)
                    g = cn - g;
                if (g < K)
                    continue;
            }
            const double *a = c->x + 3 * i, *b = c->x + 3 * j;
            double ab = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                             (a[2] - b[2]) * (a[2] - b[2]));
            /* segments can be no closer than their start points minus both lengths */
            const double *a1 = c->x + 3 * next[i], *b1 = c->x + 3 * next[j];
            double la = sqrt((a1[0] - a[0]) * (a1[0] - a[0]) + (a1[1] - a[1]) * (a1[1] - a[1]) +
                             (a1[2] - a[2]) * (a1[2] - a[2]));
            double lb = sqrt((b1[0] - b[0]) * (b1[0] - b[0]) + (b1[1] - b[1]) * (b1[1] - b[1]) +
                             (b1[2] - b[2]) * (b1[2] - b[2]));
            if (ab - la - lb > r + 1e-9)
                continue;
            double d = seg_dist_slow(a, a1, b, b1);
            if (tilt > 0.0 && tilt < 1.0) {
                /* backend.h's definition, lower edge first */
                int lo = i < j ? i : j, hi = i < j ? j : i;
                const double *l0 = c->x + 3 * lo, *l1 = c->x + 3 * next[lo];
                const double *h0 = c->x + 3 * hi, *h1 = c->x + 3 * next[hi];
                double s, t;
                d = tr_segment_distance(l0, l1, h0, h1, &s, &t);
                if (d < r && !tr_segment_nearly_normal(l0, l1, h0, h1, s, t, d, tilt))
                    continue;
            }
            if (d < r)
                want[m++] = j;
        }
    return m;
}

static void run_case(const tr_cl_ctx *ctx, cl_program prog, int kind, size_t n, double r,
                     double tilt, int K, int cap)
{
    tr_error err;
    tr_curve c;
    if (make_curve(&c, kind, n, &err) != TR_OK) {
        tr_test_failures++;
        return;
    }
    int *next, *prev, *comp, *pos;
    CHECK_OK(tr_topology_arrays(&c, &next, &prev, &comp, &pos, &err));
    tr_cl_topology topo;
    tr_cl_tree grid;
    CHECK_OK(tr_cl_topology_upload(ctx, &c, &topo, &err));
    CHECK_OK(tr_cl_tree_init(&grid, ctx, prog, &c, cap, &err));
    cl_int e;
    cl_mem x = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                              3 * c.nv * sizeof(double), c.x, &e);
    int gaps[2] = {K, K};
    cl_mem gap = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof gaps,
                                gaps, &e);
    tr_cl_reduce red;
    CHECK_OK(tr_cl_reduce_init(&red, ctx, prog, c.nv + 64, &err));
    /* every edge's partners by brute force, wall[wofs[i] ..] */
    int *wofs = malloc((c.nv + 1) * sizeof *wofs), *wbuf = malloc(c.nv * sizeof *wbuf), *wall = NULL;
    size_t wcap = 0;
    wofs[0] = 0;
    for (int i = 0; i < (int)c.nv; i++) {
        int m = brute_partners(&c, next, comp, pos, i, r, tilt, K, wbuf);
        wofs[i + 1] = wofs[i] + m;
        if ((size_t)wofs[i + 1] > wcap) {
            wcap = 2 * (size_t)wofs[i + 1];
            wall = realloc(wall, wcap * sizeof *wall);
        }
        if (m)
            memcpy(wall + wofs[i], wbuf, (size_t)m * sizeof *wall);
    }
    /* twice: the second walk sizes its rows from the first one's counts */
    for (int pass = 0; pass < 2; pass++) {
        int regrown = grid.regrown;
        int rc = tr_cl_tree_search(&grid, ctx, &red, &topo, x, r, tilt, gap, K, &err);
        CHECK_OK(rc);
        if (rc != TR_OK)
            fprintf(stderr, "%s\n", err.msg);
        int nv = (int)c.nv;
        int *cnt = malloc(c.nv * sizeof *cnt), *loff = malloc((c.nv + 1) * sizeof *loff);
        int *list = malloc(grid.list_cap * sizeof *list);
        clEnqueueReadBuffer(ctx->queue, grid.count, CL_TRUE, 0, c.nv * sizeof(int), cnt, 0, NULL, NULL);
        clEnqueueReadBuffer(ctx->queue, grid.loff, CL_TRUE, 0, (c.nv + 1) * sizeof(int), loff, 0, NULL,
                            NULL);
        clEnqueueReadBuffer(ctx->queue, grid.list, CL_TRUE, 0, grid.list_cap * sizeof(int), list, 0, NULL,
                            NULL);
        long total = 0, bad = 0;
        for (int i = 0; i < nv; i++) {
            int m = wofs[i + 1] - wofs[i];
            const int *want = wall + wofs[i];
            total += m;
            int same = cnt[i] == m && m <= loff[i + 1] - loff[i] && loff[i] >= 0 &&
                       (size_t)loff[i + 1] <= grid.list_cap;
            for (int k = 0; same && k < m; k++)
                same = list[(size_t)loff[i] + (size_t)k] == want[k];
            if (!same && bad++ < 3)
                fprintf(stderr, "kind %d n %d item %d: %d partners on device, %d by brute force\n", kind,
                        nv, i, cnt[i], m);
        }
        CHECK(bad == 0);
        if (tilt > 0.0)
            CHECK(total > 0); /* the tilted case has pairs to agree on */
        printf("kind %d n %zu r %g tilt %g, walk %d: %ld pairs, %d regrown\n", kind, n, r, tilt, pass + 1,
               total, grid.regrown - regrown);
        int most = 0;
        for (int i = 0; i < nv; i++)
            most = cnt[i] > most ? cnt[i] : most;
        if (pass == 0) /* the walk repeats exactly when a row of cap overflows */
            CHECK((grid.regrown > regrown) == (most > cap));
        if (pass == 1)
            CHECK(grid.regrown == regrown); /* rows sized from the same curve's counts fit */
        free(cnt), free(list), free(loff);
    }
    free(wofs), free(wbuf), free(wall);
    tr_cl_reduce_free(&red);
    free(next), free(prev), free(comp), free(pos);
    clReleaseMemObject(x);
    clReleaseMemObject(gap);
    tr_cl_tree_free(&grid);
    tr_cl_topology_free(&topo);
    tr_curve_free(&c);
}

int main(void)
{
    tr_error err;
    tr_device_choice ch;
    if (tr_device_select("opencl", &ch, &err) != TR_OK || ch.kind != TR_DEVICE_OPENCL) {
        printf("no usable opencl device: skipped\n");
        return TR_SKIP;
    }
    tr_cl_ctx ctx;
    cl_program prog;
    if (tr_cl_ctx_open(&ctx, &ch.cl, 0, &err) != TR_OK || tr_cl_build_all(&ctx, &prog, &err) != TR_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    /* smallest legal curves: a triangle, two triangles, two 2-vertex ropes */
    run_case(&ctx, prog, 0, 3, 10.0, 0.0, 2, 16);
    run_case(&ctx, prog, 1, 6, 10.0, 0.0, 2, 16);
    run_case(&ctx, prog, 2, 4, 10.0, 0.0, 2, 16);
    /* TIGHTROPE_TEST_SMALL (Oclgrind): smaller, still several work-groups,
     * one size not a multiple of the group size, one past the sums' single
     * stage (1024) */
    const int small = tr_test_small();
    const size_t n1021 = small ? 253 : 1021, n1024 = small ? 256 : 1024, n4099 = small ? 1100 : 4099;
    const size_t sizes[] = {64, n1021, n1024};
    for (int kind = 0; kind < 3; kind++)
        for (size_t s = 0; s < 3; s++) {
            /* cutoff 2.2 with exclusion of ~pi/e index neighbours, as the engine uses */
            size_t n = sizes[s];
            int K = (int)ceil(TR_PI / (20.0 / (double)n));
            run_case(&ctx, prog, kind, n, 2.2, 0.0, K, 8);
        }
    /* the engine's tilted list: only struts nearly normal to both edges (the
     * slab pruning of the walk in use) */
    for (int kind = 0; kind < 2; kind++)
        run_case(&ctx, prog, kind, n1024, 2.2, 0.05, (int)ceil(TR_PI / (20.0 / (double)n1024)), 8);
    run_case(&ctx, prog, 0, n1021, 2.5, 0.05, 30, 8);
    run_case(&ctx, prog, 0, n4099, 2.5, 0.01, 30, 8);
    /* overflow: lists that start too short are grown and the result is the same */
    run_case(&ctx, prog, 0, n1021, 2.5, 0.0, 30, 1);
    clReleaseProgram(prog);
    tr_cl_ctx_close(&ctx);
    return tr_test_finish("test_opencl_tree");
}
