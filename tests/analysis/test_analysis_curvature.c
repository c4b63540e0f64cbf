/* Curvature and torsion of inscribed-arc knots against closed forms:
 * circle (kappa = 1/r, tau = 0), the curvature-limited helix of the paper
 * (r = 0.2, pitch 0.8 pi: kappa = 1, tau = +2; mirror: tau = -2), block
 * averaging of a regular polygon, plateau ends and one-sided jump fits on a
 * profile with known steps. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/arc_profile.h"
#include "analysis/profile_features.h"
#include "analysis/shape_average.h"
#include "testlib.h"

#define M_PI 3.14159265358979323846

static double *regular_polygon(size_t n, double r)
{
    double *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * (double)i / (double)n;
        x[3 * i] = r * cos(t), x[3 * i + 1] = r * sin(t), x[3 * i + 2] = 0.0;
    }
    return x;
}

static void test_circle(void)
{
    tr_error err;
    size_t n = 360;
    double r = 2.5;
    double *x = regular_polygon(n, r);
    tr_arc_profile p;
    CHECK_OK(tr_arc_profile_compute(x, n, NULL, 0.0, &p, &err));
    /* The inscribed arcs touch the edges at their midpoints: radius r cos(pi/n). */
    double rc = r * cos(M_PI / (double)n);
    double kmax = 0.0, tmax = 0.0;
    for (size_t k = 0; k < n; k++) {
        kmax = fmax(kmax, fabs(p.kappa[k] - 1.0 / rc));
        tmax = fmax(tmax, fabs(p.tau[k]));
    }
    CHECK(kmax < 1e-12);
    CHECK(tmax < 1e-12);
    CHECK_NEAR(p.kappa[7], 1.0 / r, 0.6 * (M_PI / n) * (M_PI / n) / r);
    CHECK_NEAR(p.L_c, 2.0 * M_PI * rc, 1e-11);
    CHECK_NEAR(p.alpha[n - 1], 0.0, 1e-12);
    /* Whole circle at kappa >= 1/r (1 - 1e-4): one plateau covering everything. */
    tr_plateau *pl;
    size_t np;
    CHECK_OK(tr_profile_find_plateaus(&p, (1.0 - 1e-4) / r, 1, &pl, &np, &err));
    CHECK(np == 1 && pl[0].first == 0 && pl[0].last == n - 1);
    free(pl);
    tr_arc_profile_free(&p);

    /* m-averaging a regular n-gon gives a regular n/m-gon of radius
     * r sin(m pi/n) / (m sin(pi/n)) (sum of m unit vectors 2pi/n apart). */
    size_t m = 10;
    tr_averaged_knot av;
    CHECK_OK(tr_shape_average(x, n, m, 3, &av, &err));
    CHECK(av.n == n / m);
    double ra = r * sin(m * M_PI / n) / (m * sin(M_PI / n));
    double dmax = 0.0;
    for (size_t k = 0; k < av.n; k++)
        dmax = fmax(dmax, fabs(hypot(av.w[3 * k], av.w[3 * k + 1]) - ra));
    CHECK(dmax < 1e-13);
    /* block 0 = vertices 3..12, centre at vertex 7.5 */
    double e = 2.0 * r * sin(M_PI / n);
    CHECK_NEAR(av.pos[0], 7.5 * e, 1e-12);
    tr_averaged_knot_free(&av);
    free(x);
}

/* Helix r cos t, r sin t, c t over `turns` turns, n vertices per turn; the
 * profile is computed as if closed, and only arcs away from the closing edge
 * are checked. */
static void test_helix(double handed)
{
    tr_error err;
    double r = 0.2, c = handed * 0.8 * M_PI / (2.0 * M_PI);
    size_t per = 1000, turns = 2, n = per * turns;
    double *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * (double)i / (double)per;
        x[3 * i] = r * cos(t), x[3 * i + 1] = r * sin(t), x[3 * i + 2] = c * t;
    }
    tr_arc_profile p;
    CHECK_OK(tr_arc_profile_compute(x, n, NULL, 0.0, &p, &err));
    /* Edge e = 2 pi sqrt(r^2+c^2)/per ~ 2.8e-3: the polygon's kappa and tau
     * differ from the smooth helix's by O(e^2) ~ 1e-5 (prefactors ~1). Rounding
     * enters through edge vectors of size e taken from coordinates of size ~5:
     * 1e-16 * 5 / e / theta ~ 1e-10, far below. */
    double kerr = 0.0, terr = 0.0;
    for (size_t k = 5; k + 5 < n; k++) {
        kerr = fmax(kerr, fabs(p.kappa[k] - 1.0));
        terr = fmax(terr, fabs(p.tau[k] - 2.0 * handed));
    }
    CHECK(kerr < 2e-5);
    if (!(terr < 2e-5)) tr_test_report(__FILE__, __LINE__, "terr %g kerr %g tau %.12g", terr, kerr, p.tau[100]);
    CHECK(terr < 2e-5);
    /* accumulated torsion over one interior turn = tau * (turn length) */
    double turn = 2.0 * M_PI * sqrt(r * r + c * c);
    CHECK_NEAR(p.alpha[per + 10] - p.alpha[10], 2.0 * handed * turn, 1e-5);
    tr_arc_profile_free(&p);
    free(x);
}

/* A hand-made profile on a period of 10: kappa = 0.5 + 0.1 l below l = 2, 1 on
 * [2, 3], 1.2 - 0.05 (l - 3) above; torsion angles phi = 0.02 h (tau = 0.02)
 * plus a delta of weight 0.3 at the junction nearest l = 3. */
/* The hand-made profile's four jumps: kappa 0.7 -> 1 at l = 2 and by 0.2
 * at 3, alpha by 0.3 at 3 and none at 5 (test_jumps). */
static void check_jumps(const tr_arc_profile *p)
{
    tr_error err;
    tr_jump j;
    CHECK_OK(tr_profile_measure_jump(p, TR_JUMP_KAPPA, 2.0, 0.03, 0.3, &j, &err));
    CHECK_NEAR(j.jump, 1.0 - 0.7, 1e-9);
    CHECK_OK(tr_profile_measure_jump(p, TR_JUMP_KAPPA, 3.0, 0.03, 0.3, &j, &err));
    CHECK_NEAR(j.jump, 0.2, 1e-9);
    CHECK_OK(tr_profile_measure_jump(p, TR_JUMP_ALPHA, 3.0, 0.03, 0.3, &j, &err));
    CHECK_NEAR(j.jump, 0.3, 1e-9);
    CHECK_OK(tr_profile_measure_jump(p, TR_JUMP_ALPHA, 5.0, 0.03, 0.3, &j, &err));
    CHECK_NEAR(j.jump, 0.0, 1e-9);
}

static void test_jumps(void)
{
    tr_error err;
    size_t n = 1000;
    double L = 10.0, h = L / (double)n;
    tr_arc_profile p;
    memset(&p, 0, sizeof p);
    p.n = n;
    p.L = L;
    p.pos = calloc(n, sizeof(double));
    p.kappa = calloc(n, sizeof(double));
    p.dl = calloc(n, sizeof(double));
    p.jpos = calloc(n, sizeof(double));
    p.phi = calloc(n, sizeof(double));
    p.tau = calloc(n, sizeof(double));
    p.alpha = calloc(n, sizeof(double));
    for (size_t k = 0; k < n; k++) {
        double l = ((double)k + 0.5) * h;
        p.pos[k] = l;
        p.dl[k] = h;
        p.jpos[k] = l + 0.5 * h;
        p.kappa[k] = l < 2.0 ? 0.5 + 0.1 * l : l < 3.0 ? 1.0 : 1.2 - 0.05 * (l - 3.0);
        p.phi[k] = 0.02 * h + (fabs(p.jpos[k] - 3.0) < 0.5 * h ? 0.3 : 0.0);
    }
    tr_plateau *pl;
    size_t np;
    CHECK_OK(tr_profile_find_plateaus(&p, 1.0 - 1e-4, 3, &pl, &np, &err));
    /* kappa >= 1 on [2, 3] and again just after 3 (1.2 - ...) until l = 7 */
    CHECK(np == 1);
    if (np == 1) {
        CHECK_NEAR(pl[0].l1, 2.0, 1e-12);
        CHECK_NEAR(pl[0].l2, 7.0, 1e-12);
    }
    free(pl);
    /* a plateau short of convergence: single arcs on it dip by 1e-3 and
     * 5e-3; at 1 - 1e-4 it breaks into three runs, with the margin 0.02 it
     * is one again: from the jump at 2 to where the smooth decline
     * 1.2 - 0.05 (l - 3) reaches 0.98, l = 7.4 */
    double keep1 = p.kappa[250], keep2 = p.kappa[270];
    p.kappa[250] = 1.0 - 1e-3; /* l = 2.505 */
    p.kappa[270] = 1.0 - 5e-3;
    CHECK_OK(tr_profile_find_plateaus(&p, 1.0 - 1e-4, 3, &pl, &np, &err));
    CHECK(np == 3);
    free(pl);
    CHECK_OK(tr_profile_find_plateaus_margin(&p, 1.0 - 1e-4, 1.0 - 0.02, 3, &pl, &np, &err));
    CHECK(np == 1);
    if (np == 1) {
        CHECK_NEAR(pl[0].l1, 2.0, 1e-12);
        CHECK_NEAR(pl[0].l2, 7.4, 1e-12);
    }
    free(pl);
    /* a run at the margin level without min_core arcs at the core level is
     * no plateau: kappa 0.99 on [8, 8.5] */
    for (size_t k = 800; k < 850; k++)
        p.kappa[k] = 0.99;
    CHECK_OK(tr_profile_find_plateaus_margin(&p, 1.0 - 1e-4, 1.0 - 0.02, 3, &pl, &np, &err));
    CHECK(np == 1);
    free(pl);
    for (size_t k = 800; k < 850; k++)
        p.kappa[k] = 1.2 - 0.05 * (p.pos[k] - 3.0);
    p.kappa[250] = keep1, p.kappa[270] = keep2;
    tr_jump j;
    check_jumps(&p);
    CHECK_OK(tr_profile_measure_jump(&p, TR_JUMP_KAPPA, 2.0, 0.03, 0.3, &j, &err));
    CHECK(j.err < 1e-9);
    /* across the period boundary: kappa at 0 jumps from 1.2 - 0.05*7 = 0.85 to 0.5 */
    CHECK_OK(tr_profile_measure_jump(&p, TR_JUMP_KAPPA, 0.0, 0.03, 0.3, &j, &err));
    CHECK_NEAR(j.jump, 0.5 - 0.85, 1e-9);
    CHECK(tr_profile_measure_jump(&p, TR_JUMP_KAPPA, 2.0, 0.03, 0.035, &j, &err) == TR_EGEOMETRY);

    /* The tight polygon's alternation: kappa +- 0.05 and phi +- 0.1 from
     * vertex to vertex (alpha then zigzags by 0.1, as much as the jumps).
     * Neighbours averaged in pairs take a period-2 wave out exactly. */
    for (size_t k = 0; k < n; k++) {
        double sgn = k % 2 ? -1.0 : 1.0;
        p.kappa[k] += 0.05 * sgn;
        p.phi[k] += 0.1 * sgn;
    }
    check_jumps(&p);

    /* A curved approach, as kappa rises to the trefoil's plateau:
     * kappa = 0.5 + 0.1 l + 0.5 (2 - l)^2 on [1, 2), still 0.7 at 2-. The
     * quadratics give the jump 0.3 (to the pairs' h^2/8 = 1.25e-5 offset of
     * a parabola); a line over [0.03, 0.3] leans by 0.5 (w^2 + 4 w W +
     * W^2) / 6 = 0.0106, and the error says so. */
    for (size_t k = 0; k < n; k++)
        if (p.pos[k] >= 1.0 && p.pos[k] < 2.0)
            p.kappa[k] += 0.5 * (2.0 - p.pos[k]) * (2.0 - p.pos[k]);
    CHECK_OK(tr_profile_measure_jump(&p, TR_JUMP_KAPPA, 2.0, 0.03, 0.3, &j, &err));
    CHECK_NEAR(j.jump, 0.3, 5e-5);
    CHECK(j.err > 0.008 && j.err < 0.02);
    tr_arc_profile_free(&p);
}

int main(void)
{
    test_circle();
    test_helix(+1.0);
    test_helix(-1.0);
    test_jumps();
    return tr_test_finish("test_analysis_curvature");
}
