/* Start curves against closed forms and independent checks: circle vertices
 * on the circle, torus knots equilateral with the right winding and room for
 * a rope of radius 1 (a brute-force non-local distance written here, not the
 * oracle's), the Hopf link pierced once, the clasp hooked with its ends on
 * their walls, and resampling (equilateral, on the old polygon or close to
 * the smooth curve, ends and constraints kept). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/curve_io.h"
#include "curve/generate.h"
#include "testlib.h"

static const double PI = 3.14159265358979323846;

/* max |edge - mean| / mean over the edges of component k */
static double edge_spread(const tr_curve *c, int k, double *mean_out)
{
    size_t s = c->start[k], n = tr_comp_nv(c, k), m = tr_comp_ne(c, k);
    double sum = 0, dev = 0;
    for (size_t j = 0; j < m; j++) {
        const double *a = c->x + 3 * (s + j), *b = c->x + 3 * (s + (j + 1) % n);
        sum += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    double mean = sum / (double)m;
    for (size_t j = 0; j < m; j++) {
        const double *a = c->x + 3 * (s + j), *b = c->x + 3 * (s + (j + 1) % n);
        double e = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
        dev = fmax(dev, fabs(e - mean));
    }
    if (mean_out)
        *mean_out = mean;
    return dev / mean;
}

static double dist(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Smallest vertex-vertex distance over pairs a rope of radius 1 must keep
 * apart: different components always; on one component, pairs at least pi
 * apart along it (arclength by index times the mean edge, as the curves are
 * equilateral). Brute force O(N^2). */
static double nonlocal_min(const tr_curve *c)
{
    double best = INFINITY;
    for (size_t i = 0; i < c->nv; i++) {
        int ki = tr_curve_comp_of(c, i);
        double e;
        edge_spread(c, ki, &e);
        for (size_t j = i + 1; j < c->nv; j++) {
            int kj = tr_curve_comp_of(c, j);
            if (ki == kj) {
                size_t g = j - i, n = tr_comp_nv(c, ki);
                if (c->closed[ki] && n - g < g)
                    g = n - g;
                if ((double)g * e < PI)
                    continue;
            }
            best = fmin(best, dist(c->x + 3 * i, c->x + 3 * j));
        }
    }
    return best;
}

/* Rawdon's MinRad of the polygon over its interior vertices. */
static double polygon_minrad(const tr_curve *c)
{
    double best = INFINITY;
    for (int k = 0; k < c->ncomp; k++) {
        size_t s = c->start[k], n = tr_comp_nv(c, k);
        for (size_t j = 0; j < n; j++) {
            if (!c->closed[k] && (j == 0 || j == n - 1))
                continue;
            const double *a = c->x + 3 * (s + (j + n - 1) % n), *b = c->x + 3 * (s + j), *d = c->x + 3 * (s + (j + 1) % n);
            double u[3], v[3], cr[3];
            for (int q = 0; q < 3; q++) {
                u[q] = b[q] - a[q];
                v[q] = d[q] - b[q];
            }
            cr[0] = u[1] * v[2] - u[2] * v[1];
            cr[1] = u[2] * v[0] - u[0] * v[2];
            cr[2] = u[0] * v[1] - u[1] * v[0];
            double th = atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
            double r = fmin(dist(a, b), dist(b, d)) / (2 * tan(th / 2));
            best = fmin(best, r);
        }
    }
    return best;
}

static void test_circle(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_circle(&c, 2.5, 17, &err));
    CHECK(c.ncomp == 1 && c.nv == 17 && c.closed[0]);
    for (size_t i = 0; i < c.nv; i++) {
        CHECK_NEAR(hypot(c.x[3 * i], c.x[3 * i + 1]), 2.5, 4e-16 * 2.5);
        CHECK(c.x[3 * i + 2] == 0.0);
    }
    double e;
    CHECK(edge_spread(&c, 0, &e) < 1e-14);
    CHECK_NEAR(e, 2 * 2.5 * sin(PI / 17), 1e-14);
    tr_curve_free(&c);
    CHECK(tr_make_circle(&c, 1.0, 2, &err) == TR_EINVAL);
    CHECK(tr_make_circle(&c, -1.0, 10, &err) == TR_EINVAL);
    CHECK(tr_make_circle(&c, NAN, 10, &err) == TR_EINVAL);
    CHECK(tr_make_circle(&c, 1e308, 10, &err) == TR_EINVAL); /* its length would overflow */
}

/* Windings of the polygon around the z axis, and sign changes of z. */
static void torus_signature(const tr_curve *c, double *wind, int *zflips)
{
    double w = 0;
    int flips = 0;
    for (size_t i = 0; i < c->nv; i++) {
        const double *a = c->x + 3 * i, *b = c->x + 3 * ((i + 1) % c->nv);
        double da = atan2(b[1], b[0]) - atan2(a[1], a[0]);
        while (da > PI)
            da -= 2 * PI;
        while (da < -PI)
            da += 2 * PI;
        w += da;
        flips += (a[2] < 0) != (b[2] < 0);
    }
    *wind = w / (2 * PI);
    *zflips = flips;
}

static void test_torus(void)
{
    static const int pq[][3] = {{2, 3, 300}, {3, 2, 240}, {2, 5, 400}, {3, 4, 500}, {2, -3, 300}};
    tr_error err;
    for (size_t t = 0; t < sizeof pq / sizeof pq[0]; t++) {
        int p = pq[t][0], q = pq[t][1];
        size_t n = (size_t)pq[t][2];
        tr_curve c;
        int rc = tr_make_torus(&c, p, q, n, &err);
        CHECK(rc == TR_OK);
        if (rc) {
            fprintf(stderr, "T(%d,%d): %s\n", p, q, err.msg);
            continue;
        }
        CHECK(c.nv == n && c.ncomp == 1 && c.closed[0]);
        double e, spread = edge_spread(&c, 0, &e);
        double wind;
        int flips;
        torus_signature(&c, &wind, &flips);
        double d = nonlocal_min(&c), mr = polygon_minrad(&c);
        printf("T(%d,%d) n=%zu: edge %.6f spread %.2e length %.3f nonlocal min %.4f minrad %.4f winding %.6f z flips %d\n",
               p, q, n, e, spread, tr_curve_length(&c), d, mr, wind, flips);
        CHECK(spread < 1e-12);
        CHECK(e <= 1.0);
        CHECK(d >= 2.5); /* 2 would be touching; the generator aims at 3 */
        CHECK(mr >= 1.5);
        CHECK_NEAR(wind, (double)p, 1e-9);
        CHECK(flips == 2 * abs(q));
        tr_curve_free(&c);
    }
    /* A fine one is equilateral to rounding: a vertex is placed to about
     * an ulp of its parameter (2 pi) times the speed (~10) and an ulp of its
     * coordinates (~6), i.e. ~1e-14 absolute, which relative to an edge of
     * 6e-4 is ~2e-11; allow 64 ulp of the coordinates over the edge. */
    tr_curve c;
    CHECK_OK(tr_make_torus(&c, 2, 3, 100000, &err));
    if (c.nv) {
        double e, s = edge_spread(&c, 0, &e), xmax = 0;
        for (size_t i = 0; i < 3 * c.nv; i++)
            xmax = fmax(xmax, fabs(c.x[i]));
        printf("T(2,3) n=100000: edge %.3g spread %.2e (rounding bound %.2e)\n", e, s, 64 * DBL_EPSILON * xmax / e);
        CHECK(s < 64 * DBL_EPSILON * xmax / e);
        tr_curve_free(&c);
    }
    CHECK(tr_make_torus(&c, 2, 4, 300, &err) == TR_EINVAL);
    CHECK(tr_make_torus(&c, 1, 3, 300, &err) == TR_EINVAL);
    CHECK(tr_make_torus(&c, 2, 3, 20, &err) == TR_EINVAL); /* edges longer than 1 */
    CHECK(strstr(err.msg, "use at least") != NULL);
}

static void test_hopf(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_hopf(&c, 40, &err));
    CHECK(c.ncomp == 2 && c.nv == 80 && c.closed[0] && c.closed[1]);
    CHECK(edge_spread(&c, 0, NULL) < 1e-14 && edge_spread(&c, 1, NULL) < 1e-14);
    double d = INFINITY;
    for (size_t i = 0; i < 40; i++)
        for (size_t j = 40; j < 80; j++)
            d = fmin(d, dist(c.x + 3 * i, c.x + 3 * j));
    CHECK(d >= 2.5);
    CHECK(nonlocal_min(&c) >= 2.5);
    /* linked: circle B pierces the flat disk of circle A (z = 0, |x| < 3)
     * exactly once */
    int inside = 0;
    for (size_t j = 0; j < 40; j++) {
        const double *a = c.x + 3 * (40 + j), *b = c.x + 3 * (40 + (j + 1) % 40);
        if ((a[2] < 0) != (b[2] < 0)) {
            double u = a[2] / (a[2] - b[2]);
            double px = a[0] + u * (b[0] - a[0]), py = a[1] + u * (b[1] - a[1]);
            inside += hypot(px, py) < 3 * cos(PI / 40);
        }
    }
    CHECK(inside == 1);
    tr_curve_free(&c);
    CHECK(tr_make_hopf(&c, 10, &err) == TR_EINVAL);
}

static void test_clasp(void)
{
    tr_error err;
    tr_curve c;
    const double h = 5;
    const size_t n = 60;
    CHECK_OK(tr_make_clasp(&c, n, h, &err));
    if (c.nv == 0)
        return;
    CHECK(c.ncomp == 2 && c.nv == 2 * n && !c.closed[0] && !c.closed[1]);
    CHECK(c.ncst == 2);
    for (int k = 0; k < 2; k++) {
        size_t ends[2] = {c.start[k], c.start[k + 1] - 1};
        double wall = k == 0 ? h : -h;
        for (int j = 0; j < 2; j++) {
            const double *v = c.x + 3 * ends[j];
            int q = c.vcst[ends[j]];
            CHECK(q >= 0 && c.cst[q].kind == TR_CST_PLANE);
            if (q >= 0)
                CHECK(tr_constraint_violation(&c.cst[q], v) == 0.0);
            CHECK(v[2] == wall);
        }
        for (size_t i = ends[0] + 1; i < ends[1]; i++)
            CHECK(c.vcst[i] == -1);
        double e, s = edge_spread(&c, k, &e);
        printf("clasp rope %d: edge %.6f spread %.2e\n", k, e, s);
        CHECK(s < 1e-12);
        CHECK(e <= 1.0);
    }
    double d = nonlocal_min(&c);
    printf("clasp: nonlocal min %.4f minrad %.4f\n", d, polygon_minrad(&c));
    CHECK(d >= 2.5);
    CHECK(polygon_minrad(&c) >= 1.5);
    /* hooked: rope B crosses rope A's plane (y = 0) once, inside A's U
     * (|x| < 3, above A's lowest point, below the wall), and vice versa */
    for (int k = 0; k < 2; k++) {
        int other = 1 - k, axis = k == 0 ? 1 : 0; /* A lies in y = 0, B in x = 0 */
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = c.start[k]; i < c.start[k + 1]; i++) {
            lo = fmin(lo, c.x[3 * i + 2]);
            hi = fmax(hi, c.x[3 * i + 2]);
        }
        int crossings = 0, good = 0;
        for (size_t i = c.start[other]; i + 1 < c.start[other + 1]; i++) {
            const double *a = c.x + 3 * i, *b = c.x + 3 * (i + 1);
            if ((a[axis] < 0) != (b[axis] < 0)) {
                double u = a[axis] / (a[axis] - b[axis]);
                double w = a[1 - axis] + u * (b[1 - axis] - a[1 - axis]), z = a[2] + u * (b[2] - a[2]);
                crossings++;
                good += fabs(w) < 3 && z > lo && z < hi;
            }
        }
        CHECK(crossings == 1 && good == 1);
    }
    /* round trip through a VECT file keeps the constraints */
    char path[1024];
    snprintf(path, sizeof path, "%s/gen_clasp.vect", TR_BINARY_DIR);
    CHECK_OK(tr_curve_write(path, TR_FORMAT_AUTO, &c, NULL, &err));
    tr_curve r;
    CHECK_OK(tr_curve_read(path, TR_FORMAT_AUTO, &r, &err));
    CHECK(r.ncst == 2 && r.vcst && r.vcst[0] == 0 && r.vcst[2 * n - 1] == 1 && !memcmp(r.x, c.x, 6 * n * sizeof *r.x));
    tr_curve_free(&r);
    tr_curve_free(&c);
    CHECK(tr_make_clasp(&c, n, 1.0, &err) == TR_EINVAL);
    CHECK(tr_make_clasp(&c, 5, h, &err) == TR_EINVAL);
}

/* distance from x to the polygon of component k of c */
static double dist_to_polygon(const tr_curve *c, int k, const double *x)
{
    size_t s = c->start[k], n = tr_comp_nv(c, k), m = tr_comp_ne(c, k);
    double best = INFINITY;
    for (size_t j = 0; j < m; j++) {
        const double *a = c->x + 3 * (s + j), *b = c->x + 3 * (s + (j + 1) % n);
        double ab[3], ax[3], l2 = 0, t = 0;
        for (int q = 0; q < 3; q++) {
            ab[q] = b[q] - a[q];
            ax[q] = x[q] - a[q];
            l2 += ab[q] * ab[q];
            t += ab[q] * ax[q];
        }
        t = fmin(fmax(t / l2, 0), 1);
        double p[3] = {a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]};
        best = fmin(best, dist(p, x));
    }
    return best;
}

static void test_resample_circle(void)
{
    tr_error err;
    tr_curve c, r;
    /* smooth resampling of a coarse circle stays near the circle; the
     * polygonal one cannot do better than the old edges' sagitta */
    CHECK_OK(tr_make_circle(&c, 3.0, 24, &err));
    size_t fine = 240;
    tr_curve lin;
    CHECK_OK(tr_resample(&c, &fine, &lin, &err));
    CHECK_OK(tr_resample_smooth(&c, &fine, &r, &err));
    if (r.nv && lin.nv) {
        double elin = 0, esm = 0;
        for (size_t i = 0; i < fine; i++) {
            elin = fmax(elin, fabs(hypot(lin.x[3 * i], lin.x[3 * i + 1]) - 3));
            esm = fmax(esm, fabs(hypot(r.x[3 * i], r.x[3 * i + 1]) - 3));
        }
        double sag = 3 * (1 - cos(PI / 24));
        printf("circle 24 -> 240: polygonal error %.2e (sagitta %.2e), spline error %.2e, spread %.2e\n", elin, sag,
               esm, edge_spread(&r, 0, NULL));
        CHECK_NEAR(elin, sag, 0.05 * sag);
        CHECK(esm < sag / 50);
        CHECK(edge_spread(&r, 0, NULL) < 1e-12);
    }
    tr_curve_free(&lin);
    tr_curve_free(&r);
    tr_curve_free(&c);
}

static void test_resample(void)
{
    tr_error err;
    char path[1024];
    tr_curve c, r;
    /* an irregular closed KnotPlot trefoil, refined */
    tr_source_path(path, sizeof path, "tests/data/knotplot/3.1.vect");
    REQUIRE_OK(tr_curve_read(path, TR_FORMAT_AUTO, &c, &err));
    size_t n = 120;
    CHECK_OK(tr_resample(&c, &n, &r, &err));
    if (r.nv) {
        double s = edge_spread(&r, 0, NULL);
        printf("resample 3.1 47 -> 120: spread %.2e\n", s);
        CHECK(s < 1e-12);
        CHECK(r.nv == 120 && r.closed[0]);
        double off = 0;
        for (size_t i = 0; i < r.nv; i++)
            off = fmax(off, dist_to_polygon(&c, 0, r.x + 3 * i));
        CHECK(off < 1e-12);
        CHECK(!memcmp(r.x, c.x, 3 * sizeof *r.x)); /* vertex 0 stays */
        CHECK(tr_curve_length(&r) <= tr_curve_length(&c));
        tr_curve_free(&r);
    }
    tr_curve_free(&c);

    /* open ropes with plane constraints on their ends */
    tr_source_path(path, sizeof path, "tests/data/knotplot/simple_clasp.vect");
    REQUIRE_OK(tr_curve_read(path, TR_FORMAT_AUTO, &c, &err));
    size_t nn[2] = {50, 61};
    CHECK_OK(tr_resample(&c, nn, &r, &err));
    if (r.nv) {
        for (int k = 0; k < 2; k++) {
            CHECK(tr_comp_nv(&r, k) == nn[k] && !r.closed[k]);
            CHECK(edge_spread(&r, k, NULL) < 1e-12);
            size_t a0 = c.start[k], a1 = c.start[k + 1] - 1, b0 = r.start[k], b1 = r.start[k + 1] - 1;
            CHECK(!memcmp(r.x + 3 * b0, c.x + 3 * a0, 3 * sizeof *r.x));
            CHECK(!memcmp(r.x + 3 * b1, c.x + 3 * a1, 3 * sizeof *r.x));
            CHECK(r.vcst[b0] == c.vcst[a0] && r.vcst[b1] == c.vcst[a1] && r.vcst[b0 + 1] == -1);
        }
        CHECK(r.ncst == c.ncst);
        tr_curve_free(&r);
    }
    /* a constraint on an interior vertex cannot survive resampling */
    c.vcst[5] = 0;
    CHECK(tr_resample(&c, NULL, &r, &err) == TR_EINVAL);
    tr_curve_free(&c);

    /* smooth resampling of open ropes keeps their end vertices */
    tr_source_path(path, sizeof path, "tests/data/knotplot/simple_clasp.vect");
    REQUIRE_OK(tr_curve_read(path, TR_FORMAT_AUTO, &c, &err));
    CHECK_OK(tr_resample_smooth(&c, nn, &r, &err));
    if (r.nv) {
        CHECK(!memcmp(r.x, c.x, 3 * sizeof *r.x));
        CHECK(!memcmp(r.x + 3 * (r.nv - 1), c.x + 3 * (c.nv - 1), 3 * sizeof *r.x));
        CHECK(edge_spread(&r, 0, NULL) < 1e-12 && edge_spread(&r, 1, NULL) < 1e-12);
    }
    tr_curve_free(&r);
    tr_curve_free(&c);
}

int main(void)
{
    test_circle();
    test_torus();
    test_hopf();
    test_clasp();
    test_resample_circle();
    test_resample();
    return tr_test_finish("test_generate");
}
