/* The thickness oracle against closed forms (regular polygons, straight
 * segments, vertex-vertex struts, MinRad of corners), the endpoint
 * normal-wedge test, and the tree search against an all-pairs search. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/generate.h"
#include "geometry/neighbour_search.h"
#include "segment_distance.h"
#include "testlib.h"
#include "oracle/thickness.h"

static const double PI = 3.14159265358979323846;

/* Regular N-gon of circumradius R in the plane z = z0, centred at (cx, 0). */
static void put_ngon(double *x, size_t n, double R, double cx, double z0)
{
    for (size_t i = 0; i < n; i++) {
        double a = 2.0 * PI * (double)i / (double)n;
        x[3 * i] = cx + R * cos(a);
        x[3 * i + 1] = R * sin(a);
        x[3 * i + 2] = z0;
    }
}

static void test_regular_polygons(void)
{
    const size_t sizes[] = {4, 5, 6, 7, 8, 12, 31, 100, 1001, 100000};
    for (size_t q = 0; q < sizeof sizes / sizeof *sizes; q++) {
        size_t n = sizes[q];
        const double R = 1.3; /* edges < 2, so R_c is defined */
        tr_curve c;
        tr_error err;
        CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
        put_ngon(c.x, n, R, 0.0, 0.0);
        tr_thickness t;
        CHECK_OK(tr_thickness_measure(&c, NULL, &t, NULL, &err));
        double pn = PI / (double)n;
        double e = 2.0 * R * sin(pn);
        /* MinRad depends on the turning angle 2pi/N, which the rounding of
         * the coordinates (eps R) perturbs by eps R / e: relative error
         * ~ eps N^2 / (4 pi^2); 1e-15 N^2 leaves a factor 400. */
        double rtol = 1e-15 * (double)n * (double)n;
        /* Ropelength of the regular N-gon: 2 N tan(pi/N), scale-free. */
        CHECK_NEAR(t.ropelength, 2.0 * (double)n * tan(pn), rtol * t.ropelength);
        /* MinRad = e / (2 tan(pi/N)) = R cos(pi/N), the apothem. */
        CHECK_NEAR(t.minrad, R * cos(pn), rtol * R);
        if (n % 2 == 0) {
            /* Opposite edges are parallel: the strut joins their midpoints. */
            CHECK_NEAR(t.dcsd, 2.0 * R * cos(pn), 1e-12);
        } else {
            /* No two edges are parallel, and in a convex plane polygon the
             * closest points of two edges include an end vertex whose
             * partner lies inside the polygon, outside the vertex's normal
             * wedge: with octrope's definition (struts are closest-point
             * pairs of two edges) there is no strut. The vertex-to-opposite-
             * midpoint pair is critical but not a closest pair of edges. */
            CHECK(isinf(t.dcsd));
        }
        CHECK_NEAR(t.length, (double)n * e, 1e-12 * (double)n * e);
        /* Inscribed-arc length: N arcs of angle 2pi/N tangent at the edge
         * midpoints, radius MinRad, divided by R_c = sqrt(1 - e^2/4). */
        double L_c = 2.0 * PI * R * cos(pn) / sqrt(1.0 - 0.25 * e * e);
        CHECK_NEAR(t.L_p, (double)n * e, 1e-12 * t.length);
        CHECK_NEAR(t.L_c, L_c, 1e-13 * L_c);
        CHECK_NEAR(t.L_a, 0.8 * t.L_p + 0.2 * L_c, 1e-13 * L_c);
        tr_curve_free(&c);
    }
    /* The triangle has no pair of edges pi of turning apart: no strut. */
    size_t n = 3;
    tr_curve c;
    tr_error err;
    CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    put_ngon(c.x, n, 1.0, 0.0, 0.0);
    tr_thickness t;
    CHECK_OK(tr_thickness_measure(&c, NULL, &t, NULL, &err));
    CHECK(isinf(t.dcsd));
    CHECK_NEAR(t.thickness, cos(PI / 3), 1e-15);
    tr_curve_free(&c);
}

/* Ropelength does not change under translation. A regular 64-gon of
 * circumradius 5 with its coordinates rounded to multiples of 2^-12 moves
 * by 2^40 exactly (2^40 + x needs 52 bits for |x| < 8): it must measure as
 * at the origin, and within the grid's rounding of the closed form
 * 2 N tan(pi / N). Moved by 1e3, each coordinate is rounded by at most
 * u / 2, u the step between doubles at 1e3: the turning angle theta = 2 pi
 * / N moves by at most 2 u / h (h the edge) and the edges by u, so the
 * ropelength by less than 4 u / (h theta) relatively. Moved by 1e15 (u =
 * 0.125 against edges of 0.49) or 1e300 the numbers no longer hold the
 * shape: refused, and for that reason, not as "passes through itself" (as
 * it once was), nor measured as length 0 (1e300). In subnormal numbers
 * (the polygon times 2^-1070) it is refused too. */
static void test_far_from_origin(void)
{
    const size_t n = 64;
    const double R = 5.0, pn = PI / (double)n, h = 2.0 * R * sin(pn), theta = 2.0 * pn;
    const double want = 2.0 * (double)n * tan(pn);
    tr_curve c;
    tr_error err;
    CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    double grid = ldexp(1.0, -12);
    put_ngon(c.x, n, R, 0.0, 0.0);
    for (size_t i = 0; i < 3 * n; i++)
        c.x[i] = grid * round(c.x[i] / grid);
    tr_thickness t0, t1;
    tr_strut_list s0 = {0}, s1 = {0};
    tr_thickness_opts o = {.strut_rel_tol = 1e-3};
    CHECK_OK(tr_thickness_measure(&c, &o, &t0, &s0, &err));
    CHECK_NEAR(t0.ropelength, want, (4.0 * grid / (h * theta) + 4.0 * grid / h) * want);
    for (size_t i = 0; i < n; i++)
        c.x[3 * i] += ldexp(1.0, 40);
    CHECK_OK(tr_thickness_measure(&c, &o, &t1, &s1, &err));
    CHECK_NEAR(t1.ropelength, t0.ropelength, 1e-13 * want);
    CHECK_NEAR(t1.length, t0.length, 1e-13 * t0.length);
    CHECK_NEAR(t1.minrad, t0.minrad, 1e-13 * R);
    CHECK_NEAR(t1.dcsd, t0.dcsd, 1e-13 * R);
    CHECK(s1.n == s0.n);
    tr_strut_list_free(&s0);
    tr_strut_list_free(&s1);

    put_ngon(c.x, n, R, 1e3, 0.0);
    double u = nextafter(1e3, 2e3) - 1e3;
    CHECK_OK(tr_thickness_measure(&c, NULL, &t1, NULL, &err));
    CHECK_NEAR(t1.ropelength, want, (4.0 * u / (h * theta) + 1e-13) * want);

    const double far[] = {1e15, 1e100, 1e300};
    for (size_t q = 0; q < sizeof far / sizeof *far; q++) {
        put_ngon(c.x, n, R, far[q], 0.0);
        err.msg[0] = '\0';
        CHECK(tr_thickness_measure(&c, NULL, &t1, NULL, &err) == TR_EGEOMETRY);
        if (!strstr(err.msg, "far from the origin"))
            fprintf(stderr, "moved by %g: %s\n", far[q], err.msg);
        CHECK(strstr(err.msg, "far from the origin") != NULL);
    }
    put_ngon(c.x, n, R, 0.0, 0.0);
    for (size_t i = 0; i < 3 * n; i++)
        c.x[i] = ldexp(c.x[i], -1070);
    CHECK(tr_thickness_measure(&c, NULL, &t1, NULL, &err) == TR_EGEOMETRY);
    CHECK(strstr(err.msg, "subnormal") != NULL);
    tr_curve_free(&c);
}

/* Builds a curve of open/closed components from a flat coordinate list. */
static void make_curve(tr_curve *c, int ncomp, const size_t *nv, const unsigned char *closed,
                       const double *xyz)
{
    tr_error err;
    CHECK_OK(tr_curve_alloc(c, ncomp, nv, closed, &err));
    memcpy(c->x, xyz, 3 * c->nv * sizeof *xyz);
}

static void test_perpendicular_segments(void)
{
    /* Two straight ropes, perpendicular, 2.5 apart: one strut between the
     * midpoints, no vertex with two edges (MinRad infinite). */
    const double xyz[] = {-1, 0, 0, 1, 0, 0, 0, -1, 2.5, 0, 1, 2.5};
    size_t nv[2] = {2, 2};
    unsigned char closed[2] = {0, 0};
    tr_curve c;
    make_curve(&c, 2, nv, closed, xyz);
    tr_thickness t;
    tr_error err;
    tr_strut_list sl = {0};
    tr_thickness_opts o = {.strut_rel_tol = 0.0};
    CHECK_OK(tr_thickness_measure(&c, &o, &t, &sl, &err));
    CHECK_NEAR(t.dcsd, 2.5, 1e-15);
    CHECK(isinf(t.minrad));
    CHECK_NEAR(t.thickness, 1.25, 1e-15);
    CHECK_NEAR(t.ropelength, 4.0 / 1.25, 1e-14);
    CHECK(sl.n == 1);
    if (sl.n == 1) {
        CHECK(sl.s[0].ei == 1 && sl.s[0].ej == 0);
        CHECK_NEAR(sl.s[0].si, 0.5, 1e-15);
        CHECK_NEAR(sl.s[0].sj, 0.5, 1e-15);
    }
    CHECK(isnan(t.L_c) && isnan(t.L_a)); /* open components */
    tr_strut_list_free(&sl);
    tr_curve_free(&c);
}

static void test_normal_wedge(void)
{
    /* Rope A is an L: (-1,0,0) -> (0,0,0) -> (0,1,0). Rope B runs along z
     * through y = (-0.5,-1,0). For edge A1 = (0,0,0)->(0,1,0) the closest
     * point to B is its start vertex, at distance sqrt(1.25), but y is
     * behind the normal plane of A0 there (moving back along A0 brings the
     * ropes closer): not doubly critical. The only strut is A0-B, from
     * (-0.5,0,0) to y, length 1. */
    const double xyz[] = {-1, 0, 0, 0, 0, 0, 0, 1, 0, -0.5, -1, -1, -0.5, -1, 1};
    size_t nv[2] = {3, 2};
    unsigned char closed[2] = {0, 0};
    tr_curve c;
    make_curve(&c, 2, nv, closed, xyz);
    tr_thickness t;
    tr_error err;
    tr_strut_list sl = {0};
    tr_thickness_opts o = {.strut_rel_tol = 1.0}; /* everything up to 2 */
    CHECK_OK(tr_thickness_measure(&c, &o, &t, &sl, &err));
    CHECK_NEAR(t.dcsd, 1.0, 1e-15);
    CHECK(sl.n == 1);
    if (sl.n == 1) {
        CHECK(sl.s[0].ei == 2 && sl.s[0].ej == 0); /* B's edge is global edge 2 */
        CHECK_NEAR(sl.s[0].sj, 0.5, 1e-15);
    }
    /* MinRad of the one interior vertex: 90 degrees, shorter edge 1 -> 1/2. */
    CHECK_NEAR(t.minrad, 0.5, 1e-15);
    CHECK_NEAR(t.thickness, 0.5, 1e-15);
    tr_strut_list_free(&sl);
    tr_curve_free(&c);

    /* Two V's pointing at each other: the shortest strut joins the two
     * vertices (s = t = 0 on the outgoing edges); the end of the incoming
     * edge (s = 1) must not count it a second time. */
    const double vv[] = {-1, 1, 0, 0, 0, 0, 1, 1, 0, -1, -3, 0, 0, -2, 0, 1, -3, 0};
    size_t nv2[2] = {3, 3};
    make_curve(&c, 2, nv2, closed, vv);
    o.strut_rel_tol = 0.0;
    CHECK_OK(tr_thickness_measure(&c, &o, &t, &sl, &err));
    CHECK_NEAR(t.dcsd, 2.0, 1e-15);
    CHECK(sl.n == 1);
    if (sl.n == 1) {
        CHECK(sl.s[0].ei == 3 && sl.s[0].ej == 1);
        CHECK(sl.s[0].si == 0.0 && sl.s[0].sj == 0.0);
    }
    /* MinRad at a 90-degree corner with edges sqrt(2): sqrt(2)/2. */
    CHECK_NEAR(t.minrad, sqrt(2.0) / 2.0, 1e-15);
    tr_strut_list_free(&sl);
    tr_curve_free(&c);
}

static void test_segment_closest(void)
{
    double s, t;
    /* Skew: x-axis segment [0,2] and a z-parallel segment over (1, 1, .),
     * z in [-1, 3]: closest (1,0,0)-(1,1,0), distance 1, s = 1/2, t = 1/4. */
    const double a0[3] = {0, 0, 0}, a1[3] = {2, 0, 0}, b0[3] = {1, 1, -1}, b1[3] = {1, 1, 3};
    CHECK_NEAR(tr_segment_closest(a0, a1, b0, b1, &s, &t), 1.0, 1e-15);
    CHECK_NEAR(s, 0.5, 1e-15);
    CHECK_NEAR(t, 0.25, 1e-15);
    /* Parallel, overlapping in [1, 2] along x, 3 apart: the middle of the
     * overlap, s = 3/4 on [0,2], t = 1/4 on [1,3]. */
    const double c0[3] = {1, 3, 0}, c1[3] = {3, 3, 0};
    CHECK_NEAR(tr_segment_closest(a0, a1, c0, c1, &s, &t), 3.0, 1e-15);
    CHECK_NEAR(s, 0.75, 1e-15);
    CHECK_NEAR(t, 0.25, 1e-15);
    /* Collinear and apart: end to end. */
    const double d0[3] = {5, 0, 0}, d1[3] = {4, 0, 0};
    CHECK_NEAR(tr_segment_closest(a0, a1, d0, d1, &s, &t), 2.0, 1e-15);
    CHECK(s == 1.0 && t == 1.0);
}

static void test_minrad(void)
{
    /* Open chain with one interior vertex, turn of 60 degrees, unit edges:
     * MinRad = 1 / (2 tan 30deg) = sqrt(3)/2. End vertices do not count. */
    double c60 = cos(PI / 3), s60 = sin(PI / 3);
    const double xyz[] = {0, 0, 0, 1, 0, 0, 1 + c60, s60, 0};
    size_t nv = 3;
    unsigned char open = 0;
    tr_curve c;
    make_curve(&c, 1, &nv, &open, xyz);
    tr_thickness t;
    tr_error err;
    CHECK_OK(tr_thickness_measure(&c, NULL, &t, NULL, &err));
    CHECK_NEAR(t.minrad, sqrt(3.0) / 2.0, 1e-15);
    CHECK(t.minrad_vertex == 1);
    tr_curve_free(&c);
    /* Unequal edges 3 and 1 at a right angle: min(3,1) / (2 tan 45deg). */
    const double l[] = {0, 0, 0, 3, 0, 0, 3, 1, 0};
    make_curve(&c, 1, &nv, &open, l);
    CHECK_OK(tr_thickness_measure(&c, NULL, &t, NULL, &err));
    CHECK_NEAR(t.minrad, 0.5, 1e-15);
    tr_curve_free(&c);
    /* A 1 x 2 rectangle, closed: MinRad 1/2 at every corner; its edges are
     * far from equal, so L_c and L_a are not defined. */
    const double r[] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0};
    size_t n4 = 4;
    make_curve(&c, 1, &n4, NULL, r);
    CHECK_OK(tr_thickness_measure(&c, NULL, &t, NULL, &err));
    CHECK_NEAR(t.minrad, 0.5, 1e-15);
    CHECK_NEAR(t.dcsd, 1.0, 1e-15); /* the long edges, 1 apart */
    CHECK_NEAR(t.length, 6.0, 1e-15);
    CHECK(isnan(t.L_c) && isnan(t.L_p));
    tr_curve_free(&c);
    /* A hairpin: the rope runs out and folds straight back (turning angle pi).
     * The limit of MinRad as the turn angle -> pi is 0, so the fold has
     * thickness 0; treating the antiparallel edges as "straight" would call
     * it infinitely thick at that vertex. */
    const double hp[] = {0, 0, 0, 2, 0, 0, 1, 0, 0};
    make_curve(&c, 1, &nv, &open, hp);
    CHECK_OK(tr_thickness_measure(&c, NULL, &t, NULL, &err));
    CHECK(t.minrad == 0.0 && t.minrad_vertex == 1);
    CHECK(t.thickness == 0.0 && isinf(t.ropelength));
    tr_curve_free(&c);
}

static void test_components(void)
{
    /* Two regular 40-gons, radii 1 and 2, far apart: each alone has the
     * regular-polygon ropelength; together the thinner one sets Delta. */
    size_t nv[2] = {40, 40};
    tr_curve c;
    tr_error err;
    CHECK_OK(tr_curve_alloc(&c, 2, nv, NULL, &err));
    put_ngon(c.x, 40, 1.0, 0.0, 0.0);
    put_ngon(c.x + 120, 40, 2.0, 10.0, 0.0);
    double rl = 80.0 * tan(PI / 40);
    for (int k = 0; k < 2; k++) {
        tr_thickness t;
        CHECK_OK(tr_thickness_measure_component(&c, k, &t, &err));
        CHECK_NEAR(t.ropelength, rl, 1e-12 * rl);
        CHECK(t.minrad_vertex >= c.start[k] && t.minrad_vertex < c.start[k + 1]);
    }
    tr_thickness all;
    CHECK_OK(tr_thickness_measure(&c, NULL, &all, NULL, &err));
    CHECK_NEAR(all.thickness, cos(PI / 40), 1e-14);
    CHECK_NEAR(all.length, 3.0 * 40.0 * 2.0 * sin(PI / 40), 1e-12);
    tr_curve_free(&c);
}

static uint64_t rng_next(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}
static double rng_unit(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1.0p-53; }

static int strut_cmp(const void *a, const void *b)
{
    const tr_strut *p = a, *q = b;
    if (p->ei != q->ei)
        return p->ei < q->ei ? -1 : 1;
    if (p->ej != q->ej)
        return p->ej < q->ej ? -1 : 1;
    return 0;
}

/* Tree search and all-pairs search must give the same struts, bit for bit. */
static void compare_with_brute(const tr_curve *c, const char *what)
{
    tr_error err;
    tr_thickness a, b;
    tr_strut_list la = {0}, lb = {0};
    tr_thickness_opts o = {.strut_rel_tol = 0.05};
    CHECK_OK(tr_thickness_measure(c, &o, &a, &la, &err));
    o.brute_force = 1;
    CHECK_OK(tr_thickness_measure(c, &o, &b, &lb, &err));
    int same = a.dcsd == b.dcsd && la.n == lb.n;
    if (same && la.n) {
        qsort(la.s, la.n, sizeof *la.s, strut_cmp);
        qsort(lb.s, lb.n, sizeof *lb.s, strut_cmp);
        for (size_t i = 0; i < la.n; i++)
            same = same && la.s[i].ei == lb.s[i].ei && la.s[i].ej == lb.s[i].ej &&
                   la.s[i].dist == lb.s[i].dist;
    }
    if (!same)
        fprintf(stderr, "%s: tree dcsd %.17g (%zu struts), brute %.17g (%zu struts)\n", what, a.dcsd,
                la.n, b.dcsd, lb.n);
    CHECK(same);
    CHECK(isfinite(a.dcsd));
    tr_strut_list_free(&la);
    tr_strut_list_free(&lb);
}

static void test_tree_against_brute(void)
{
    uint64_t seed = 0x9e3779b97f4a7c15ull;
    tr_error err;
    for (int rep = 0; rep < 6; rep++) {
        /* A crumpled closed polygon (random points in a cube) and an open
         * random walk with unit steps, as one link. */
        size_t nv[2] = {150 + 37 * (size_t)rep, 200};
        unsigned char closed[2] = {1, 0};
        tr_curve c;
        CHECK_OK(tr_curve_alloc(&c, 2, nv, closed, &err));
        for (size_t i = 0; i < 3 * nv[0]; i++)
            c.x[i] = rng_unit(&seed);
        double *w = c.x + 3 * nv[0];
        w[0] = w[1] = w[2] = 0.5;
        for (size_t i = 1; i < nv[1]; i++) {
            double z = 2 * rng_unit(&seed) - 1, ph = 2 * PI * rng_unit(&seed);
            double r = sqrt(1 - z * z);
            w[3 * i] = w[3 * i - 3] + 0.1 * r * cos(ph);
            w[3 * i + 1] = w[3 * i - 2] + 0.1 * r * sin(ph);
            w[3 * i + 2] = w[3 * i - 1] + 0.1 * z;
        }
        char what[64];
        snprintf(what, sizeof what, "random link, seed step %d", rep);
        compare_with_brute(&c, what);
        tr_curve_free(&c);
    }
    /* Tight-ish smooth curves: torus knots T(2,3) and T(3,5) on a thin torus,
     * where many strands run close and parallel. */
    const int pq[2][2] = {{2, 3}, {3, 5}};
    for (int k = 0; k < 2; k++) {
        size_t n = 600;
        tr_curve c;
        CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
        int p = pq[k][0], q = pq[k][1];
        for (size_t i = 0; i < n; i++) {
            double ph = 2 * PI * (double)i / (double)n;
            double rr = 1.0 + 0.45 * cos(q * ph);
            c.x[3 * i] = rr * cos(p * ph);
            c.x[3 * i + 1] = rr * sin(p * ph);
            c.x[3 * i + 2] = 0.45 * sin(q * ph);
        }
        compare_with_brute(&c, k ? "torus T(3,5)" : "torus T(2,3)");
        tr_curve_free(&c);
    }
    /* Finer smooth curves, where runs of edges are queried together:
     * T(2,5) at N = 4000 and a Hopf link of two 900-gons (radius 1, each
     * through the other's centre, perpendicular planes). */
    {
        size_t n = 4000;
        tr_curve c;
        CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
        for (size_t i = 0; i < n; i++) {
            double ph = 2 * PI * (double)i / (double)n;
            double rr = 1.0 + 0.4 * cos(5 * ph);
            c.x[3 * i] = rr * cos(2 * ph);
            c.x[3 * i + 1] = rr * sin(2 * ph);
            c.x[3 * i + 2] = 0.4 * sin(5 * ph);
        }
        compare_with_brute(&c, "torus T(2,5), N = 4000");
        tr_curve_free(&c);
        size_t nv[2] = {900, 900};
        CHECK_OK(tr_curve_alloc(&c, 2, nv, NULL, &err));
        for (size_t i = 0; i < 900; i++) {
            double ph = 2 * PI * (double)i / 900.0;
            c.x[3 * i] = cos(ph);
            c.x[3 * i + 1] = sin(ph);
            c.x[3 * i + 2] = 0.0;
            c.x[2700 + 3 * i] = 1.0 + cos(ph);
            c.x[2700 + 3 * i + 1] = 0.0;
            c.x[2700 + 3 * i + 2] = sin(ph);
        }
        compare_with_brute(&c, "Hopf link, 2 x 900");
        tr_curve_free(&c);
    }
}

static int count_pair(void *ctx, size_t ei, size_t ej, double *cutoff)
{
    (void)ei;
    (void)ej;
    (void)cutoff;
    (*(size_t *)ctx)++;
    return 0;
}

static void test_index_exclusion(void)
{
    /* A closed 10-gon with min_gap 3 offers exactly the pairs whose cyclic
     * index distance is 3..7: 10 * 5 / 2 = 25; an open 10-vertex chain
     * (9 edges) offers pairs with |i-j| >= 3: 6+5+...+1 = 21. */
    size_t n = 10;
    tr_curve c;
    tr_error err;
    CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    put_ngon(c.x, n, 1.0, 0, 0);
    tr_nsearch ns;
    CHECK_OK(tr_nsearch_build(&ns, &c, &err));
    size_t cnt = 0;
    double cut = INFINITY;
    CHECK_OK(tr_nsearch_pairs(&ns, &cut, 3, 0, count_pair, &cnt));
    CHECK(cnt == 25);
    cnt = 0;
    CHECK_OK(tr_nsearch_pairs_brute(&ns, &cut, 3, 0, count_pair, &cnt));
    CHECK(cnt == 25);
    tr_nsearch_free(&ns);
    c.closed[0] = 0;
    CHECK_OK(tr_nsearch_build(&ns, &c, &err));
    cnt = 0;
    CHECK_OK(tr_nsearch_pairs(&ns, &cut, 3, 0, count_pair, &cnt));
    CHECK(cnt == 21);
    tr_nsearch_free(&ns);
    tr_curve_free(&c);
}

/* Pairs within the cutoff whose strut is within `tilt` of both normal
 * planes (the engine's contact list), counted from whatever is offered. */
typedef struct tilt_count {
    const tr_nsearch *ns;
    double cutoff, tilt;
    size_t offered, kept;
} tilt_count;

static int count_tilted(void *ctx, size_t ei, size_t ej, double *cutoff)
{
    (void)cutoff;
    tilt_count *t = ctx;
    const double *x = t->ns->c->x;
    const double *a0 = x + 3 * t->ns->ea[ej], *a1 = x + 3 * t->ns->eb[ej];
    const double *b0 = x + 3 * t->ns->ea[ei], *b1 = x + 3 * t->ns->eb[ei];
    double s, u;
    double d = tr_segment_distance(a0, a1, b0, b1, &s, &u);
    t->offered++;
    if (d < t->cutoff && tr_segment_nearly_normal(a0, a1, b0, b1, s, u, d, t->tilt))
        t->kept++;
    return 0;
}

/* The slab walk must offer every nearly normal pair the brute force finds
 * (its pruning is conservative), on a closed knot and an open rope, while
 * offering few more candidates than it keeps (brute force offers all). */
static void test_slab_search(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_torus(&c, 2, 3, 1500, &err));
    for (int open = 0; open <= 1; open++) {
        c.closed[0] = (unsigned char)!open;
        tr_nsearch ns;
        CHECK_OK(tr_nsearch_build(&ns, &c, &err));
        double tilts[] = {0.02, 0.2};
        for (int k = 0; k < 2; k++) {
            tilt_count slab = {.ns = &ns, .cutoff = 4.0, .tilt = tilts[k]};
            tilt_count brute = slab;
            CHECK_OK(tr_nsearch_pairs_slab(&ns, 4.0, 12, tilts[k] * 4.0, count_tilted, &slab));
            double cut = 4.0;
            CHECK_OK(tr_nsearch_pairs_brute(&ns, &cut, 12, 0, count_tilted, &brute));
            printf("slab search (%s, tilt %.2f): %zu of %zu offered kept, brute %zu of %zu\n",
                   open ? "open" : "closed", tilts[k], slab.kept, slab.offered, brute.kept, brute.offered);
            CHECK(brute.kept > 0);
            CHECK(slab.kept == brute.kept);
            CHECK(slab.offered < 3 * slab.kept + ns.ne); /* pruned close to what is kept */
        }
        /* without a slab (pad < 0) it is the plain cutoff search */
        tilt_count all = {.ns = &ns, .cutoff = 4.0, .tilt = 1.0}, ball = all;
        CHECK_OK(tr_nsearch_pairs_slab(&ns, 4.0, 12, -1.0, count_tilted, &all));
        double cut = 4.0;
        CHECK_OK(tr_nsearch_pairs(&ns, &cut, 12, 0, count_tilted, &ball));
        CHECK(all.kept == ball.kept && all.offered == ball.offered);
        tr_nsearch_free(&ns);
    }
    tr_curve_free(&c);
}

int main(void)
{
    test_slab_search();
    test_regular_polygons();
    test_far_from_origin();
    test_perpendicular_segments();
    test_normal_wedge();
    test_segment_closest();
    test_minrad();
    test_components();
    test_tree_against_brute();
    test_index_exclusion();
    return tr_test_finish("test_thickness");
}
