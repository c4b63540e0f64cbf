/* The simple clasp (docs/physics.md 6) through the second-order solver
 * (solver/newton.h), which holds its end vertices on their planes by
 * eliminating the motions the planes forbid. The start is what the route
 * gives the solver: a 2 x 50 clasp tightened by the engine (first-order
 * steps and polish, no time limit, so the result does not depend on the
 * machine's speed), refined to 2 x 100 by the engine's low-pass refinement
 * (so pressed a little through itself, and not scalable: the planes stay).
 * Checked against the physics and the independent oracles, not against our
 * own numbers:
 *  - accepted, and the end vertices on their planes z = +-H to rounding;
 *  - thickness 1 (MinRad >= 1, struts >= 2) to the solver's 1e-6, by the
 *    thickness oracle;
 *  - critical: the KKT certificate (kkt.h, the `measure --kkt` code path,
 *    computed on the curve alone) below 1e-3;
 *  - the published anatomy (REFERENCE.md 6.2): the kink K at the tip has
 *    curvature 1 (the curvature limit, reached at this resolution, as the
 *    first-order route reaches it at 2 x 100:
 *    bench/notes/2026-11-23-simple-clasp-polish.md), and the
 *    shoulder S, on a circle of radius 2 about the other rope's tip,
 *    curvature 1/2 (the mean of four vertices: the polygon zigzags about it
 *    with period 2);
 *  - each rope symmetric about its tip (the problem's symmetry). */
#include <math.h>
#include <stdio.h>

#include "curve/generate.h"
#include "engine/engine.h"
#include "engine/refine_lowpass.h"
#include "oracle/kkt.h"
#include "oracle/thickness.h"
#include "solver/newton.h"
#include "rope_curvature.h"
#include "clasp_route.h"
#include "testlib.h"
#include "util/vec3.h"

#define NCOARSE 50
#define NPER 100
#define HEIGHT 5.0

static void test_clasp_newton(void)
{
    tr_error err;
    tr_curve coarse, f;
    REQUIRE_OK(clasp_first_order(NCOARSE, HEIGHT, &coarse, &err));
    REQUIRE_OK(tr_refine_lowpass(&coarse, NPER, 0.5, 0.5, &f, &err));
    tr_curve_free(&coarse);

    tr_newton_stats st;
    CHECK_OK(tr_newton(&f, NULL, &st, &err));
    printf("solver: %s%s, ropelength %.9f -> %.9f in %d steps, %.2f s\n", st.accepted ? "accepted" : "rejected",
           st.converged ? " converged" : (st.settled ? " settled" : ""), st.ropelength_before, st.ropelength_after,
           st.iters, st.seconds);
    CHECK(!st.skipped && st.accepted);
    CHECK(st.converged || st.settled);

    double worst_plane = 0.0;
    for (size_t i = 0; i < f.nv; i++)
        if (f.vcst && f.vcst[i] >= 0)
            worst_plane = fmax(worst_plane, tr_constraint_violation(&f.cst[f.vcst[i]], f.x + 3 * i));
    printf("ends off their planes by %.1e\n", worst_plane);
    CHECK(f.ncst == 2 && worst_plane <= 1e-12);

    tr_thickness th;
    CHECK_OK(tr_thickness_measure(&f, NULL, &th, NULL, &err));
    tr_kkt k;
    CHECK_OK(tr_kkt_certify(&f, NULL, &k, &err));
    printf("clasp %d per rope: ropelength %.9f, MinRad %.9f, dcsd %.9f, KKT residual %.3e (%zu/%zu struts)\n", NPER,
           th.ropelength, th.minrad, th.dcsd, k.residual, k.strut_active, k.strut_rows);
    CHECK(th.minrad >= 1.0 - 1e-6 && th.dcsd >= 2.0 * (1.0 - 1e-6));
    CHECK(k.residual < 1e-3);

    for (int r = 0; r < 2; r++) {
        double ka[NPER - 2], kmax = 0.0, drev = 0.0;
        rope_curvature(&f, r, ka);
        size_t imax = 0;
        for (size_t i = 0; i < NPER - 2; i++) {
            drev = fmax(drev, fabs(ka[i] - ka[NPER - 3 - i]));
            if (ka[i] > kmax) {
                kmax = ka[i];
                imax = i;
            }
        }
        size_t i0 = 0;
        while (i0 < NPER - 2 && ka[i0] < 0.4)
            i0++;
        double sh = i0 + 4 < NPER / 2 ? 0.25 * (ka[i0] + ka[i0 + 1] + ka[i0 + 2] + ka[i0 + 3]) : NAN;
        printf("rope %d: kink %.6f at interior vertex %zu, shoulder %.4f (vertices %zu..%zu), symmetry %.1e\n", r, kmax,
               imax + 1, sh, i0 + 1, i0 + 4, drev);
        CHECK_NEAR(kmax, 1.0, 1e-6);
        CHECK(imax + 1 == NPER / 2 - 1 || imax + 1 == NPER / 2); /* the tip */
        CHECK_NEAR(sh, 0.5, 0.02);
        CHECK(drev < 1e-2);
    }
    tr_curve_free(&f);
}

int main(void)
{
    test_clasp_newton();
    return tr_test_failures ? 1 : 0;
}
