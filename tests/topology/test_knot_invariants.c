/* The knot type from a curve (topology/knot_diagram.h, topology/alexander.h),
 * held against closed forms, never against its own output:
 *  - torus knots T(p,q): Delta = (t^pq - 1)(t - 1) / ((t^p - 1)(t^q - 1)),
 *    divided out here in integers; determinant |Delta(-1)|;
 *  - unknots: a circle, T(5,1) (a spiral of 4 crossings seen from above),
 *    a circle with 11 curls (Reidemeister I kinks): Delta = 1;
 *  - the figure eight, (2 + cos 2t) cos 3t, (2 + cos 2t) sin 3t, sin 4t:
 *    -t^-1 + 3 - t, determinant 5;
 *  - invariance: rotated, translated, resampled finer, mirrored, seen from
 *    other directions: the same polynomial;
 *  - PD codes as KnotInfo writes them (3_1, 4_1, 5_2, 5_1), and bad ones;
 *  - refusals: a link, an open rope, a curve through itself;
 *  - the size the tight curves have: 10^5 vertices. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "curve/curve.h"
#include "curve/generate.h"
#include "testlib.h"
#include "topology/alexander.h"
#include "topology/knot_diagram.h"
#include "util/splitmix64.h"

#define PI 3.14159265358979323846

/* ---- closed forms ---- */

/* The torus knot's Delta by exact long division of integer polynomials
 * (both divisors are monic); coefficients of t^0 .. t^(p-1)(q-1). */
static int torus_alexander(int p, int q, long long *out)
{
    int deg = p * q + 1; /* p q <= 126 here */
    long long num[128] = {0};
    /* (t^pq - 1)(t - 1) = t^(pq+1) - t^pq - t + 1 */
    num[p * q + 1] += 1;
    num[p * q] -= 1;
    num[1] -= 1;
    num[0] += 1;
    int div[2] = {p, q};
    for (int k = 0; k < 2; k++) {
        int d = div[k];
        long long quo[128] = {0};
        for (int i = deg; i >= d; i--) {
            long long c = num[i];
            quo[i - d] = c;
            num[i] -= c;     /* c t^(i-d) * t^d */
            num[i - d] += c; /* c t^(i-d) * (-1), subtracted */
        }
        for (int i = 0; i < d; i++)
            if (num[i] != 0)
                return -1; /* not exact: cannot happen for coprime p, q */
        deg -= d;
        memcpy(num, quo, sizeof num);
    }
    memcpy(out, num, (size_t)(deg + 1) * sizeof *out);
    return deg;
}

static long long at_minus_one(const long long *c, int span)
{
    long long v = 0;
    for (int k = 0; k <= span; k++)
        v += (k % 2 ? -1 : 1) * c[k];
    return v < 0 ? -v : v;
}

static int same_poly(const tr_alexander *a, const long long *want, int span)
{
    if (a->span != span)
        return 0;
    for (int k = 0; k <= span; k++)
        if (a->coef[k] != want[k])
            return 0;
    return 1;
}

static void print_poly(const char *what, const tr_alexander *a)
{
    printf("  %s: span %d, coefficients", what, a->span);
    for (int k = 0; k <= a->span; k++)
        printf(" %lld", a->coef[k]);
    printf(", determinant %lld\n", a->determinant);
}

/* ---- curves ---- */

typedef void (*param_curve)(double t, double *x);

static int sample(tr_curve *c, size_t n, param_curve f)
{
    tr_error err;
    int rc = tr_curve_alloc(c, 1, &n, NULL, &err);
    if (rc)
        return rc;
    for (size_t i = 0; i < n; i++)
        f(2 * PI * (double)i / (double)n, c->x + 3 * i);
    return 0;
}

static void figure_eight(double t, double *x)
{
    double r = 2 + cos(2 * t);
    x[0] = r * cos(3 * t);
    x[1] = r * sin(3 * t);
    x[2] = sin(4 * t);
}

/* T(5,1): five times round the z axis, once round the core: the unknot,
 * whose view from above is a spiral with 4 crossings */
static void torus_5_1(double t, double *x)
{
    double r = 3 + cos(t);
    x[0] = r * cos(5 * t);
    x[1] = r * sin(5 * t);
    x[2] = sin(t);
}

/* A circle with 11 small curls (an epitrochoid, 12 turns of radius 0.2 on
 * one of radius 1): every crossing of its view from above is a kink. The
 * height sin 11t is odd about each curl's middle, so the two strands of a
 * curl pass at different heights. */
static void curly_circle(double t, double *x)
{
    x[0] = cos(t) + 0.2 * cos(12 * t);
    x[1] = sin(t) + 0.2 * sin(12 * t);
    x[2] = 0.1 * sin(11 * t);
}

static void flat_curly_circle(double t, double *x)
{
    x[0] = cos(t) + 0.2 * cos(12 * t);
    x[1] = sin(t) + 0.2 * sin(12 * t);
    x[2] = 0;
}

static void mirror(tr_curve *c)
{
    for (size_t i = 0; i < c->nv; i++)
        c->x[3 * i + 2] = -c->x[3 * i + 2];
}

/* A random rotation (unit quaternion from the seeded stream), then a
 * translation far from the origin. */
static void move(tr_curve *c, uint64_t seed)
{
    uint64_t s = seed;
    double q[4], n2 = 0;
    for (int k = 0; k < 4; k++) {
        q[k] = 2.0 * ((double)(tr_splitmix64(&s) >> 11) * 0x1p-53) - 1.0;
        n2 += q[k] * q[k];
    }
    for (int k = 0; k < 4; k++)
        q[k] /= sqrt(n2);
    double w = q[0], x = q[1], y = q[2], z = q[3];
    double R[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                   2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                   2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    const double shift[3] = {1234.5, -77.25, 3.0};
    for (size_t i = 0; i < c->nv; i++) {
        double *p = c->x + 3 * i, o[3];
        for (int r = 0; r < 3; r++)
            o[r] = R[3 * r] * p[0] + R[3 * r + 1] * p[1] + R[3 * r + 2] * p[2] + shift[r];
        memcpy(p, o, sizeof o);
    }
}

/* Delta of c as a check against want (span, coefficients); the diagram's
 * PD code is also run through tr_alexander_from_pd's validation. */
static void check_knot(const char *name, const tr_curve *c, const long long *want, int span)
{
    tr_knot_invariants inv;
    tr_error err;
    int rc = tr_knot_invariants_of(c, &inv, &err);
    if (rc) {
        printf("  %s: %s\n", name, err.msg);
        CHECK(rc == 0);
        return;
    }
    int ok = same_poly(&inv.alexander, want, span);
    printf("  %s: %d crossings (%d in the projection)%s\n", name, inv.crossings, inv.projected_crossings,
           ok ? "" : " WRONG");
    if (!ok)
        print_poly(name, &inv.alexander);
    CHECK(ok);
    CHECK(inv.alexander.determinant == at_minus_one(want, span));
}

static void test_torus_knots(void)
{
    printf("torus knots T(p,q) against (t^pq - 1)(t - 1) / ((t^p - 1)(t^q - 1)):\n");
    /* the last three take the exact arithmetic past 20 crossings */
    const int pq[][2] = {{2, 3}, {2, 5}, {2, 7}, {3, 4}, {3, 5}, {2, 9}, {2, 41}, {4, 7}, {5, 6}};
    /* |Delta(-1)| of T(p,q): the even one of p, q when there is one, else 1 */
    const long long det_want[] = {3, 5, 7, 3, 1, 9, 41, 7, 5};
    for (size_t i = 0; i < sizeof pq / sizeof pq[0]; i++) {
        int p = pq[i][0], q = pq[i][1];
        long long want[128];
        int span = torus_alexander(p, q, want);
        CHECK(span == (p - 1) * (q - 1));
        CHECK(at_minus_one(want, span) == det_want[i]);
        tr_curve c = {0};
        tr_error err;
        char name[64];
        snprintf(name, sizeof name, "T(%d,%d)", p, q);
        if (tr_make_torus(&c, p, q, p * q > 20 ? 800 : 200, &err)) {
            printf("  %s: %s\n", name, err.msg);
            CHECK(0);
            continue;
        }
        check_knot(name, &c, want, span);
        /* the mirror image has the same polynomial */
        mirror(&c);
        snprintf(name, sizeof name, "T(%d,%d) mirrored", p, q);
        check_knot(name, &c, want, span);
        tr_curve_free(&c);
    }
}

/* The crossing signs: the 3-crossing diagram of T(2,3) has one sign
 * throughout (a torus knot is a positive or a negative braid's closure),
 * and its mirror image, seen from the same direction, the other. */
static void test_signs(void)
{
    printf("crossing signs:\n");
    tr_curve c = {0};
    tr_error err;
    REQUIRE_OK(tr_make_torus(&c, 2, 3, 200, &err));
    int writhe[2] = {0, 0};
    const double dir[3] = {0.1, 0.2, 1.0};
    for (int m = 0; m < 2; m++) {
        tr_knot_diagram d;
        CHECK_OK(tr_knot_diagram_along(&c, dir, &d, &err));
        CHECK(d.ncross == 3);
        for (int k = 0; k < d.ncross; k++)
            writhe[m] += d.sign[k];
        /* the Gauss code alternates over and under, as T(2,3)'s minimal diagram does */
        for (int k = 0; k < 2 * d.ncross; k++)
            CHECK((d.gauss[k] > 0) != (d.gauss[(k + 1) % (2 * d.ncross)] > 0));
        tr_knot_diagram_free(&d);
        /* mirror through the plane z = 0 keeps the view from dir's side */
        mirror(&c);
    }
    printf("  writhe %d, mirrored %d\n", writhe[0], writhe[1]);
    CHECK(abs(writhe[0]) == 3 && writhe[1] == -writhe[0]);
    tr_curve_free(&c);
}

static void test_unknots(void)
{
    printf("unknots:\n");
    const long long one[1] = {1};
    tr_curve c = {0};
    tr_error err;
    if (tr_make_circle(&c, 5.0, 64, &err) == 0) {
        check_knot("circle", &c, one, 0);
        tr_knot_diagram d;
        CHECK_OK(tr_knot_diagram_of(&c, &d, &err));
        CHECK(d.ncross == 0 && d.projected_crossings == 0);
        tr_knot_diagram_free(&d);
    } else {
        CHECK(0);
    }
    tr_curve_free(&c);

    CHECK_OK(sample(&c, 1000, torus_5_1));
    check_knot("T(5,1)", &c, one, 0);
    /* seen from above the spiral's 4 crossings, none of them a kink */
    tr_knot_diagram d;
    const double up[3] = {0.001, 0.002, 1}; /* straight down, each vertex would lie on 4 others' plumb line */
    CHECK_OK(tr_knot_diagram_along(&c, up, &d, &err));
    printf("  T(5,1) from above: %d crossings, %d after removing kinks\n", d.projected_crossings, d.ncross);
    CHECK(d.projected_crossings == 4);
    tr_alexander a;
    CHECK_OK(tr_alexander_from_pd((const int(*)[4])d.pd, d.ncross, &a, &err));
    CHECK(a.span == 0 && a.coef[0] == 1);
    tr_knot_diagram_free(&d);
    tr_curve_free(&c);

    CHECK_OK(sample(&c, 2000, curly_circle));
    check_knot("circle with 11 curls", &c, one, 0);
    CHECK_OK(tr_knot_diagram_along(&c, up, &d, &err));
    printf("  circle with 11 curls from above: %d crossings, %d after removing kinks\n", d.projected_crossings,
           d.ncross);
    CHECK(d.projected_crossings == 11 && d.ncross == 0);
    tr_knot_diagram_free(&d);
    tr_curve_free(&c);
}

static void test_figure_eight(void)
{
    printf("figure eight:\n");
    const long long want[3] = {-1, 3, -1};
    tr_curve c = {0};
    CHECK_OK(sample(&c, 1500, figure_eight));
    check_knot("figure eight", &c, want, 2);
    tr_knot_invariants inv;
    tr_error err;
    CHECK_OK(tr_knot_invariants_of(&c, &inv, &err));
    CHECK(inv.alexander.determinant == 5);
    CHECK(inv.crossings >= 4); /* its crossing number */
    mirror(&c);
    check_knot("figure eight mirrored", &c, want, 2);
    tr_curve_free(&c);
}

/* The same knot moved, resampled finer and seen from many directions. */
static void test_invariance(void)
{
    printf("invariance (rotation, translation, resampling, direction):\n");
    const long long trefoil[3] = {1, -1, 1}, fig8[3] = {-1, 3, -1};
    long long t34[7];
    int span34 = torus_alexander(3, 4, t34);
    tr_error err;
    for (int k = 0; k < 3; k++) {
        tr_curve c = {0}, fine = {0};
        const long long *want = k == 0 ? trefoil : (k == 1 ? fig8 : t34);
        int span = k == 2 ? span34 : 2;
        int rc = k == 0 ? tr_make_torus(&c, 2, 3, 300, &err)
                        : (k == 1 ? sample(&c, 800, figure_eight) : tr_make_torus(&c, 3, 4, 300, &err));
        CHECK_OK(rc);
        if (rc)
            continue;
        move(&c, 0x1234u + (uint64_t)k);
        size_t n3 = 3 * c.nv;
        CHECK_OK(tr_resample_smooth(&c, &n3, &fine, &err));
        const char *names[3] = {"trefoil moved and resampled", "figure eight moved and resampled",
                                "T(3,4) moved and resampled"};
        check_knot(names[k], &fine, want, span);
        /* every generic direction of a seeded list gives the same Delta */
        uint64_t s = 99 + (uint64_t)k;
        int generic = 0;
        for (int j = 0; j < 12; j++) {
            double dir[3];
            for (int a = 0; a < 3; a++)
                dir[a] = 2.0 * ((double)(tr_splitmix64(&s) >> 11) * 0x1p-53) - 1.0;
            tr_knot_diagram d;
            if (tr_knot_diagram_along(&fine, dir, &d, &err) == 0) {
                tr_alexander a;
                generic++;
                CHECK_OK(tr_alexander_from_pd((const int(*)[4])d.pd, d.ncross, &a, &err));
                CHECK(same_poly(&a, want, span));
            }
            tr_knot_diagram_free(&d);
        }
        CHECK(generic >= 10);
        tr_curve_free(&c);
        tr_curve_free(&fine);
    }
}

/* PD codes as KnotInfo lists them (pd_notation), Delta from Rolfsen's table. */
static void test_pd_codes(void)
{
    printf("PD codes:\n");
    tr_alexander a;
    tr_error err;
    const int k31[3][4] = {{1, 5, 2, 4}, {3, 1, 4, 6}, {5, 3, 6, 2}};
    CHECK_OK(tr_alexander_from_pd(k31, 3, &a, &err));
    const long long w31[3] = {1, -1, 1};
    CHECK(same_poly(&a, w31, 2) && a.determinant == 3);
    const int k41[4][4] = {{4, 2, 5, 1}, {8, 6, 1, 5}, {6, 3, 7, 4}, {2, 7, 3, 8}};
    CHECK_OK(tr_alexander_from_pd(k41, 4, &a, &err));
    const long long w41[3] = {-1, 3, -1};
    CHECK(same_poly(&a, w41, 2) && a.determinant == 5);
    const int k51[5][4] = {{2, 8, 3, 7}, {4, 10, 5, 9}, {6, 2, 7, 1}, {8, 4, 9, 3}, {10, 6, 1, 5}};
    CHECK_OK(tr_alexander_from_pd(k51, 5, &a, &err));
    const long long w51[5] = {1, -1, 1, -1, 1};
    CHECK(same_poly(&a, w51, 4) && a.determinant == 5);
    const int k52[5][4] = {{1, 5, 2, 4}, {3, 9, 4, 8}, {5, 1, 6, 10}, {7, 3, 8, 2}, {9, 7, 10, 6}};
    CHECK_OK(tr_alexander_from_pd(k52, 5, &a, &err));
    const long long w52[3] = {2, -3, 2};
    CHECK(same_poly(&a, w52, 2) && a.determinant == 7);
    /* a table's sign convention compares equal */
    tr_alexander table = a;
    for (int k = 0; k <= table.span; k++)
        table.coef[k] = -table.coef[k];
    CHECK(tr_alexander_equal(&a, &table));
    CHECK_OK(tr_alexander_from_pd(NULL, 0, &a, &err));
    CHECK(a.span == 0 && a.coef[0] == 1 && a.determinant == 1);

    const int bad_label[3][4] = {{1, 5, 2, 4}, {3, 1, 4, 7}, {5, 3, 6, 2}};
    CHECK(tr_alexander_from_pd(bad_label, 3, &a, &err) == TR_EINVAL);
    printf("  bad label: %s\n", err.msg);
    const int bad_twice[3][4] = {{1, 5, 2, 4}, {3, 1, 4, 6}, {5, 3, 6, 3}};
    CHECK(tr_alexander_from_pd(bad_twice, 3, &a, &err) == TR_EINVAL);
    printf("  bad count: %s\n", err.msg);
    const int bad_under[3][4] = {{1, 5, 3, 4}, {2, 1, 4, 6}, {5, 3, 6, 2}};
    CHECK(tr_alexander_from_pd(bad_under, 3, &a, &err) == TR_EINVAL);
    printf("  bad under strand: %s\n", err.msg);
}

static void test_refusals(void)
{
    printf("refusals:\n");
    tr_curve c = {0};
    tr_error err;
    tr_knot_invariants inv;
    CHECK_OK(tr_make_hopf(&c, 64, &err));
    CHECK(tr_knot_invariants_of(&c, &inv, &err) == TR_EUNSUPPORTED);
    printf("  Hopf link: %s\n", err.msg);
    tr_curve_free(&c);

    size_t n = 50;
    unsigned char open = 0;
    CHECK_OK(tr_curve_alloc(&c, 1, &n, &open, &err));
    for (size_t i = 0; i < n; i++)
        c.x[3 * i] = (double)i;
    CHECK(tr_knot_invariants_of(&c, &inv, &err) == TR_EINVAL);
    printf("  open rope: %s\n", err.msg);
    tr_curve_free(&c);

    /* a plane curve with self-intersections passes through itself */
    CHECK_OK(sample(&c, 2000, flat_curly_circle));
    CHECK(tr_knot_invariants_of(&c, &inv, &err) == TR_EGEOMETRY);
    printf("  flat curls: %s\n", err.msg);
    /* a direction in the curve's plane sees edges end-on or overlapping */
    const double side[3] = {1, 0, 0};
    tr_knot_diagram d;
    CHECK(tr_knot_diagram_along(&c, side, &d, &err) == TR_EGEOMETRY);
    tr_knot_diagram_free(&d);
    /* a repeated vertex has no direction */
    memcpy(c.x + 3, c.x, 3 * sizeof *c.x);
    CHECK(tr_knot_invariants_of(&c, &inv, &err) == TR_EGEOMETRY);
    printf("  repeated vertex: %s\n", err.msg);
    c.x[7] = NAN;
    CHECK(tr_knot_invariants_of(&c, &inv, &err) == TR_EINVAL);
    tr_curve_free(&c);
}

/* The size of the finest tight curves: the work is the grid's, O(N). */
static void test_large(void)
{
    printf("large:\n");
    tr_curve c = {0};
    tr_error err;
    long long want[16];
    int span = torus_alexander(3, 5, want);
    clock_t tm = clock();
    if (tr_make_torus(&c, 3, 5, 100000, &err)) {
        printf("  %s\n", err.msg);
        CHECK(0);
        return;
    }
    clock_t t0 = clock();
    printf("  made in %.3f s of CPU\n", (double)(t0 - tm) / CLOCKS_PER_SEC);
    check_knot("T(3,5) at 100000 vertices", &c, want, span);
    double s = (double)(clock() - t0) / CLOCKS_PER_SEC;
    printf("  %.3f s of CPU\n", s); /* reported, not asserted: valgrind runs it 25 times slower */
    tr_curve_free(&c);
}

int main(void)
{
    test_pd_codes();
    test_torus_knots();
    test_signs();
    test_unknots();
    test_figure_eight();
    test_invariance();
    test_refusals();
    test_large();
    return tr_test_finish("test_knot_invariants");
}
