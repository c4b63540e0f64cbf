/* The serial reference backend against closed forms and finite differences:
 * tension force = -grad(length), the coupled correction restores equal edges,
 * struts >= 2 and the curvature chords, contact lists obey the exclusion rule. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/backend.h"
#include "segment_distance.h"
#include "testlib.h"
#include "util/vec3.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Torus knot T(2,3) on radii (R, r), n vertices (not equilateral). */
static void torus_knot(tr_curve *c, size_t n, double R, double r, double scale)
{
    tr_error err;
    size_t nv[1] = {n};
    unsigned char cl[1] = {1};
    CHECK_OK(tr_curve_alloc(c, 1, nv, cl, &err));
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * (double)i / (double)n;
        double rr = R + r * cos(3.0 * t);
        c->x[3 * i] = scale * rr * cos(2.0 * t);
        c->x[3 * i + 1] = scale * rr * sin(2.0 * t);
        c->x[3 * i + 2] = scale * r * sin(3.0 * t);
    }
}

static double seg_min_brute(const tr_curve *c, int gap, size_t *count, double cutoff)
{
    size_t n = c->nv;
    double m = INFINITY;
    *count = 0;
    for (size_t a = 0; a < n; a++)
        for (size_t b = a + 1; b < n; b++) {
            size_t d = b - a;
            if (n - d < d)
                d = n - d;
            if (d < (size_t)gap)
                continue;
            double s, t;
            double dd = tr_segment_distance(c->x + 3 * a, c->x + 3 * ((a + 1) % n), c->x + 3 * b,
                                            c->x + 3 * ((b + 1) % n), &s, &t);
            if (dd < cutoff)
                (*count)++;
            if (dd < m)
                m = dd;
        }
    return m;
}

int main(void)
{
    tr_error err;
    /* segment distance closed forms */
    {
        double p0[3] = {0, 0, 0}, p1[3] = {2, 0, 0}, q0[3] = {1, -1, 3}, q1[3] = {1, 1, 3};
        double s, t;
        CHECK_NEAR(tr_segment_distance(p0, p1, q0, q1, &s, &t), 3.0, 1e-15);
        CHECK_NEAR(s, 0.5, 1e-15);
        CHECK_NEAR(t, 0.5, 1e-15);
        double r0[3] = {3, 1, 0}, r1[3] = {5, 1, 0}; /* parallel, offset past the end */
        CHECK_NEAR(tr_segment_distance(p0, p1, r0, r1, &s, &t), sqrt(2.0), 1e-15);
        CHECK_NEAR(s, 1.0, 0);
        CHECK_NEAR(t, 0.0, 0);
    }

    tr_curve c;
    torus_knot(&c, 120, 2.0, 1.0, 1.6);
    tr_backend be;
    CHECK_OK(tr_backend_open("reference", &c, &be, &err));
    const tr_backend_ops *op = be.ops;
    tr_measure m0;
    CHECK_OK(op->measure(be.state, &m0, NULL, NULL, &err));
    CHECK_NEAR(m0.length, tr_curve_length(&c), 1e-12);
    printf("start: length %.6f minrad %.4f\n", m0.length, m0.min_minrad);
    CHECK(m0.min_minrad > 1.0);

    /* equalise the (parametric, unequal) edges first */
    tr_correct_params cpp = {.max_newton = 30, .max_cg = 400, .cg_rtol = 1e-10, .viol_tol = 1e-11,
                             .active_strut = 0.01, .active_curv = 0.01, .strut_dist = 2.0,
                             .minrad = 1.0, .ebar_weight = 1.0, .reg = 1e-12,
                             .max_step = 0.05};
    tr_correct_stats cst;
    CHECK_OK(op->correct(be.state, &cpp, &cst, &err));
    CHECK(cst.viol_after <= 1e-10);
    CHECK_OK(op->measure(be.state, &m0, NULL, NULL, &err));
    CHECK(m0.edge_dev < 1e-10);
    CHECK_OK(op->download(be.state, c.x, NULL, &err));

    /* contacts equal a brute-force count with the same exclusion rule */
    int gap[1] = {10};
    tr_contact_params cp = {.cutoff = 3.0, .exclude_gap = gap};
    tr_contact_stats cs;
    CHECK_OK(op->find_contacts(be.state, &cp, &cs, &err));
    size_t brute_count;
    double brute_min = seg_min_brute(&c, gap[0], &brute_count, cp.cutoff);
    CHECK(cs.pairs == brute_count);
    CHECK_NEAR(cs.min_dist, brute_min, 0);
    CHECK(cs.pairs > 0);

    /* With a tilt the list is exactly the brute-force set of pairs within
     * the cutoff whose strut is nearly normal to both edges, and that set
     * holds every local minimum of the distance along both strands (from
     * the full distance table) once the tilt reaches the sine of the largest
     * turning angle (backend.h's claim, tested at that very bound). */
    {
        size_t n = c.nv;
        double sin_max = 0.0;
        for (size_t i = 0; i < n; i++) {
            double u[3], w[3], x[3];
            v3_sub(u, c.x + 3 * i, c.x + 3 * ((i + n - 1) % n));
            v3_sub(w, c.x + 3 * ((i + 1) % n), c.x + 3 * i);
            v3_cross(x, u, w);
            sin_max = fmax(sin_max, v3_norm(x) / (v3_norm(u) * v3_norm(w)));
        }
        tr_contact_params ct = cp;
        ct.tilt = sin_max * (1.0 + 1e-9);
        tr_contact_stats cst2;
        CHECK_OK(op->find_contacts(be.state, &ct, &cst2, &err));
        double *dt = malloc(n * n * sizeof *dt);
        for (size_t a = 0; a < n; a++)
            for (size_t b = 0; b < n; b++) {
                double s, t;
                dt[a * n + b] = tr_segment_distance(c.x + 3 * a, c.x + 3 * ((a + 1) % n), c.x + 3 * b,
                                                    c.x + 3 * ((b + 1) % n), &s, &t);
            }
        size_t kept = 0, minima = 0, minima_kept = 0;
        double min_kept = INFINITY, min_local = INFINITY;
        for (size_t a = 0; a < n; a++)
            for (size_t b = a + 1; b < n; b++) {
                size_t g = b - a < n - (b - a) ? b - a : n - (b - a);
                const double *a0 = c.x + 3 * a, *a1 = c.x + 3 * ((a + 1) % n);
                const double *b0 = c.x + 3 * b, *b1 = c.x + 3 * ((b + 1) % n);
                double s, t, d = tr_segment_distance(a0, a1, b0, b1, &s, &t);
                if (g < (size_t)gap[0] || !(d < cp.cutoff))
                    continue;
                int normal = tr_segment_nearly_normal(a0, a1, b0, b1, s, t, d, ct.tilt);
                if (normal) {
                    kept++;
                    min_kept = fmin(min_kept, d);
                }
                size_t ap = (a + n - 1) % n, an = (a + 1) % n, bp = (b + n - 1) % n, bn = (b + 1) % n;
                if (d <= dt[ap * n + b] && d <= dt[an * n + b] && d <= dt[a * n + bp] && d <= dt[a * n + bn]) {
                    minima++;
                    minima_kept += (size_t)normal;
                    min_local = fmin(min_local, d);
                }
            }
        printf("contacts: %zu plain, %zu with tilt %.3f (brute %zu), %zu local minima, %zu kept\n",
               cs.pairs, cst2.pairs, ct.tilt, kept, minima, minima_kept);
        CHECK(cst2.pairs == kept);
        CHECK(cst2.pairs < cs.pairs);
        CHECK(minima > 0 && minima_kept == minima);
        CHECK_NEAR(cst2.min_dist, min_kept, 0);
        CHECK_NEAR(cst2.min_dist, min_local, 0);
        free(dt);
        CHECK_OK(op->find_contacts(be.state, &cp, &cs, &err));
    }

    /* tension: predicted decrease matches the actual one for a tiny step
     * (F = -grad L), relative error O(h) */
    CHECK_OK(op->save(be.state, &err));
    tr_tension_params tp = {.h = 1e-6, .max_move = 1.0, .smooth_passes = 0};
    tr_tension_stats ts;
    CHECK_OK(op->tension_step(be.state, &tp, &ts, &err));
    tr_measure m1;
    CHECK_OK(op->measure(be.state, &m1, NULL, NULL, &err));
    CHECK_NEAR((m0.length - m1.length) / ts.predicted, 1.0, 1e-4);
    CHECK_NEAR(ts.predicted, tp.h * ts.force2, 1e-12 * ts.predicted);
    CHECK_NEAR(m1.max_disp, ts.max_move, 1e-15);
    CHECK_OK(op->restore(be.state, &err));

    /* a large smoothed step, then the correction: edges equal again, chords
     * and struts satisfied */
    tp.h = 0.1;
    tp.max_move = 0.02;
    tp.smooth_passes = 4;
    CHECK_OK(op->tension_step(be.state, &tp, &ts, &err));
    CHECK_OK(op->correct(be.state, &cpp, &cst, &err));
    printf("correct: before %.3g after %.3g newton %d cg %d active %zu\n", cst.viol_before,
           cst.viol_after, cst.newton_iters, cst.cg_iters, cst.active_rows);
    CHECK(cst.viol_before > 1e-6);
    CHECK(cst.viol_after <= 1e-10);
    tr_measure m2;
    double ebar;
    CHECK_OK(op->measure(be.state, &m2, NULL, &ebar, &err));
    CHECK(m2.edge_dev < 1e-10);
    CHECK(m2.length < m0.length);
    CHECK_NEAR(m2.length, 120 * ebar, 1e-9);

    tr_backend_close(&be);
    tr_curve_free(&c);
    return tr_test_finish("test_engine_backend");
}
