/* The public C API (include/tightrope/tightrope.h, host/api): curves in and
 * out as arrays, start curves, files, measures against closed forms, the
 * errors a caller meets, tighten (with its cancel flag and progress) and
 * analyze. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"
#include "tightrope/tightrope.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A regular n-gon of circumradius R: edges e = 2 R sin(pi/n), and Rawdon's
 * MinRad e / (2 tan(pi/n)) = R cos(pi/n); for even n the opposite edges'
 * distance 2 R cos(pi/n) is the shortest strut, so thickness = R cos(pi/n). */
static void test_circle_closed_form(void)
{
    tightrope_curve *c = NULL;
    tightrope_error err;
    REQUIRE_OK(tightrope_make("circle 5", 64, &c, &err));
    CHECK(tightrope_curve_vertices(c) == 64);
    CHECK(tightrope_curve_components(c) == 1);
    CHECK(tightrope_curve_closed(c, 0) == 1);
    CHECK(tightrope_curve_offset(c, 1) == 64);
    tightrope_measurement m;
    CHECK_OK(tightrope_measure(c, -1, &m, &err));
    double R = 5.0, t = M_PI / 64;
    CHECK_NEAR(m.length, 64 * 2 * R * sin(t), 1e-12);
    CHECK_NEAR(m.minrad, R * cos(t), 1e-12);
    CHECK_NEAR(m.thickness, R * cos(t), 1e-12);
    CHECK_NEAR(m.ropelength, 64 * 2 * sin(t) / cos(t), 1e-12);
    CHECK(m.has_shortest_strut);
    CHECK_NEAR(m.shortest_strut.length, 2 * R * cos(t), 1e-12);
    /* every pair of opposite edges is a shortest strut: 32 of them */
    tightrope_strut *s = NULL;
    size_t ns = 0;
    CHECK_OK(tightrope_struts(c, 1e-9, &s, &ns, &err));
    CHECK(ns == 32);
    tightrope_free(s);
    tightrope_curve_free(c);
}

/* MinRad of a torus knot computed here from the vertices the API hands
 * out, with Rawdon's formula min(|a|,|b|) (|a||b| + a.b) / (2 |a x b|)
 * (thickness.h), against the oracle's through the API. */
static void test_minrad_independent(void)
{
    tightrope_curve *c = NULL;
    tightrope_error err;
    REQUIRE_OK(tightrope_make("torus 2 5", 150, &c, &err));
    const double *x = tightrope_curve_xyz(c);
    size_t n = tightrope_curve_vertices(c), at = 0;
    double best = INFINITY;
    for (size_t i = 0; i < n; i++) {
        const double *p = x + 3 * ((i + n - 1) % n), *v = x + 3 * i, *q = x + 3 * ((i + 1) % n);
        double a[3] = {v[0] - p[0], v[1] - p[1], v[2] - p[2]}, b[3] = {q[0] - v[0], q[1] - v[1], q[2] - v[2]};
        double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
        double mr = fmin(la, lb) * (la * lb + a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) /
                    (2 * sqrt(cx * cx + cy * cy + cz * cz));
        if (mr < best) {
            best = mr;
            at = i;
        }
    }
    tightrope_measurement m;
    CHECK_OK(tightrope_measure(c, -1, &m, &err));
    CHECK_NEAR(m.minrad, best, 1e-12 * best);
    CHECK(m.minrad_vertex == at);
    CHECK(m.thickness <= m.minrad && m.thickness < 0.999 * m.minrad); /* the struts set it here */
    CHECK_NEAR(m.ropelength, m.length / m.thickness, 1e-12 * m.ropelength);
    tightrope_curve_free(c);
}

/* Arrays in, arrays out, and a file's round trip (%.17g: exact). */
static void test_arrays_and_files(void)
{
    double xyz[3 * 7];
    size_t off[3] = {0, 4, 7};
    int closed[2] = {1, 0};
    for (int i = 0; i < 4; i++) {
        xyz[3 * i] = 3 * cos(i * M_PI / 2);
        xyz[3 * i + 1] = 3 * sin(i * M_PI / 2) + 0.1 * i;
        xyz[3 * i + 2] = 0.0;
    }
    for (int i = 0; i < 3; i++) {
        xyz[12 + 3 * i] = 20.0 + i;
        xyz[12 + 3 * i + 1] = 0.5 * i * i;
        xyz[12 + 3 * i + 2] = 1.0 / 3.0;
    }
    tightrope_curve *c = NULL, *r = NULL;
    tightrope_error err;
    REQUIRE_OK(tightrope_curve_new(2, off, closed, xyz, &c, &err));
    CHECK(tightrope_curve_vertices(c) == 7 && tightrope_curve_components(c) == 2);
    CHECK(tightrope_curve_closed(c, 0) == 1 && tightrope_curve_closed(c, 1) == 0);
    CHECK(memcmp(tightrope_curve_xyz(c), xyz, sizeof xyz) == 0);
    char path[4096];
    snprintf(path, sizeof path, "%s/tests/api_roundtrip.vect", TR_BINARY_DIR);
    CHECK_OK(tightrope_write(path, c, "written by test_api", &err));
    REQUIRE_OK(tightrope_read(path, &r, &err));
    CHECK(tightrope_curve_vertices(r) == 7 && tightrope_curve_offset(r, 1) == 4 && !tightrope_curve_closed(r, 1));
    CHECK(memcmp(tightrope_curve_xyz(r), xyz, sizeof xyz) == 0);
    remove(path);
    tightrope_curve_free(r);
    tightrope_curve_free(c);

    /* the clasp keeps its ends' constraints through a file */
    REQUIRE_OK(tightrope_make("clasp", 40, &c, &err));
    CHECK(tightrope_curve_components(c) == 2 && tightrope_curve_constraints(c) == 4);
    snprintf(path, sizeof path, "%s/tests/api_clasp.vect", TR_BINARY_DIR);
    CHECK_OK(tightrope_write(path, c, NULL, &err));
    REQUIRE_OK(tightrope_read(path, &r, &err));
    CHECK(tightrope_curve_constraints(r) == 4);
    remove(path);
    tightrope_curve_free(r);
    tightrope_curve_free(c);
}

/* What a caller gets wrong comes back as a status and one line. */
static void test_errors(void)
{
    tightrope_error err;
    tightrope_curve *c = NULL;
    double two[6] = {0, 0, 0, 1, 0, 0};
    size_t off2[2] = {0, 2};
    CHECK(tightrope_curve_new(1, off2, NULL, two, &c, &err) == TIGHTROPE_EINVAL && !c);
    CHECK(err.status == TIGHTROPE_EINVAL && strstr(err.message, "needs at least 3"));
    double sq[12] = {0, 0, 0, 1, 0, 0, 1, NAN, 0, 0, 1, 0};
    size_t off4[2] = {0, 4};
    CHECK(tightrope_curve_new(1, off4, NULL, sq, &c, &err) == TIGHTROPE_EINVAL);
    CHECK(strstr(err.message, "vertex 2 of component 0 is not finite") != NULL);
    sq[7] = 1.0;
    sq[9] = 1.0; /* vertex 3 = vertex 2 */
    CHECK(tightrope_curve_new(1, off4, NULL, sq, &c, &err) == TIGHTROPE_EINVAL);
    CHECK(strstr(err.message, "coincides") != NULL);
    CHECK(tightrope_make("figure-eight", 0, &c, &err) == TIGHTROPE_EINVAL &&
          strstr(err.message, "no knot or link named 'figure-eight'"));
    CHECK(tightrope_make("knot L6a4", 0, &c, &err) == TIGHTROPE_EINVAL && strstr(err.message, "is a link, not a knot"));
    /* notation: the trefoil's PD code (checked against the code's own
     * invariants as it is made), a braid closing into two components */
    CHECK(tightrope_make("pd [[1,5,2,4],[3,1,4,6],[5,3,6,2]]", 0, &c, &err) == TIGHTROPE_OK);
    CHECK(c && tightrope_curve_components(c) == 1);
    tightrope_curve_free(c);
    c = NULL;
    CHECK(tightrope_make("braid 1,1", 0, &c, &err) == TIGHTROPE_OK);
    CHECK(c && tightrope_curve_components(c) == 2);
    tightrope_curve_free(c);
    c = NULL;
    /* a braid word names no type: a closure past the type check's five
     * components is made all the same (1,1,3,3,5,5 on six strands: three
     * Hopf links, six components) */
    CHECK(tightrope_make("braid 1,1,3,3,5,5", 0, &c, &err) == TIGHTROPE_OK);
    CHECK(c && tightrope_curve_components(c) == 6);
    tightrope_curve_free(c);
    c = NULL;
    CHECK(tightrope_make("braid 1,0", 0, &c, &err) == TIGHTROPE_EINVAL && strstr(err.message, "is 0"));
    /* the unknot by name with too few vertices for edges below 1: refused, nothing to free */
    CHECK(tightrope_make("0_1", 10, &c, &err) == TIGHTROPE_EINVAL && strstr(err.message, "at least 19"));
    /* by name: the figure eight (KnotInfo's 4_1), its type checked as it is made */
    CHECK(tightrope_make("knot 4_1", 0, &c, &err) == TIGHTROPE_OK);
    CHECK(c && tightrope_curve_components(c) == 1 && tightrope_curve_vertices(c) > 20);
    tightrope_curve_free(c);
    c = NULL;
    CHECK(tightrope_make("torus 2 4", 0, &c, &err) == TIGHTROPE_EINVAL);
    CHECK(tightrope_make("torus 2", 0, &c, &err) == TIGHTROPE_EINVAL);
    const char *bad = "VECT\n1 3 0\n3\n0\n0 0 0\n1 0\n";
    CHECK(tightrope_parse("bad.vect", bad, strlen(bad), &c, &err) == TIGHTROPE_EPARSE);
    CHECK(strncmp(err.message, "bad.vect:", 9) == 0);
    CHECK(tightrope_read("/nonexistent/k.vect", &c, &err) == TIGHTROPE_EIO);
    CHECK(strcmp(tightrope_strerror(TIGHTROPE_EINVAL), "invalid argument") == 0);
    CHECK(tightrope_measure(NULL, -1, NULL, NULL) == TIGHTROPE_EINVAL); /* no error struct: status alone */
    char v[32];
    snprintf(v, sizeof v, "%s", tightrope_version());
    int a, b, d;
    CHECK(sscanf(v, "%d.%d.%d", &a, &b, &d) == 3);
}

/* A curve that passes through itself (a figure of eight in the plane:
 * vertices 0 and 100 at the origin) has no thickness: measure and tighten
 * refuse it with the oracle's message naming the edges. */
static void test_self_crossing(void)
{
    tightrope_error err;
    tightrope_curve *c = NULL, *out = NULL;
    double xyz[3 * 200];
    size_t off[2] = {0, 200};
    for (int i = 0; i < 200; i++) {
        double t = 2 * M_PI * i / 200;
        xyz[3 * i] = 15 * sin(t);
        xyz[3 * i + 1] = 15 * sin(t) * cos(t);
        xyz[3 * i + 2] = 0.0;
    }
    REQUIRE_OK(tightrope_curve_new(1, off, NULL, xyz, &c, &err));
    tightrope_measurement m;
    CHECK(tightrope_measure(c, -1, &m, &err) == TIGHTROPE_EGEOMETRY);
    CHECK(strstr(err.message, "passes through itself") != NULL);
    tightrope_tighten_options o;
    tightrope_tighten_options_init(&o);
    o.device = "reference";
    o.time_limit = 1;
    tightrope_tighten_result r;
    int rc = tightrope_tighten(c, &o, &out, &r, &err);
    CHECK(rc == TIGHTROPE_EGEOMETRY && out == NULL && err.status == rc);
    CHECK(strstr(err.message, "passes through itself") != NULL);
    tightrope_curve_free(c);
}

static void count_progress(const tightrope_progress *p, void *user)
{
    (void)p;
    ++*(int *)user;
}

/* Tightening shortens the trefoil towards the ideal 32.7429 (Przybyl &
 * Pieranski), never below it, and what it reports is what an independent
 * measure of its curve finds; a raised cancel flag stops it at once with a
 * curve. */
static void test_tighten(void)
{
    tightrope_error err;
    tightrope_curve *c = NULL, *out = NULL;
    REQUIRE_OK(tightrope_make("torus 2 3", 64, &c, &err));
    tightrope_measurement m0, m1;
    REQUIRE_OK(tightrope_measure(c, -1, &m0, &err));
    tightrope_tighten_options o;
    tightrope_tighten_options_init(&o);
    o.device = "reference";
    o.time_limit = 2;
    o.progress_every = 0.05;
    int calls = 0;
    o.progress = count_progress;
    o.user = &calls;
    tightrope_tighten_result r;
    REQUIRE_OK(tightrope_tighten(c, &o, &out, &r, &err));
    REQUIRE_OK(tightrope_measure(out, -1, &m1, &err));
    CHECK(m1.ropelength < m0.ropelength - 1 && m1.ropelength > 32.7429);
    CHECK_NEAR(r.ropelength, m1.ropelength, 1e-12 * m1.ropelength);
    CHECK(r.n == 64 && !r.interrupted && r.stopped[0]);
    CHECK(calls > 0);
    CHECK(r.certified && r.kkt_residual >= 0 && r.kkt_residual < 1);
    tightrope_curve_free(out);

    volatile sig_atomic_t cancel = 1;
    o.cancel = &cancel;
    o.time_limit = 60;
    o.progress = NULL;
    out = NULL;
    REQUIRE_OK(tightrope_tighten(c, &o, &out, &r, &err));
    CHECK(out != NULL && r.interrupted && r.elapsed < 10);
    CHECK(strcmp(r.stopped, "signal") == 0);
    tightrope_curve_free(out);
    tightrope_curve_free(c);
}

/* Curvature of the inscribed-arc curve at a vertex is 1 / its MinRad
 * (arc_profile.h); scaled to thickness 1, no arc is curved beyond 1 and the
 * MinRad vertex's arc is exactly 1 when MinRad sets the thickness. */
static void test_analyze(void)
{
    tightrope_error err;
    tightrope_curve *c = NULL;
    REQUIRE_OK(tightrope_make("circle 4", 40, &c, &err));
    tightrope_analysis *a = NULL;
    tightrope_analyze_options ao = {.m = 1};
    REQUIRE_OK(tightrope_analyze(c, 0, &ao, &a, &err));
    size_t n = 0, nj = 0, nc = 0;
    const double *k = tightrope_analysis_profile(a, TIGHTROPE_ARC_CURVATURE, &n);
    const double *tau = tightrope_analysis_profile(a, TIGHTROPE_JUNCTION_TORSION, &nj);
    tightrope_analysis_profile(a, TIGHTROPE_CONTACTS, &nc);
    CHECK(n == 40 && nj == 40 && nc % 3 == 0);
    double kmax = 0, tmax = 0;
    for (size_t i = 0; i < n; i++)
        kmax = fmax(kmax, k[i]);
    for (size_t i = 0; i < nj; i++)
        tmax = fmax(tmax, fabs(tau[i]));
    CHECK_NEAR(kmax, 1.0, 1e-12); /* a circle: MinRad everywhere, the thickness */
    CHECK(tmax < 1e-9);           /* planar: no torsion */
    const char *s = tightrope_analysis_summary(a);
    CHECK(s && s[0] == '{' && strstr(s, "\"vertices\": 40"));
    tightrope_analysis_free(a);
    CHECK(tightrope_analyze(c, 1, NULL, &a, &err) == TIGHTROPE_EINVAL);
    tightrope_curve_free(c);
}

int main(void)
{
    test_circle_closed_form();
    test_minrad_independent();
    test_arrays_and_files();
    test_errors();
    test_self_crossing();
    test_tighten();
    test_analyze();
    return tr_test_finish("test_api");
}
