/* Tests the open rope's refinement along inscribed arcs (engine/refine_arcs.h)
 * against closed forms:
 *  - a rope on a circle (an open regular polygon inscribed in a circle of
 *    radius R, tilted out of every coordinate plane) refines to points on
 *    that circle, to rounding, at equal arclength of the circle, its end
 *    vertices kept exactly; so every new vertex's circumcircle is the same
 *    circle (curvature 1 / R), which linear resampling's kept corners and
 *    straight chords do not give;
 *  - a straight rope stays on its line at equal spacing;
 *  - a rope that turns from an arc of radius 1 onto a straight line (the
 *    clasp's K meeting D2, the case the refinement is for) refines with no
 *    vertex more curved than 1, where linear resampling overshoots. */
#include <math.h>
#include <stdio.h>

#include "curve/curve.h"
#include "engine/refine_arcs.h"
#include "testlib.h"
#include "util/vec3.h"

#define PI 3.14159265358979323846

/* curvature of the circle through three points */
static double circum_kappa(const double *a, const double *b, const double *c)
{
    double u[3], v[3], w[3], x[3];
    v3_sub(u, b, a);
    v3_sub(v, c, b);
    v3_sub(w, c, a);
    v3_cross(x, u, v);
    return 2.0 * v3_norm(x) / (v3_norm(u) * v3_norm(v) * v3_norm(w));
}

static void test_circle(void)
{
    const size_t n = 20, m = 57;
    const double R = 2.5, span = 2.0 * PI / 3.0;
    /* the circle in a tilted plane: e1, e2 orthonormal, centre c0 */
    const double c0[3] = {0.3, -1.2, 0.7};
    double e1[3] = {1.0, 2.0, 2.0}, e2[3] = {2.0, -2.0, 1.0};
    v3_scale(e1, 1.0 / 3.0, e1);
    v3_scale(e2, 1.0 / 3.0, e2);
    tr_error err;
    tr_curve c;
    unsigned char open = 0;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, &open, &err));
    for (size_t i = 0; i < n; i++) {
        double t = span * (double)i / (double)(n - 1);
        for (int d = 0; d < 3; d++)
            c.x[3 * i + d] = c0[d] + R * (cos(t) * e1[d] + sin(t) * e2[d]);
    }
    double y[3 * 57];
    REQUIRE_OK(tr_refine_arcs_open(&c, 0, m, y, &err));
    double off = 0.0, spacing = 0.0, kap = 0.0;
    for (size_t i = 0; i < m; i++) {
        double p[3], a1, a2;
        v3_sub(p, y + 3 * i, c0);
        off = fmax(off, fabs(v3_norm(p) - R));
        /* equal arclength: the angle of vertex i is span i / (m - 1) */
        a1 = v3_dot(p, e1);
        a2 = v3_dot(p, e2);
        spacing = fmax(spacing, fabs(atan2(a2, a1) - span * (double)i / (double)(m - 1)));
        if (i > 0 && i + 1 < m)
            kap = fmax(kap, fabs(circum_kappa(y + 3 * (i - 1), y + 3 * i, y + 3 * (i + 1)) - 1.0 / R));
    }
    printf("circle: off the circle %.1e, angle error %.1e, curvature error %.1e\n", off, spacing, kap);
    CHECK(off < 1e-12);
    CHECK(spacing < 1e-12);
    CHECK(kap < 1e-9);
    CHECK(y[0] == c.x[0] && y[1] == c.x[1] && y[2] == c.x[2]);
    CHECK(y[3 * (m - 1)] == c.x[3 * (n - 1)] && y[3 * (m - 1) + 2] == c.x[3 * (n - 1) + 2]);
    tr_curve_free(&c);
}

static void test_line(void)
{
    const size_t n = 7, m = 19;
    tr_error err;
    tr_curve c;
    unsigned char open = 0;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, &open, &err));
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++)
            c.x[3 * i + d] = (double)i * (d + 1.0) * 0.25;
    double y[3 * 19];
    REQUIRE_OK(tr_refine_arcs_open(&c, 0, m, y, &err));
    double worst = 0.0;
    for (size_t i = 0; i < m; i++)
        for (int d = 0; d < 3; d++)
            worst = fmax(worst, fabs(y[3 * i + d] - (double)(n - 1) * (double)i / (double)(m - 1) * (d + 1.0) * 0.25));
    printf("line: off the equal spacing %.1e\n", worst);
    CHECK(worst < 1e-13);
    tr_curve_free(&c);
}

/* an arc of radius 1 (a quarter turn) continued by a straight line */
static void test_arc_to_line(void)
{
    const size_t na = 16, nl = 16, n = na + nl;
    tr_error err;
    tr_curve c;
    unsigned char open = 0;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, &open, &err));
    double h = 0.5 * PI / (double)(na - 1); /* the arc's step angle: edge 2 sin(h / 2) */
    double edge = 2.0 * sin(0.5 * h);
    for (size_t i = 0; i < na; i++) {
        double t = h * (double)i;
        c.x[3 * i] = sin(t);
        c.x[3 * i + 1] = 1.0 - cos(t);
        c.x[3 * i + 2] = 0.0;
    }
    for (size_t j = 1; j <= nl; j++) { /* along +y from (1, 1) */
        c.x[3 * (na + j - 1)] = 1.0;
        c.x[3 * (na + j - 1) + 1] = 1.0 + edge * (double)j;
        c.x[3 * (na + j - 1) + 2] = 0.0;
    }
    const size_t m = 2 * n + 5;
    double y[3 * (2 * 32 + 5)];
    REQUIRE_OK(tr_refine_arcs_open(&c, 0, m, y, &err));
    double kmax = 0.0;
    for (size_t i = 1; i + 1 < m; i++)
        kmax = fmax(kmax, circum_kappa(y + 3 * (i - 1), y + 3 * i, y + 3 * (i + 1)));
    /* the coarse polygon's own most curved vertex, as the oracle's circle */
    double kc = 0.0;
    for (size_t i = 1; i + 1 < n; i++)
        kc = fmax(kc, circum_kappa(c.x + 3 * (i - 1), c.x + 3 * i, c.x + 3 * (i + 1)));
    printf("arc to line: largest curvature %.9f (the coarse polygon's %.9f)\n", kmax, kc);
    CHECK(kmax <= kc * (1.0 + 1e-9));
    tr_curve_free(&c);
}

int main(void)
{
    test_circle();
    test_line();
    test_arc_to_line();
    return tr_test_failures ? 1 : 0;
}
