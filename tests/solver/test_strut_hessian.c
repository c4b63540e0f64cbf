/* Tests the exact strut distance's gradient and Hessian (strut_hessian.h)
 * against central finite differences of the distance itself (kernels/segment_distance.h),
 * for the cases the closest points can be in: both interior (crossing
 * skew segments), one at an end, both at ends, and nearly parallel. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "segment_distance.h"
#include "solver/strut_hessian.h"
#include "testlib.h"

static double dist12(const double *x)
{
    double s, t;
    return tr_segment_distance(x, x + 3, x + 6, x + 9, &s, &t);
}

/* the derivatives at x against differences of step h; tol relative to the
 * largest entry (central differences: error ~ h^2 |third derivative|) */
static void check_case(const char *name, const double *x0, double h, double tol)
{
    double g[12], H[144], x[12];
    memcpy(x, x0, sizeof x);
    double d = tr_strut_distance_derivs(x, x + 3, x + 6, x + 9, g, H);
    CHECK_NEAR(d, dist12(x), 1e-15);
    double gmax = 0.0, hmax = 0.0, gerr = 0.0, herr = 0.0;
    for (int i = 0; i < 12; i++) {
        double xp[12], xm[12], gp[12], gm[12];
        memcpy(xp, x, sizeof x);
        memcpy(xm, x, sizeof x);
        xp[i] += h;
        xm[i] -= h;
        double fd = (dist12(xp) - dist12(xm)) / (2.0 * h);
        gmax = fmax(gmax, fabs(g[i]));
        gerr = fmax(gerr, fabs(fd - g[i]));
        tr_strut_distance_derivs(xp, xp + 3, xp + 6, xp + 9, gp, NULL);
        tr_strut_distance_derivs(xm, xm + 3, xm + 6, xm + 9, gm, NULL);
        for (int j = 0; j < 12; j++) {
            double fh = (gp[j] - gm[j]) / (2.0 * h);
            hmax = fmax(hmax, fabs(H[i * 12 + j]));
            herr = fmax(herr, fabs(fh - H[i * 12 + j]));
            /* symmetric */
            if (!(fabs(H[i * 12 + j] - H[j * 12 + i]) <= 1e-12 * (1.0 + fabs(H[i * 12 + j]))))
                tr_test_report(__FILE__, __LINE__, "%s: H not symmetric at %d %d", name, i, j);
        }
    }
    if (!(gerr <= tol * gmax) || !(herr <= tol * fmax(hmax, 1.0))) {
        tr_test_report(__FILE__, __LINE__, "%s: gradient error %.3g (max %.3g), Hessian error %.3g (max %.3g)", name,
                       gerr, gmax, herr, hmax);
    }
}

int main(void)
{
    /* skew, both closest points interior: d = 2 exactly (z offset) */
    const double skew[12] = {-1, 0.1, 0, 1, -0.2, 0, 0.2, -1, 2, -0.1, 1, 2};
    check_case("skew interior", skew, 1e-5, 1e-7);
    double s, t;
    double d = tr_segment_distance(skew, skew + 3, skew + 6, skew + 9, &s, &t);
    CHECK(s > 0.1 && s < 0.9 && t > 0.1 && t < 0.9);
    CHECK_NEAR(d, 2.0, 1e-14); /* the segments lie in z = 0 and z = 2 */
    /* one closest point at an end (s = 1), the other interior */
    const double end1[12] = {-2, 0, 0, -0.5, 0.1, 0.05, 0.3, -1, 1.8, 0.1, 1, 2.1};
    check_case("end and interior", end1, 1e-5, 1e-7);
    /* both at ends: point-point distance */
    const double ends[12] = {0, 0, 0, -1, 0.2, 0.1, 0.8, 0.5, 2, 1.2, 0.9, 2.4};
    check_case("end and end", ends, 1e-5, 1e-7);
    /* nearly parallel, overlapping (a tight rope's contacts are of this kind):
     * the distance is flat along the overlap */
    const double par[12] = {0, 0, 0, 0.01, 0, 0.0001, 0.003, 2, 0.00002, 0.013, 2.00003, 0.0001};
    check_case("nearly parallel", par, 1e-7, 1e-5);
    /* gradient of a distance has unit length (in each strand's pair of points
     * the weights sum to 1): |g_p0 + g_p1| = 1 */
    double g[12];
    tr_strut_distance_derivs(skew, skew + 3, skew + 6, skew + 9, g, NULL);
    double n[3] = {g[0] + g[3], g[1] + g[4], g[2] + g[5]};
    CHECK_NEAR(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-14);
    if (tr_test_failures)
        printf("%d failures\n", tr_test_failures);
    return tr_test_failures ? 1 : 0;
}
