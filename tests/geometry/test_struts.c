/* This file contains the test of the strut rules (geometry/struts.h): the
 * exclusion gap's values and bounds, and the strut gradient against central
 * differences of the segment distance. */
#include <math.h>


#include "geometry/struts.h"
#include "segment_distance.h"
#include "testlib.h"

/* c = P(s) - Q(t) */
static const double *connector(const double pts[4][3], double s, double t, double c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = (pts[0][k] + s * (pts[1][k] - pts[0][k])) - (pts[2][k] + t * (pts[3][k] - pts[2][k]));
    return c;
}

/* max over the 12 coordinates of |analytic - central difference| of d */
static double gradient_error(const double pts[4][3], double scale)
{
    double s, t, c[3], d = tr_segment_distance(pts[0], pts[1], pts[2], pts[3], &s, &t), g[4][3];
    tr_strut_gradient(connector(pts, s, t, c), s, t, d, scale, g);
    double worst = 0.0, h = 1e-6;
    for (int v = 0; v < 4; v++)
        for (int k = 0; k < 3; k++) {
            double p[4][3], m[4][3];
            for (int a = 0; a < 4; a++)
                for (int b = 0; b < 3; b++)
                    p[a][b] = m[a][b] = pts[a][b];
            p[v][k] += h;
            m[v][k] -= h;
            double sp, tp, sm, tm;
            double dp = tr_segment_distance(p[0], p[1], p[2], p[3], &sp, &tp);
            double dm = tr_segment_distance(m[0], m[1], m[2], m[3], &sm, &tm);
            double fd = scale * (dp - dm) / (2.0 * h);
            worst = fmax(worst, fabs(g[v][k] - fd));
        }
    return worst;
}

int main(void)
{
    /* ceil(pi r / ebar), at least 2, at most 1e9, 2 without a positive ebar */
    CHECK(tr_exclusion_gap(1.0, 0.1) == 32);   /* pi / 0.1 = 31.4 */
    CHECK(tr_exclusion_gap(2.0, 0.1) == 63);   /* 62.8 */
    CHECK(tr_exclusion_gap(1.0, 0.5) == 7);    /* 6.28 */
    CHECK(tr_exclusion_gap(1.0, 4.0) == 2);    /* 0.79: the floor */
    CHECK(tr_exclusion_gap(1.0, 1e-12) == 1000000000);
    CHECK(tr_exclusion_gap(1.0, 0.0) == 2);
    CHECK(tr_exclusion_gap(1.0, -1.0) == 2);
    CHECK(tr_exclusion_gap(1.0, NAN) == 2);

    /* interior closest points (skew edges), an end point of one edge, and
     * both ends (the closest points at vertices) */
    const double skew[4][3] = {{0, 0, 0}, {1, 0.2, 0}, {0.3, -0.5, 2.1}, {0.6, 0.9, 1.9}};
    const double end[4][3] = {{0, 0, 0}, {1, 0, 0}, {1.5, -0.5, 2}, {1.5, 0.5, 2.2}};
    const double corner[4][3] = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 2, 0.5}};
    CHECK(gradient_error(skew, 1.0) < 1e-7);
    CHECK(gradient_error(skew, -2.5) < 1e-7);
    CHECK(gradient_error(end, 1.0) < 1e-7);
    CHECK(gradient_error(corner, 0.75) < 1e-7);

    /* the four parts sum to zero (a translation does not change d) */
    double s, t, c[3], g[4][3];
    double d = tr_segment_distance(skew[0], skew[1], skew[2], skew[3], &s, &t);
    tr_strut_gradient(connector(skew, s, t, c), s, t, d, 1.0, g);
    for (int k = 0; k < 3; k++)
        CHECK(fabs(g[0][k] + g[1][k] + g[2][k] + g[3][k]) < 1e-15);
    return tr_test_finish("test_struts");
}
