/* The whole per-component pipeline on a stadium: two unit semicircles joined
 * by straight segments of length s. Curvature is exactly 1 on the
 * semicircles and 0 on the straights, so the kappa = 1 plateaus, their ends
 * (a quarter circle, pi/2, either side of the apex) and the curvature jumps
 * (1 at each end) are known in closed form; the in-plane twofold axes give
 * the verdict C2, and the origin rule picks a semicircle apex (the twofold
 * point with the higher curvature). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/analysis_report.h"
#include "analysis/portrait.h"
#include "testlib.h"

#define PI 3.14159265358979323846

/* Point at arclength t on the stadium, starting at the apex of the right
 * semicircle (x = s/2 + 1, y = 0), counter-clockwise. */
static void stadium(double s, double t, double *p)
{
    double L = 2.0 * PI + 2.0 * s;
    t = fmod(t, L);
    if (t < 0)
        t += L;
    p[2] = 0.0;
    if (t < PI / 2) { /* upper quarter of the right cap */
        p[0] = s / 2 + cos(t), p[1] = sin(t);
    } else if (t < PI / 2 + s) { /* top straight, leftwards */
        p[0] = s / 2 - (t - PI / 2), p[1] = 1.0;
    } else if (t < 3 * PI / 2 + s) { /* left cap */
        double a = PI / 2 + (t - PI / 2 - s);
        p[0] = -s / 2 + cos(a), p[1] = sin(a);
    } else if (t < 3 * PI / 2 + 2 * s) { /* bottom straight, rightwards */
        p[0] = -s / 2 + (t - 3 * PI / 2 - s), p[1] = -1.0;
    } else { /* lower quarter of the right cap */
        double a = 3 * PI / 2 + (t - 3 * PI / 2 - 2 * s);
        p[0] = s / 2 + cos(a), p[1] = sin(a);
    }
}

int main(void)
{
    tr_error err;
    double s = 3.0, L = 2.0 * PI + 2.0 * s;
    size_t n = 2000;
    double *x = malloc(3 * n * sizeof *x);
    /* start away from the apex so the origin has to be found */
    for (size_t i = 0; i < n; i++)
        stadium(s, 1.234 + (double)i * L / (double)n, x + 3 * i);
    tr_analysis a;
    tr_analysis_opts o = {.m = 10};
    CHECK_OK(tr_analyze_component(x, n, NULL, 0, &o, &a, &err));
    CHECK(a.sym.verdict == TR_SYM_C2);
    /* apexes at arclength 0 and L/2 on the stadium, i.e. -1.234 and
     * L/2 - 1.234 on the input polygon (chords shorten L by ~1e-6) */
    double o1 = fmod(a.sym.origin + 1.234, a.L / 2.0);
    CHECK(fabs(o1) < 1e-3 || fabs(o1 - a.L / 2.0) < 1e-3);
    CHECK(a.nplateaus == 2);
    CHECK(a.have_l12);
    double me = o.m * L / (double)n;
    /* the plateau through the origin: from L - pi/2 to pi/2, less half an
     * averaging block at each end (an averaged vertex is on the cap only when
     * its whole block is); ends resolved to one averaged edge */
    CHECK_NEAR(a.l1, a.L - PI / 2 + 0.5 * me, me);
    CHECK_NEAR(a.l2, PI / 2 - 0.5 * me, me);
    CHECK_NEAR(a.dkappa1.jump, 1.0, 0.01);
    CHECK_NEAR(a.dkappa2.jump, 1.0, 0.01);
    CHECK(a.dkappa1.err < 0.01);
    /* planar: no torsion anywhere */
    CHECK_NEAR(a.dalpha1.jump, 0.0, 1e-9);
    CHECK(!a.have_sigma); /* no contacts given */
    char *json = NULL;
    tr_report_ctx ctx = {"stadium", 0, 1.0, NULL, 0};
    CHECK_OK(tr_report_summary_json(&a, &ctx, &json));
    CHECK(json && strstr(json, "\"verdict\": \"C2\""));
    free(json);
    tr_analysis_free(&a);
    free(x);
    return tr_test_finish("test_analysis_pipeline");
}
