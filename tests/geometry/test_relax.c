/* The relaxation of a loose start (geometry/relax.h), against what symmetry
 * says of it:
 *  - a regular polygon stays a regular polygon in its plane (every force on
 *    it is radial and the same at every vertex): it may only grow;
 *  - a circle whose vertices are unevenly spaced becomes a regular polygon
 *    (its edges equal, its vertices equidistant from the centre);
 *  - two equal circles side by side keep their mirror symmetries;
 *  - an open component or one of 3 vertices is refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "curve/curve.h"
#include "curve/generate.h"
#include "geometry/relax.h"
#include "testlib.h"

#define TEST_PI 3.14159265358979323846

/* the largest and smallest distance of component k's vertices from their
 * centroid, the largest |z|, and the extreme edge lengths */
static void shape(const tr_curve *c, int k, double *rmin, double *rmax, double *zmax, double *emin, double *emax)
{
    size_t s = c->start[k], n = tr_comp_nv(c, k);
    double m[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int q = 0; q < 3; q++)
            m[q] += c->x[3 * (s + i) + q] / (double)n;
    *rmin = *emin = INFINITY;
    *rmax = *zmax = *emax = 0;
    for (size_t i = 0; i < n; i++) {
        const double *a = c->x + 3 * (s + i), *b = c->x + 3 * (s + (i + 1) % n);
        double r = sqrt((a[0] - m[0]) * (a[0] - m[0]) + (a[1] - m[1]) * (a[1] - m[1]) + (a[2] - m[2]) * (a[2] - m[2]));
        double e = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
        *rmin = fmin(*rmin, r);
        *rmax = fmax(*rmax, r);
        *zmax = fmax(*zmax, fabs(a[2] - m[2]));
        *emin = fmin(*emin, e);
        *emax = fmax(*emax, e);
    }
}

static void test_regular_polygon(void)
{
    tr_curve c;
    tr_error err;
    CHECK_OK(tr_make_circle(&c, 3.0, 40, &err));
    double r0, r1, z, e0, e1;
    shape(&c, 0, &r0, &r1, &z, &e0, &e1);
    CHECK_OK(tr_curve_relax(&c, 400, &err));
    double rmin, rmax, emin, emax;
    shape(&c, 0, &rmin, &rmax, &z, &emin, &emax);
    printf("regular polygon relaxed: radius %.9f .. %.9f (from %.9f), edges %.9f .. %.9f\n", rmin, rmax, r0, emin,
           emax);
    CHECK(rmax - rmin <= 1e-9 * rmax);
    CHECK(emax - emin <= 1e-9 * emax);
    CHECK(z <= 1e-12);
    /* the push is outward and nothing pulls inward but the springs */
    CHECK(rmin >= r0 * (1 - 1e-12));
    tr_curve_free(&c);
}

static void test_uneven_circle(void)
{
    tr_curve c;
    tr_error err;
    size_t n = 30;
    CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    for (size_t i = 0; i < n; i++) {
        /* angles crowded towards 0: edges from 0.6 to 1.4 times the mean */
        double u = 2 * TEST_PI * (double)i / (double)n, a = u - 0.4 * sin(u);
        c.x[3 * i] = 3 * cos(a);
        c.x[3 * i + 1] = 3 * sin(a);
        c.x[3 * i + 2] = 0;
    }
    double rmin, rmax, z, emin, emax;
    shape(&c, 0, &rmin, &rmax, &z, &emin, &emax);
    CHECK(emax / emin > 2);
    CHECK_OK(tr_curve_relax(&c, 3000, &err));
    shape(&c, 0, &rmin, &rmax, &z, &emin, &emax);
    printf("uneven circle relaxed: edges %.6f .. %.6f, radii %.6f .. %.6f\n", emin, emax, rmin, rmax);
    CHECK(emax / emin < 1.001);
    CHECK(rmax / rmin < 1.02);
    CHECK(z <= 1e-12);
    tr_curve_free(&c);
}

static void test_two_circles(void)
{
    tr_curve c;
    tr_error err;
    size_t n[2] = {24, 24};
    CHECK_OK(tr_curve_alloc(&c, 2, n, NULL, &err));
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; i < 24; i++) {
            double a = 2 * TEST_PI * (double)i / 24.0;
            double *p = c.x + 3 * (24 * (size_t)k + i);
            p[0] = 3 * cos(a) + (k ? 10 : -10);
            p[1] = 3 * sin(a);
            p[2] = 0;
        }
    CHECK_OK(tr_curve_relax(&c, 500, &err));
    /* mirror images in x = 0: the mirror takes vertex i of one to vertex
     * 12 - i of the other (the angle a to pi - a), and y -> -y takes
     * vertex i of each to its vertex -i */
    double worst = 0;
    for (size_t i = 0; i < 24; i++) {
        const double *a = c.x + 3 * i, *b = c.x + 3 * (24 + (36 - i) % 24), *m = c.x + 3 * ((24 - i) % 24);
        worst = fmax(worst, fmax(fabs(a[0] + b[0]), fmax(fabs(a[1] - b[1]), fabs(a[2] - b[2]))));
        worst = fmax(worst, fmax(fabs(a[0] - m[0]), fabs(a[1] + m[1])));
    }
    CHECK(worst <= 1e-9);
    tr_curve_free(&c);
}

static void test_refused(void)
{
    tr_curve c;
    tr_error err;
    size_t n = 3;
    CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    for (int q = 0; q < 9; q++)
        c.x[q] = q == 0 || q == 4 || q == 8;
    CHECK(tr_curve_relax(&c, 10, &err) == TR_EINVAL);
    tr_curve_free(&c);
    unsigned char open = 0;
    n = 10;
    CHECK_OK(tr_curve_alloc(&c, 1, &n, &open, &err));
    for (size_t i = 0; i < n; i++)
        c.x[3 * i] = (double)i;
    CHECK(tr_curve_relax(&c, 10, &err) == TR_EINVAL);
    tr_curve_free(&c);
}

int main(void)
{
    test_regular_polygon();
    test_uneven_circle();
    test_two_circles();
    test_refused();
    return tr_test_finish("test_relax");
}
