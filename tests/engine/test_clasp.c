/* The simple clasp (docs/physics.md 6) tightened by the whole engine, polish
 * included, from `tightrope make clasp` at 60 vertices per rope, with no
 * time limit (the run stops when it jams, so the result does not depend on
 * the machine's speed). Checked against the physics, not our own numbers:
 *  - converged: the KKT certificate (kkt.h, computed on the curve alone)
 *    below 1e-3 (a clasp the engine alone leaves sits near 0.74);
 *  - the end vertices are still on their planes z = +-H;
 *  - thickness 1: MinRad >= 1 and struts >= 2 to 1e-8;
 *  - both ropes congruent and each symmetric about its tip: the discrete
 *    curvature profiles agree to 1e-2 (the problem's symmetry, [P]);
 *  - the shoulder S has curvature 1/2 (it runs on a circle of radius 2
 *    around the other rope's tip, docs/physics.md 6.2): its first four
 *    vertices average to 1/2 within 0.02;
 *  - nowhere more bent than the limit, and most bent at the tip (the kink
 *    K; its curvature reaches 1 only from ~100 vertices per rope on,
 *    bench/notes/2026-11-23-simple-clasp-polish.md). */
#include <math.h>
#include <stdio.h>

#include "engine/engine.h"
#include "curve/generate.h"
#include "oracle/kkt.h"
#include "rope_curvature.h"
#include "testlib.h"
#include "oracle/thickness.h"
#include "util/vec3.h"

#define NPER 60
#define HEIGHT 5.0

static void test_clasp(void)
{
    tr_error err;
    tr_curve s, f;
    REQUIRE_OK(tr_make_clasp(&s, NPER, HEIGHT, &err));
    tr_engine *e;
    REQUIRE_OK(tr_engine_create(&e, &s, "reference", NULL, &err));
    tr_engine_limits lim = {.residual = 1e-4, .max_steps = 50000};
    tr_stop_reason why;
    CHECK_OK(tr_engine_run(e, &lim, &why, &err));
    tr_engine_progress p;
    tr_engine_get_progress(e, &p);
    CHECK(p.polished == 1);
    int got = tr_engine_get_curve(e, &f, &err);
    tr_engine_destroy(e);
    if (got) {
        tr_curve_free(&s);
        REQUIRE_OK(got);
    }

    tr_kkt k;
    CHECK_OK(tr_kkt_certify(&f, NULL, &k, &err));
    tr_thickness th;
    CHECK_OK(tr_thickness_measure(&f, NULL, &th, NULL, &err));
    printf("clasp %d per rope: %ld steps, ropelength %.9f, KKT residual %.3e (%zu/%zu struts)\n", NPER, p.steps,
           th.ropelength, k.residual, k.strut_active, k.strut_rows);
    CHECK(k.residual < 1e-3);
    CHECK(th.minrad >= 1.0 - 1e-8 && th.dcsd >= 2.0 * (1.0 - 1e-8));
    double worst_plane = 0.0;
    for (size_t i = 0; i < f.nv; i++)
        if (f.vcst && f.vcst[i] >= 0)
            worst_plane = fmax(worst_plane, tr_constraint_violation(&f.cst[f.vcst[i]], f.x + 3 * i));
    CHECK(f.ncst > 0 && worst_plane < 1e-12);

    double ka[NPER - 2], kb[NPER - 2];
    rope_curvature(&f, 0, ka);
    rope_curvature(&f, 1, kb);
    double dab = 0.0, drev = 0.0, kmax = 0.0;
    size_t imax = 0;
    for (size_t i = 0; i < NPER - 2; i++) {
        dab = fmax(dab, fabs(ka[i] - kb[i]));
        drev = fmax(drev, fabs(ka[i] - ka[NPER - 3 - i]));
        if (ka[i] > kmax) {
            kmax = ka[i];
            imax = i;
        }
    }
    printf("congruence %.2e, symmetry %.2e, max curvature %.6f at interior vertex %zu of %d\n", dab, drev, kmax,
           imax + 1, NPER);
    CHECK(dab < 1e-2 && drev < 1e-2);
    CHECK(kmax <= 1.0 + 1e-6);
    CHECK(imax + 1 == NPER / 2 - 1 || imax + 1 == NPER / 2); /* the tip */
    size_t i0 = 0;
    while (i0 < NPER - 2 && ka[i0] < 0.4)
        i0++;
    CHECK(i0 + 4 < NPER / 2);
    if (i0 + 4 < NPER / 2) {
        double sh = 0.25 * (ka[i0] + ka[i0 + 1] + ka[i0 + 2] + ka[i0 + 3]);
        printf("shoulder curvature %.4f (vertices %zu..%zu)\n", sh, i0 + 1, i0 + 4);
        CHECK_NEAR(sh, 0.5, 0.02);
    }
    tr_curve_free(&f);
    tr_curve_free(&s);
}

int main(void)
{
    test_clasp();
    return tr_test_failures ? 1 : 0;
}
