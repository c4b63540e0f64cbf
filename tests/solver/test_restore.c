/* Tests the restoration (solver/newton.h, tr_newton_restore) on ideal
 * polygons known in closed form, nudged off their bounds, each result
 * judged by the thickness oracle (oracle/thickness.h):
 *  - the regular n-gon with MinRad 1 (edge 2 tan(pi / n), ropelength
 *    2 n tan(pi / n), the shortest closed n-gon with MinRad >= 1; its
 *    opposite edges are exactly 2 apart as well);
 *  - the Hopf link's ideal pair of n-gons: each ring the regular n-gon
 *    circumscribed about the circle of radius 2 about a point of the other
 *    (ropelength 8 n tan(pi / n), MinRad 2, struts exactly 2).
 * A vertex moved by 1e-8 puts the polygon over its bounds (MinRad's rows
 * are in units of edge^2, so by ~1e-6 relative): rescaled to thickness 1 it
 * is longer by that share of its whole length, while a correction of the
 * vertices near the nudge costs a few 1e-8 of length at most. Any curve of
 * thickness 1 is at least the closed form, so the restored one must lie
 * between the closed form and the rescaled one, much nearer the former. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "oracle/thickness.h"
#include "solver/newton.h"
#include "testlib.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void measure(const tr_curve *c, tr_thickness *th)
{
    tr_error err = {0};
    REQUIRE_OK(tr_thickness_measure(c, NULL, th, NULL, &err));
}

/* nudged: the curve off its bounds; want: the closed form */
static void check_restore(const char *name, tr_curve *c, double want)
{
    tr_thickness th0, th1;
    measure(c, &th0);
    double before, after;
    tr_error err = {0};
    CHECK_OK(tr_newton_restore(c, NULL, &before, &after, &err));
    measure(c, &th1);
    printf("%s: rescaled %.12f (thickness %.3e below 1), restored %.12f (thickness %.3e below 1), closed form "
           "%.12f; row violation %.2e -> %.2e\n",
           name, th0.ropelength, 1.0 - th0.thickness, th1.ropelength, 1.0 - th1.thickness, want, before, after);
    /* the nudge is over the rounding's reach */
    CHECK(th0.ropelength - want > 1e-7 * want);
    CHECK(after < 1e-3 * before);
    /* at thickness 1, and no shorter than any curve of thickness 1 can be */
    CHECK_NEAR(th1.thickness, 1.0, 1e-12);
    CHECK(th1.ropelength >= want * (1.0 - 1e-12));
    /* much nearer the closed form than the rescaling */
    CHECK(th1.ropelength - want < 0.1 * (th0.ropelength - want));
}

static void test_ngon(size_t n)
{
    tr_curve c = {0};
    tr_error err = {0};
    size_t sizes[1] = {n};
    unsigned char closed[1] = {1};
    REQUIRE_OK(tr_curve_alloc(&c, 1, sizes, closed, &err));
    double R = 1.0 / cos(M_PI / (double)n);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * (double)i / (double)n;
        c.x[3 * i] = R * cos(t);
        c.x[3 * i + 1] = R * sin(t);
        c.x[3 * i + 2] = 0.0;
    }
    /* one vertex out (its MinRad over), one in (its neighbours' MinRad and
     * the opposite struts over) */
    c.x[3 * 5] += 1e-8;
    c.x[3 * 20 + 1] -= 1e-8;
    check_restore("n-gon", &c, 2.0 * (double)n * tan(M_PI / (double)n));
    tr_curve_free(&c);
}

static void test_hopf(size_t n)
{
    tr_curve c = {0};
    tr_error err = {0};
    size_t sizes[2] = {n, n};
    unsigned char closed[2] = {1, 1};
    REQUIRE_OK(tr_curve_alloc(&c, 2, sizes, closed, &err));
    double R = 2.0 / cos(M_PI / (double)n);
    for (size_t i = 0; i < n; i++) {
        /* ring A about the origin in the xy plane, an edge's midpoint at
         * (2, 0, 0); ring B about (2, 0, 0) in the xz plane, an edge's
         * midpoint at the origin */
        double t = (2.0 * (double)i + 1.0) * M_PI / (double)n, u = M_PI + t;
        double *a = c.x + 3 * i, *b = c.x + 3 * (n + i);
        a[0] = R * cos(t);
        a[1] = R * sin(t);
        a[2] = 0.0;
        b[0] = 2.0 + R * cos(u);
        b[1] = 0.0;
        b[2] = R * sin(u);
    }
    /* ring A's edge through B's disk lifted toward B's upper edges */
    c.x[2] += 1e-6;
    c.x[3 * (n - 1) + 2] += 1e-6;
    check_restore("hopf", &c, 8.0 * (double)n * tan(M_PI / (double)n));
    tr_curve_free(&c);
}

/* The nudged n-gon 8192 away along x: held in doubles, a vertex there is
 * known to 9e-13, and a MinRad row (a second difference of size l0^2 =
 * 9.6e-3) to 1e-10 of itself, so a restoration in doubles leaves its rows
 * about that far over and the rescaling charges it (the thickness check
 * below, at 1e-12); the restoration's last pass on the positions with low
 * parts (curve.h) closes them as at the origin, and the result carries its
 * low parts. (Farther away the start's own rounding, which no restoration
 * undoes, and the long double's 64 bits at the coordinates take over.) */
static void test_ngon_far(size_t n)
{
    tr_curve c = {0};
    tr_error err = {0};
    size_t sizes[1] = {n};
    REQUIRE_OK(tr_curve_alloc(&c, 1, sizes, NULL, &err));
    double R = 1.0 / cos(M_PI / (double)n);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * (double)i / (double)n;
        c.x[3 * i] = 8192.0 + R * cos(t);
        c.x[3 * i + 1] = R * sin(t);
    }
    c.x[3 * 5] += 1e-8;
    c.x[3 * 20 + 1] -= 1e-8;
    check_restore("n-gon far away", &c, 2.0 * (double)n * tan(M_PI / (double)n));
    CHECK(c.lo != NULL);
    tr_curve_free(&c);
}

int main(void)
{
    test_ngon(64);
    test_ngon_far(64);
    test_hopf(40);
    return tr_test_finish("test_restore");
}
