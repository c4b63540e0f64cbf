/* Open ropes (issue 23): the inscribed-arc profiles of an open polyline
 * against closed forms. The helix r cos t, r sin t, c t has kappa =
 * r/(r^2+c^2) and tau = c/(r^2+c^2): r = 0.2, c = +-0.4 (pitch 0.8 pi) gives
 * kappa = 1, tau = +-2 everywhere, up to the ends; the end vertices carry no
 * arc; a planar open arc has tau = 0. */
#include <math.h>
#include <stdlib.h>

#include "analysis/open_rope.h"
#include "testlib.h"

#define M_PI 3.14159265358979323846

static double *helix(size_t n, double turns, double r, double c)
{
    double *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * turns * (double)i / (double)(n - 1);
        x[3 * i] = r * cos(t), x[3 * i + 1] = r * sin(t), x[3 * i + 2] = c * t;
    }
    return x;
}

static void test_helix(double hand)
{
    tr_error err;
    double r = 0.2, c = hand * 0.4;
    double kappa = r / (r * r + c * c), tau = c / (r * r + c * c);
    size_t n = 2000;
    double *x = helix(n, 3.0, r, c);
    tr_open_rope rope;
    CHECK_OK(tr_open_rope_analyze(x, n, &rope, &err));
    CHECK(rope.prof.n == n - 2 && rope.prof.nj == n - 3 && !rope.prof.closed);
    /* edge e = 6 pi sqrt(r^2+c^2)/1999 ~ 4.2e-3: the polygon's kappa and tau
     * differ from the helix's by O(e^2) ~ 1e-5, well inside 1e-3 */
    double kerr = 0.0, terr = 0.0;
    for (size_t k = 0; k < rope.prof.n; k++)
        kerr = fmax(kerr, fabs(rope.prof.kappa[k] - kappa));
    for (size_t k = 0; k < rope.prof.nj; k++)
        terr = fmax(terr, fabs(rope.prof.tau[k] - tau));
    CHECK(kerr < 1e-4);
    CHECK(terr < 1e-4);
    /* positions: arc k at vertex k + 1, arclength from vertex 0 */
    double dt = 6.0 * M_PI / (double)(n - 1), e = hypot(2.0 * r * sin(0.5 * dt), c * dt); /* chord */
    CHECK_NEAR(rope.prof.pos[0], e, 1e-9);
    CHECK_NEAR(rope.L, e * (double)(n - 1), 1e-9);
    CHECK_NEAR(rope.prof.jpos[0], 1.5 * e, 1e-9);
    /* total torsion: tau times the span of the junctions' h, (n - 3) e */
    CHECK_NEAR(rope.total_torsion, tau * e * (double)(n - 3), 1e-4);
    tr_open_rope_free(&rope);
    free(x);
}

/* A planar quarter circle: kappa = 1/R on every interior arc, tau = 0; and
 * a straight start carries the first binormal back (no NaN). */
static void test_planar_and_straight(void)
{
    tr_error err;
    size_t n = 200;
    double R = 3.0;
    double *x = malloc(3 * (n + 3) * sizeof *x);
    for (size_t i = 0; i < 3; i++) /* three straight vertices before the arc */
        x[3 * i] = R, x[3 * i + 1] = -0.1 * (double)(3 - i), x[3 * i + 2] = 0.0;
    for (size_t i = 0; i < n; i++) {
        double t = 0.5 * M_PI * (double)i / (double)(n - 1);
        x[3 * (i + 3)] = R * cos(t), x[3 * (i + 3) + 1] = R * sin(t), x[3 * (i + 3) + 2] = 0.0;
    }
    tr_open_rope rope;
    CHECK_OK(tr_open_rope_analyze(x, n + 3, &rope, &err));
    double dth = 0.5 * M_PI / (double)(n - 1), rc = R * cos(0.5 * dth);
    for (size_t k = 3; k < rope.prof.n; k++) /* arcs at vertices 4 .. n + 1 */
        CHECK_NEAR(rope.prof.kappa[k], 1.0 / rc, 1e-9);
    CHECK(rope.prof.kappa[0] == 0.0 && rope.prof.kappa[1] == 0.0);
    for (size_t k = 0; k < rope.prof.nj; k++)
        CHECK(fabs(rope.prof.tau[k]) < 1e-12);
    tr_open_rope_free(&rope);
    free(x);
    /* too short */
    double y[9] = {0, 0, 0, 1, 0, 0, 1, 1, 0};
    CHECK(tr_open_rope_analyze(y, 3, &rope, &err) == TR_EINVAL);
}

int main(void)
{
    test_helix(1.0);
    test_helix(-1.0);
    test_planar_and_straight();
    return tr_test_finish("test_analysis_open_rope");
}
