/* analyze's default averaging block follows N (issue 46 item 4): m is the
 * paper's arclength window s = 10 x 1.63192456437e-4 (its m = 10 at
 * N = 200640) in edges, m = max(1, round(s / e)), e = L/N.
 * - closed forms: the paper's own N and length give its m = 10; a regular
 *   n-gon inscribed in the unit circle, L = 2 n sin(pi/n), gives
 *   round(s n / L), so m doubles with N within rounding;
 * - the tight N = 2400 trefoil (bench/data/trefoil_2400.vect): MinRad >= 1
 *   bounds every inscribed-arc curvature by 1, and the ideal trefoil reaches
 *   1 on six plateaus, so the analysed curvature's maximum is 1 to within
 *   the polygon's dips (5e-3 at this N). The old default m = 10 averaged
 *   over 0.136, near the plateau width 0.161, and drew a peak of 0.89. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/analysis_report.h"
#include "analysis/portrait.h"
#include "curve/curve_io.h"
#include "oracle/thickness.h"
#include "testlib.h"

#define PI 3.14159265358979323846

static double polygon_length(size_t n) { return 2.0 * (double)n * sin(PI / (double)n); }

static double max_kappa(const tr_analysis *a)
{
    double k = 0.0;
    for (size_t i = 0; i < a->prof.n; i++)
        k = fmax(k, a->prof.kappa[i]);
    return k;
}

int main(void)
{
    tr_error err;
    /* the paper's knot: L_p = 32.742934460, N = 200640, its m = 10 */
    CHECK(tr_analysis_default_m(32.742934460, 200640) == 10);
    /* s n / (2 pi): 20000 -> 5.195, 40000 -> 10.39; 400000 -> 103.9, 800000 -> 207.8 */
    size_t ns[4] = {20000, 40000, 400000, 800000}, want[4] = {5, 10, 104, 208};
    for (int i = 0; i < 4; i++)
        CHECK(tr_analysis_default_m(polygon_length(ns[i]), ns[i]) == want[i]);
    for (int i = 0; i < 4; i += 2) { /* doubling N doubles m, within rounding (+-1/2 each) */
        size_t m1 = tr_analysis_default_m(polygon_length(ns[i]), ns[i]);
        size_t m2 = tr_analysis_default_m(polygon_length(ns[i + 1]), ns[i + 1]);
        CHECK(m2 + 1 >= 2 * m1 && m2 <= 2 * m1 + 1);
    }
    /* coarse polygons average nothing; unusable lengths and tiny units
     * (s n / L beyond size_t) stay inside [1, n/4] */
    CHECK(tr_analysis_default_m(polygon_length(400), 400) == 1);
    CHECK(tr_analysis_default_m(32.74, 2400) == 1);
    CHECK(tr_analysis_default_m(1e-300, 400) == 100);
    CHECK(tr_analysis_default_m(NAN, 400) == 1);
    CHECK(tr_analysis_default_m(0.0, 400) == 1);
    CHECK(tr_analysis_default_m(1.0, 3) == 1);

    tr_curve c;
    const char *path = TR_SOURCE_DIR "/bench/data/trefoil_2400.vect";
    CHECK_OK(tr_curve_read(path, TR_FORMAT_AUTO, &c, &err));
    if (tr_test_failures)
        return tr_test_finish("test_analysis_default_m");
    size_t n = tr_comp_nv(&c, 0);
    CHECK(n == 2400);
    tr_thickness th;
    CHECK_OK(tr_thickness_measure(&c, NULL, &th, NULL, &err));
    for (size_t i = 0; i < 3 * n; i++) /* to thickness 1, as analyze does */
        c.x[i] /= th.thickness;

    tr_analysis a;
    CHECK_OK(tr_analyze_component(c.x, n, NULL, 0, NULL, &a, &err));
    CHECK(a.m == 1 && a.m_default); /* e = 0.0136: s / e = 0.12 */
    double k1 = max_kappa(&a);
    CHECK_NEAR(k1, 1.0, 1e-2);
    CHECK(k1 <= 1.0 + 1e-9); /* MinRad >= 1 */
    CHECK(a.sym.verdict == TR_SYM_D3);
    CHECK(a.nplateaus == 6);
    char *txt = NULL;
    tr_report_ctx ctx = {"trefoil_2400", 0, 1.0, NULL, 0};
    CHECK_OK(tr_report_text(&a, &ctx, &txt));
    CHECK(txt && strstr(txt, "m = 1 (the paper's window of arclength 0.001632 at e = 0.01364"));
    free(txt);
    tr_analysis_free(&a);

    /* the old default, now only when asked for: the peak drawn down */
    tr_analysis_opts o10 = {.m = 10};
    CHECK_OK(tr_analyze_component(c.x, n, NULL, 0, &o10, &a, &err));
    CHECK(a.m == 10 && !a.m_default);
    CHECK(max_kappa(&a) < 0.95);
    CHECK_OK(tr_report_text(&a, &ctx, &txt));
    CHECK(txt && strstr(txt, "m = 10 (given;"));
    free(txt);
    tr_analysis_free(&a);
    tr_curve_free(&c);
    return tr_test_finish("test_analysis_default_m");
}
