/* The KKT certificate (kkt.h) against closed forms.
 *
 * Regular N-gon with vertex radius R = 1/cos(pi/N): every edge is
 * 2 tan(pi/N) and every turning angle 2 pi/N, so Rawdon's MinRad is exactly
 * 1 at every vertex; the polygon is critical for length at thickness 1 (it
 * shrinks only by bending harder) and its residual is 0. N is odd so that
 * no two edges are exactly 2 apart (no struts): the curvature rows alone
 * hold the tension.
 *
 * The same polygon looser (scaled by 1.1, certified at radius 1): no
 * curvature row is near its bound and only the equal-edge rows, with their
 * free common length ebar, can take the tension. By symmetry the best
 * multipliers are equal, y on every edge; the tension g (|g|^2 = G =
 * N (2 sin(pi/N))^2) is reduced to (1 - y) g and the ebar equation leaves
 * y (weighted by ne = N in the metric of kkt.h), so
 *   residual^2 = min_y [(1-y)^2 G + N y^2] / G = N / (N + G).
 * For several loose components the minima add: sum G_k N_k / (G_k + N_k)
 * over sum G_k.
 *
 * A straight open rope whose end vertices are held on planes normal to it
 * (the clasp's constraint) has no tension left after projection: force 0.
 * With planes along it instead, its ends slide in; the edge multipliers y_a
 * of the chain leave (1 - y_0) and (1 - y_{m-1}) at the ends, y_{a-1} - y_a
 * inside and (sum y) / sqrt(m) on the common length: a small linear least
 * squares, solved here directly by its normal equations.
 *
 * The per-vertex forces (tr_kkt_certify_forces) of the loose polygon: the
 * pull 2 sin(pi/N) at every vertex, of which N / (G + N) is left.
 *
 * Certified at its own thickness (radius unset) a scaled tight polygon is
 * tight again: the residual does not depend on the scale. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "oracle/kkt.h"
#include "testlib.h"
#include "oracle/thickness.h"
#include "util/vec3.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void polygon(tr_curve *c, size_t comp_start, size_t n, double R, double off)
{
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * (double)i / (double)n;
        double *x = c->x + 3 * (comp_start + i);
        x[0] = R * cos(t) + off;
        x[1] = R * sin(t);
        x[2] = 0.0;
    }
}

static double loose_residual2_part(size_t n)
{
    double s = 2.0 * sin(M_PI / (double)n), G = (double)n * s * s;
    return G * (double)n / (G + (double)n);
}

/* min over y of (1-y_0)^2 + (1-y_{m-1})^2 + sum (y_{a-1}-y_a)^2 + (sum y)^2/m,
 * divided by the tension 2, square-rooted: Gaussian elimination on the
 * m x m normal equations (m <= 64). */
static double chain_residual(size_t m)
{
    double A[64][65] = {{0}};
    for (size_t i = 0; i < m; i++) {
        for (size_t j = 0; j < m; j++)
            A[i][j] = 1.0 / (double)m; /* the common-length term */
        if (i == 0 || i == m - 1) {
            A[i][i] += 1.0;
            A[i][m] += 1.0;
        }
        if (i > 0) { /* (y_{i-1} - y_i)^2 */
            A[i][i] += 1.0;
            A[i][i - 1] -= 1.0;
        }
        if (i + 1 < m) { /* (y_i - y_{i+1})^2 */
            A[i][i] += 1.0;
            A[i][i + 1] -= 1.0;
        }
    }
    for (size_t k = 0; k < m; k++)
        for (size_t i = k + 1; i < m; i++) {
            double f = A[i][k] / A[k][k];
            for (size_t j = k; j <= m; j++)
                A[i][j] -= f * A[k][j];
        }
    double y[64];
    for (size_t k = m; k-- > 0;) {
        double v = A[k][m];
        for (size_t j = k + 1; j < m; j++)
            v -= A[k][j] * y[j];
        y[k] = v / A[k][k];
    }
    double f = (1.0 - y[0]) * (1.0 - y[0]) + (1.0 - y[m - 1]) * (1.0 - y[m - 1]), sum = 0.0;
    for (size_t a = 0; a < m; a++) {
        sum += y[a];
        if (a > 0)
            f += (y[a - 1] - y[a]) * (y[a - 1] - y[a]);
    }
    f += sum * sum / (double)m;
    return sqrt(f / 2.0);
}

static void test_tight_polygon(void)
{
    const size_t n = 101;
    unsigned char closed = 1;
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, &closed, &err));
    polygon(&c, 0, n, 1.0 / cos(M_PI / (double)n), 0.0);
    tr_thickness th;
    CHECK_OK(tr_thickness_measure(&c, NULL, &th, NULL, &err));
    CHECK_NEAR(th.minrad, 1.0, 1e-12);

    tr_kkt_params p;
    tr_kkt_params_default(&p);
    p.radius = 1.0;
    tr_kkt k;
    CHECK_OK(tr_kkt_certify(&c, &p, &k, &err));
    CHECK(k.residual < 1e-10);
    CHECK(k.converged);
    CHECK(k.strut_rows == 0);
    CHECK(k.minrad_rows == 2 * n); /* both sides of every vertex are at the bound */
    CHECK_NEAR(k.force, (double)n * 2.0 * sin(M_PI / (double)n) / sqrt((double)n), 1e-12);

    /* looser by 10 %: only the edges and their common length hold */
    for (size_t i = 0; i < 3 * n; i++)
        c.x[i] *= 1.1;
    CHECK_OK(tr_kkt_certify(&c, &p, &k, &err));
    CHECK(k.minrad_rows == 0 && k.strut_rows == 0);
    double s = 2.0 * sin(M_PI / (double)n), G = (double)n * s * s;
    CHECK_NEAR(k.residual, sqrt(loose_residual2_part(n) / G), 1e-12);
    CHECK(k.converged);
    /* where: every vertex keeps the share (1 - y) = N / (G + N) of its pull */
    double gv[3 * 101], rv[3 * 101];
    CHECK_OK(tr_kkt_certify_forces(&c, &p, &k, gv, rv, &err));
    double worst = 0.0;
    for (size_t i = 0; i < n; i++) {
        CHECK_NEAR(v3_norm(gv + 3 * i), s, 1e-14);
        worst = fmax(worst, fabs(v3_norm(rv + 3 * i) - s * (double)n / (G + (double)n)));
    }
    CHECK(worst < 1e-12);

    /* at its own thickness (1.1) the scaled polygon is tight again */
    CHECK_OK(tr_kkt_certify(&c, NULL, &k, &err));
    CHECK_NEAR(k.radius, 1.1, 1e-12);
    CHECK(k.residual < 1e-10);
    tr_curve_free(&c);
}

static void test_two_loose_components(void)
{
    size_t nv[2] = {61, 101};
    unsigned char closed[2] = {1, 1};
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 2, nv, closed, &err));
    polygon(&c, 0, nv[0], 3.0, 0.0);
    polygon(&c, nv[0], nv[1], 4.0, 100.0);
    tr_kkt_params p;
    tr_kkt_params_default(&p);
    p.radius = 1.0;
    tr_kkt k;
    CHECK_OK(tr_kkt_certify(&c, &p, &k, &err));
    double num = 0.0, den = 0.0;
    for (int q = 0; q < 2; q++) {
        double s = 2.0 * sin(M_PI / (double)nv[q]);
        num += loose_residual2_part(nv[q]);
        den += (double)nv[q] * s * s;
    }
    CHECK_NEAR(k.residual, sqrt(num / den), 1e-12);
    CHECK(k.minrad_rows == 0 && k.strut_rows == 0);
    tr_curve_free(&c);
}

/* Many loose components, as a link of small circles: the minima add as for
 * two (the closed form above). 300 small ones (25 rows each) go into the
 * sparse factor as their own columns, the one large one (1001 rows) keeps
 * its Woodbury column (rowchol.c): both at once, against the closed form. */
static void test_many_loose_components(void)
{
    enum { M = 301 };
    size_t nv[M];
    unsigned char closed[M];
    for (int q = 0; q < M; q++) {
        nv[q] = q == 0 ? 1001 : 25;
        closed[q] = 1;
    }
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, M, nv, closed, &err));
    polygon(&c, 0, nv[0], 200.0, -1000.0);
    for (int q = 1; q < M; q++)
        polygon(&c, c.start[q], nv[q], 3.0 + 0.001 * q, 20.0 * q);
    tr_kkt_params p;
    tr_kkt_params_default(&p);
    p.radius = 1.0;
    tr_kkt k;
    CHECK_OK(tr_kkt_certify(&c, &p, &k, &err));
    double num = 0.0, den = 0.0;
    for (int q = 0; q < M; q++) {
        double s = 2.0 * sin(M_PI / (double)nv[q]);
        num += loose_residual2_part(nv[q]);
        den += (double)nv[q] * s * s;
    }
    CHECK_NEAR(k.residual, sqrt(num / den), 1e-12);
    CHECK(k.minrad_rows == 0 && k.strut_rows == 0);
    CHECK(k.converged);
    tr_curve_free(&c);
}

/* A curve far from the origin for its size is certified where it is: the
 * tight 101-gon moved by 1e6 (its vertices rounded to the 1.2e-10 between
 * doubles there, a turning-angle error of ~2e-9 against 0.062) stays
 * critical, as at the origin; moved by 1e15 (steps of 0.125 against edges
 * of 0.062) it is refused, as the thickness oracle refuses it. */
static void test_far_from_origin(void)
{
    const size_t n = 101;
    unsigned char closed = 1;
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, &closed, &err));
    polygon(&c, 0, n, 1.0 / cos(M_PI / (double)n), 1e6);
    tr_kkt k;
    CHECK_OK(tr_kkt_certify(&c, NULL, &k, &err));
    CHECK_NEAR(k.radius, 1.0, 1e-6);
    CHECK(k.residual < 1e-6);
    polygon(&c, 0, n, 1.0 / cos(M_PI / (double)n), 1e15);
    CHECK(tr_kkt_certify(&c, NULL, &k, &err) == TR_EGEOMETRY);
    CHECK(strstr(err.msg, "far from the origin") != NULL);
    tr_curve_free(&c);
}

static void test_straight_clasp_rope(void)
{
    const size_t n = 21;
    unsigned char closed = 0;
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, &closed, &err));
    for (size_t i = 0; i < n; i++)
        c.x[3 * i] = (double)i;
    for (int end = 0; end < 2; end++) {
        tr_constraint k = {.kind = TR_CST_PLANE, .id = end + 1, .u = {1.0, 0.0, 0.0}, .d = end ? (double)(n - 1) : 0.0};
        int idx = tr_curve_add_constraint(&c, &k, &err);
        CHECK(idx >= 0);
        c.vcst[end ? n - 1 : 0] = idx;
    }
    tr_kkt_params p;
    tr_kkt_params_default(&p);
    p.radius = 1.0;
    tr_kkt kk;
    CHECK_OK(tr_kkt_certify(&c, &p, &kk, &err));
    CHECK(kk.force < 1e-12);
    CHECK(kk.residual == 0.0);
    CHECK(kk.converged);

    /* the same rope with its ends free to slide along it is pulled in by a
     * unit pull at each end; only the equal-edge rows are left */
    c.cst[0].u[0] = 0.0;
    c.cst[0].u[1] = 1.0;
    c.cst[1].u[0] = 0.0;
    c.cst[1].u[1] = 1.0;
    CHECK_OK(tr_kkt_certify(&c, &p, &kk, &err));
    CHECK_NEAR(kk.force, sqrt(2.0), 1e-12);
    CHECK_NEAR(kk.residual, chain_residual(n - 1), 1e-12);
    tr_curve_free(&c);
}

static void test_bad_parameters(void)
{
    const size_t n = 11;
    unsigned char closed = 1;
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, &closed, &err));
    polygon(&c, 0, n, 5.0, 0.0);
    tr_kkt_params p;
    tr_kkt_params_default(&p);
    p.band = -1.0;
    tr_kkt k;
    CHECK(tr_kkt_certify(&c, &p, &k, &err) == TR_EINVAL);
    tr_curve_free(&c);
}

int main(void)
{
    test_tight_polygon();
    test_two_loose_components();
    test_many_loose_components();
    test_far_from_origin();
    test_straight_clasp_rope();
    test_bad_parameters();
    return tr_test_failures ? 1 : 0;
}
