/* The vertex model (oracle/vertex_thickness.h) against closed forms (regular
 * polygons, scale free and at a fixed radius; two straight ropes; two
 * circles side by side) and against an all-pairs computation written here,
 * independently of the library's iteration, on torus knots and the clasp. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/generate.h"
#include "oracle/vertex_thickness.h"
#include "testlib.h"
#include "util/vec3.h"

static const double PI = 3.14159265358979323846;

static void put_ngon(double *x, size_t n, double R, double cx)
{
    for (size_t i = 0; i < n; i++) {
        double a = 2.0 * PI * (double)i / (double)n;
        x[3 * i] = cx + R * cos(a);
        x[3 * i + 1] = R * sin(a);
        x[3 * i + 2] = 0.0;
    }
}

/* Scale free, a regular n-gon's thickness is its MinRad, rho cos(pi/n): at
 * R = MinRad, K = ceil(pi R / e) = ceil(pi / (2 tan(pi/n))) ~ n/2, and the
 * vertices that far apart are 2 rho sin(pi K / n) ~ 2 rho > 2 R apart, or
 * none is, when K > n/2 (n = 7, 1001). */
static void test_regular_polygon_scale_free(void)
{
    const size_t sizes[] = {7, 12, 100, 1001};
    for (size_t q = 0; q < sizeof sizes / sizeof *sizes; q++) {
        size_t n = sizes[q];
        double rho = 7.0, pn = PI / (double)n;
        tr_curve c;
        tr_error err;
        REQUIRE_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
        put_ngon(c.x, n, rho, 0.0);
        tr_vertex_thickness v;
        CHECK_OK(tr_vertex_thickness_measure(&c, NULL, NULL, &v, &err));
        size_t K = (size_t)ceil(PI / (2.0 * tan(pn)));
        double rtol = 1e-15 * (double)n * (double)n; /* MinRad's rounding, as in test_thickness.c */
        CHECK(v.exclusion == K);
        CHECK_NEAR(v.edge, 2.0 * rho * sin(pn), 1e-14 * rho);
        if (2 * K <= n)
            CHECK_NEAR(v.vertex_dmin, 2.0 * rho * sin(pn * (double)K), 1e-14 * rho);
        else
            CHECK(isinf(v.vertex_dmin)); /* no two vertices are K apart the shorter way round */
        CHECK_NEAR(v.thickness, rho * cos(pn), rtol * rho);
        CHECK_NEAR(v.radius, v.thickness, 0.0);
        CHECK_NEAR(v.ropelength, 2.0 * (double)n * tan(pn), rtol * v.ropelength);
        tr_curve_free(&c);
    }
}

/* SP-FEM's own convention, a rope of radius 1 (bench/vertex_contacts): the
 * regular 100-gon of circumradius 7 has e = 14 sin(pi/100), K = ceil(pi /
 * e) = 8 (pi / e = 7.14), and vertices K apart are the closest that count:
 * k < K is excluded and the chords 2 rho sin(pi k / n) grow with k up to
 * n/2. Their half, 7 sin(8 pi/100) = 1.74, is below MinRad = 7 cos(pi/100). */
static void test_regular_polygon_fixed_radius(void)
{
    size_t n = 100;
    double rho = 7.0, pn = PI / (double)n, e = 2.0 * rho * sin(pn);
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    put_ngon(c.x, n, rho, 0.0);
    tr_vertex_opts o = {.radius = 1.0};
    tr_vertex_thickness v;
    CHECK_OK(tr_vertex_thickness_measure(&c, &o, NULL, &v, &err));
    CHECK(v.exclusion == 8);
    CHECK_NEAR(v.radius, 1.0, 0.0);
    double d = 2.0 * rho * sin(8.0 * pn);
    CHECK_NEAR(v.vertex_dmin, d, 1e-14);
    CHECK(v.vi - v.vj == 8 || v.vi - v.vj == n - 8);
    CHECK_NEAR(v.minrad, rho * cos(pn), 1e-15 * (double)(n * n) * rho);
    CHECK_NEAR(v.thickness, 0.5 * d, 1e-14);
    CHECK_NEAR(v.ropelength, (double)n * e / (0.5 * d), 1e-13);
    o.radius = -1.0;
    CHECK(tr_vertex_thickness_measure(&c, &o, NULL, &v, &err) == TR_EINVAL);
    tr_curve_free(&c);
}

/* Two straight open ropes of n vertices, spacing h, side by side at distance
 * D, the second shifted by h/2 along them: straight, so MinRad is infinite;
 * the closest vertices are on different ropes, sqrt(D^2 + h^2/4) apart, and
 * vertices of one rope at least K = ceil(pi R / h) apart are >= K h > 2 R
 * apart: the thickness is R = sqrt(D^2 + h^2/4) / 2. */
static void test_parallel_ropes(void)
{
    size_t nv[2] = {50, 50};
    unsigned char closed[2] = {0, 0};
    double h = 0.125, D = 2.0; /* binary fractions: the coordinates are exact */
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 2, nv, closed, &err));
    for (size_t i = 0; i < 50; i++) {
        double *a = c.x + 3 * i, *b = c.x + 3 * (50 + i);
        a[0] = h * (double)i;
        b[0] = h * (double)i + 0.5 * h;
        b[1] = D;
    }
    tr_vertex_thickness v;
    CHECK_OK(tr_vertex_thickness_measure(&c, NULL, NULL, &v, &err));
    double d = sqrt(D * D + 0.25 * h * h), R = 0.5 * d;
    CHECK(isinf(v.minrad));
    CHECK_NEAR(v.vertex_dmin, d, 0.0);
    CHECK_NEAR(v.thickness, R, 0.0);
    CHECK(v.exclusion == (size_t)ceil(PI * R / h));
    CHECK_NEAR(v.edge, h, 0.0);
    CHECK_NEAR(v.ropelength, 2.0 * 49.0 * h / R, 1e-15 * v.ropelength);
    /* One rope alone: no pair counts, as in Rawdon's measure (infinitely thick). */
    size_t one = 50;
    tr_curve s;
    REQUIRE_OK(tr_curve_alloc(&s, 1, &one, closed, &err));
    memcpy(s.x, c.x, 150 * sizeof *s.x);
    CHECK_OK(tr_vertex_thickness_measure(&s, NULL, NULL, &v, &err));
    CHECK(isinf(v.vertex_dmin) && isinf(v.thickness) && v.exclusion == SIZE_MAX && v.ropelength == 0.0);
    tr_curve_free(&s);
    tr_curve_free(&c);
}

/* Two regular 60-gons of circumradius 1.5 in one plane, centres 5 apart,
 * vertex 0 of the first facing vertex 30 of the second: those are 5 - 3 = 2
 * apart, below 2 MinRad = 3 cos(pi/60); within one polygon the vertices
 * K = ceil(pi / e) = 21 apart (e = 3 sin(pi/60)) are 3 sin(21 pi/60) = 2.67
 * apart. So the thickness is 1 and the ropelength 2 * 60 e. */
static void test_two_circles(void)
{
    size_t nv[2] = {60, 60};
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 2, nv, NULL, &err));
    put_ngon(c.x, 60, 1.5, 0.0);
    put_ngon(c.x + 180, 60, 1.5, 5.0);
    tr_vertex_thickness v;
    CHECK_OK(tr_vertex_thickness_measure(&c, NULL, NULL, &v, &err));
    double e = 3.0 * sin(PI / 60.0);
    CHECK_NEAR(v.vertex_dmin, 2.0, 1e-15);
    CHECK(v.vi == 90 && v.vj == 0);
    CHECK_NEAR(v.thickness, 1.0, 1e-15);
    CHECK(v.exclusion == 21);
    CHECK_NEAR(v.ropelength, 120.0 * e, 1e-13);
    tr_curve_free(&c);
}

/* The definition, all pairs, computed another way than the library's
 * iteration: m[g] the least squared distance of pairs g apart along one
 * component (the shorter way round), x the least between components; d(k)
 * = min(x, min_{g >= k} m[g]). A radius R is feasible when R <= MinRad and
 * R <= d(K(R)) / 2; the R with K(R) = k form the interval ((k-1) e/pi, k
 * e/pi], so the largest feasible R is the largest min(MinRad, d(k)/2,
 * k e/pi) that lies in its interval. Returns it and d(K(R)) in *dmin. */
static double brute_thickness(const tr_curve *c, double minrad, double length, double radius, size_t *Kout,
                              double *dmin)
{
    size_t gmax = 0, ne = 0;
    for (int k = 0; k < c->ncomp; k++) {
        gmax = tr_comp_nv(c, k) > gmax ? tr_comp_nv(c, k) : gmax;
        ne += tr_comp_ne(c, k);
    }
    double e = length / (double)ne;
    double *m = malloc((gmax + 2) * sizeof *m);
    for (size_t g = 0; g < gmax + 2; g++)
        m[g] = INFINITY;
    double x = INFINITY;
    for (int ka = 0; ka < c->ncomp; ka++)
        for (int kb = 0; kb <= ka; kb++)
            for (size_t i = c->start[ka]; i < c->start[ka + 1]; i++)
                for (size_t j = c->start[kb]; j < (ka == kb ? i : c->start[kb + 1]); j++) {
                    double d2 = v3_dist2(c->x + 3 * i, c->x + 3 * j);
                    if (ka != kb) {
                        x = fmin(x, d2);
                        continue;
                    }
                    size_t g = i - j, n = tr_comp_nv(c, ka);
                    if (c->closed[ka] && n - g < g)
                        g = n - g;
                    m[g] = fmin(m[g], d2);
                }
    for (size_t g = gmax + 1; g-- > 0;)
        m[g] = fmin(m[g], m[g + 1]); /* suffix minimum: d(k)^2 without x */
    double best = -1.0;
    size_t bestK = 0;
    if (radius > 0) {
        bestK = (size_t)ceil(PI * radius / e);
        best = fmin(minrad, 0.5 * sqrt(fmin(x, m[bestK < gmax + 1 ? bestK : gmax + 1])));
    } else {
        for (size_t k = 1; k <= gmax + 1; k++) {
            double hi = k <= gmax ? (double)k * e / PI : INFINITY;
            double r = fmin(fmin(minrad, 0.5 * sqrt(fmin(x, m[k]))), hi);
            if (r > (double)(k - 1) * e / PI && r > best) {
                best = r;
                bestK = k;
            }
        }
    }
    if (bestK > gmax) /* only pairs between components */
        bestK = isinf(best) ? SIZE_MAX : (size_t)ceil(PI * best / e);
    *dmin = sqrt(fmin(x, m[bestK < gmax + 1 ? bestK : gmax + 1]));
    *Kout = bestK;
    free(m);
    return best;
}

static void compare_with_brute(const tr_curve *c, const char *what)
{
    tr_error err;
    for (int fixed = 0; fixed < 2; fixed++) {
        tr_vertex_opts o = {.radius = fixed ? 1.0 : 0.0};
        tr_vertex_thickness v, b;
        CHECK_OK(tr_vertex_thickness_measure(c, &o, NULL, &v, &err));
        o.brute_force = 1;
        CHECK_OK(tr_vertex_thickness_measure(c, &o, NULL, &b, &err));
        size_t K;
        double d, th = brute_thickness(c, v.minrad, v.length, o.radius, &K, &d);
        int ok = v.exclusion == K && v.vertex_dmin == d && v.thickness == th && b.exclusion == K &&
                 b.vertex_dmin == d && b.thickness == th;
        if (!ok)
            tr_test_report(__FILE__, __LINE__, "%s (%s): K %zu / %zu / %zu, dmin %.17g / %.17g / %.17g", what,
                           fixed ? "radius 1" : "scale free", v.exclusion, b.exclusion, K, v.vertex_dmin,
                           b.vertex_dmin, d);
        CHECK(ok);
        CHECK(v.ropelength == v.length / th);
    }
}

static void test_against_brute(void)
{
    const int pq[][2] = {{2, 3}, {3, 5}, {2, 7}};
    const size_t ns[] = {300, 451, 640};
    tr_error err;
    for (size_t t = 0; t < 3; t++) {
        tr_curve c;
        REQUIRE_OK(tr_make_torus(&c, pq[t][0], pq[t][1], ns[t], &err));
        char what[64];
        snprintf(what, sizeof what, "T(%d,%d) N %zu", pq[t][0], pq[t][1], ns[t]);
        compare_with_brute(&c, what);
        /* Scaled by 2^-1000 the curve is measured in its frame (thickness.c):
         * the same numbers, exactly scaled. */
        tr_vertex_thickness v, s;
        CHECK_OK(tr_vertex_thickness_measure(&c, NULL, NULL, &v, &err));
        for (size_t i = 0; i < 3 * c.nv; i++)
            c.x[i] = ldexp(c.x[i], -1000);
        CHECK_OK(tr_vertex_thickness_measure(&c, NULL, NULL, &s, &err));
        CHECK(s.exclusion == v.exclusion && s.vertex_dmin == ldexp(v.vertex_dmin, -1000) &&
              s.ropelength == v.ropelength);
        tr_curve_free(&c);
    }
    /* Open ropes: the clasp, its end vertices included. */
    tr_curve c;
    REQUIRE_OK(tr_make_clasp(&c, 200, 4.0, &err));
    compare_with_brute(&c, "clasp 2 x 200");
    tr_curve_free(&c);
    REQUIRE_OK(tr_make_hopf(&c, 150, &err));
    compare_with_brute(&c, "Hopf 2 x 150");
    tr_curve_free(&c);
    /* a link of a small and a large component: K, from the whole curve's
     * mean edge, is larger than the hexagon's 6 vertices (K mod 6 = 0 at
     * 2100 circle vertices paired each hexagon vertex with itself: thickness
     * 0.015 where it is the hexagon's sqrt(3)/2) */
    size_t nv[2] = {6, 2100};
    REQUIRE_OK(tr_curve_alloc(&c, 2, nv, NULL, &err));
    put_ngon(c.x, 6, 1.0, 0.0);
    put_ngon(c.x + 18, 2100, 10.0, 0.0);
    for (size_t i = 6; i < 2106; i++)
        c.x[3 * i + 2] = 50.0;
    compare_with_brute(&c, "hexagon and a 2100-gon");
    tr_vertex_thickness v;
    CHECK_OK(tr_vertex_thickness_measure(&c, NULL, NULL, &v, &err));
    CHECK_NEAR(v.thickness, sqrt(3.0) / 2.0, 1e-12);
    tr_curve_free(&c);
}

int main(void)
{
    test_regular_polygon_scale_free();
    test_regular_polygon_fixed_radius();
    test_parallel_ropes();
    test_two_circles();
    test_against_brute();
    return tr_test_finish("test_vertex_thickness");
}
