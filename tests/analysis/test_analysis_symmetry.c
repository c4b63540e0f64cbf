/* Symmetry detection on shapes whose symmetry is known exactly: the torus
 * knot T(2,3) in its standard embedding (D3), a rigidly moved copy (same
 * verdict, same origin up to the symmetry), perturbations that keep only a
 * twofold axis (C2) or nothing (none); the representative-interval map on the
 * paper's 9-cycle (docs/physics.md 4.4). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/arc_profile.h"
#include "curve/polyline.h"
#include "analysis/rotation_fit.h"
#include "analysis/symmetry.h"
#include "testlib.h"

#define PI 3.14159265358979323846

/* (2 + cos 3t) cos 2t, (2 + cos 3t) sin 2t, sin 3t at t = 2 pi i/n, plus
 * eps_even * cos t on x (keeps t -> -t, i.e. the twofold axis x, breaks C3)
 * and eps_odd * sin t on x (breaks both). */
static double *trefoil(size_t n, double eps_even, double eps_odd)
{
    double *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * PI * (double)i / (double)n;
        x[3 * i] = (2.0 + cos(3 * t)) * cos(2 * t) + eps_even * cos(t) + eps_odd * sin(t);
        x[3 * i + 1] = (2.0 + cos(3 * t)) * sin(2 * t);
        x[3 * i + 2] = sin(3 * t);
    }
    return x;
}

static double uniform(uint64_t *st)
{
    *st = *st * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*st >> 11) / 9007199254740992.0;
}

static void analyse(const double *x, size_t n, tr_symmetry *s)
{
    tr_error err;
    tr_arc_profile p;
    CHECK_OK(tr_symmetry_find(x, n, NULL, s, &err));
    CHECK_OK(tr_arc_profile_compute(x, n, NULL, 0.0, &p, &err));
    tr_symmetry_choose_origin(s, &p);
    tr_arc_profile_free(&p);
}

static void test_torus_knot(void)
{
    size_t n = 300;
    double *x = trefoil(n, 0.0, 0.0);
    tr_symmetry s;
    analyse(x, n, &s);
    CHECK(s.verdict == TR_SYM_D3);
    /* The sampled polygon is exactly symmetric: residuals are rounding
     * (coordinates ~3, 1e-16 each, times the golden-section tolerance). */
    CHECK(s.c3.rms < 1e-10 * s.rg);
    CHECK(s.n_twofold == 6);
    CHECK(s.twofold_rms_max < 1e-9 * s.rg);
    CHECK_NEAR(fabs(s.c3.axis[2]), 1.0, 1e-12);
    CHECK_NEAR(s.c3.angle, 2.0 * PI / 3.0, 1e-12);
    /* Twofold points at t = k pi/3, i.e. arclength k L/6 (the knot's six parts
     * are congruent), axes in the xy plane. */
    double *sl = malloc((n + 1) * sizeof *sl);
    tr_polyline_arclength(x, n, sl);
    double L = sl[n];
    for (size_t i = 0; i < s.n_twofold; i++) {
        CHECK_NEAR(s.twofold[i].l, sl[i * n / 6], 1e-9);
        CHECK_NEAR(s.twofold[i].axis[2], 0.0, 1e-9);
    }
    CHECK(!isnan(s.origin));
    double o1 = s.origin;
    /* The origin rule picks the class of twofold points that is bent more
     * sharply; from the smooth curve's derivatives, kappa(0) = |(0,6,3) x
     * (-21,0,0)| / 45^1.5 = 0.467 at the outer points (t = 0, 2pi/3, ...) and
     * |(-sqrt3,-1,-3) x (-2.5, 2.5 sqrt3, 0)| / 13^1.5 = 0.385 at the inner
     * ones: even k. */
    double kout = sqrt(63.0 * 63.0 + 126.0 * 126.0) / pow(45.0, 1.5);
    double c1 = 7.5 * sqrt(3.0), c2 = 7.5, c3 = -2.5 * sqrt(3.0) * sqrt(3.0) - 2.5;
    double kin = sqrt(c1 * c1 + c2 * c2 + c3 * c3) / pow(13.0, 1.5);
    CHECK(kout > kin);
    double k6 = o1 / (L / 6.0);
    CHECK_NEAR(k6, round(k6), 1e-9);
    CHECK(((long)round(k6)) % 2 == 0);

    /* Random rigid motion (fixed seed). */
    uint64_t st = 12345;
    double ax[3] = {uniform(&st) - 0.5, uniform(&st) - 0.5, uniform(&st) - 0.5};
    double an = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    for (int d = 0; d < 3; d++)
        ax[d] /= an;
    double R[3][3], T[3] = {3.7, -1.2, 8.9};
    tr_rotation_matrix(ax, 2.0 * PI * uniform(&st), R);
    double *y = malloc(3 * n * sizeof *y);
    for (size_t i = 0; i < n; i++)
        for (int r = 0; r < 3; r++)
            y[3 * i + r] = R[r][0] * x[3 * i] + R[r][1] * x[3 * i + 1] + R[r][2] * x[3 * i + 2] + T[r];
    tr_symmetry sy;
    analyse(y, n, &sy);
    CHECK(sy.verdict == TR_SYM_D3);
    CHECK(sy.c3.rms < 1e-10 * sy.rg);
    CHECK(sy.n_twofold == 6);
    double rot_axis[3] = {R[0][2], R[1][2], R[2][2]}; /* image of z */
    CHECK_NEAR(fabs(rot_axis[0] * sy.c3.axis[0] + rot_axis[1] * sy.c3.axis[1] +
                    rot_axis[2] * sy.c3.axis[2]),
               1.0, 1e-10);
    /* Same origin up to the threefold symmetry (l -> l + L/3). */
    double shift = fmod(fabs(sy.origin - o1) + 1e-9, L / 3.0);
    CHECK(shift < 1e-8);
    free(y);

    /* Twofold axis only. */
    double *z = trefoil(n, 0.05, 0.0);
    tr_symmetry sz;
    analyse(z, n, &sz);
    CHECK(sz.verdict == TR_SYM_C2);
    CHECK(!sz.has_c3);
    CHECK(sz.c3.rms > 10.0 * sz.tol * sz.rg);
    free(z);
    /* Nothing. */
    double *w = trefoil(n, 0.0, 0.05);
    tr_symmetry sw;
    analyse(w, n, &sw);
    CHECK(sw.verdict == TR_SYM_NONE);
    CHECK(sw.n_twofold == 0);
    CHECK(sw.c3.rms > 10.0 * sw.tol * sw.rg);
    CHECK(sw.twofold_rms_best > 10.0 * sw.tol * sw.rg);
    free(w);
    free(sl);
    free(x);
}

static void test_reduce(void)
{
    /* docs/physics.md 4.4: with L = 32.7429345 the paper's C9- reduces to the
     * three classes {0.189, 0.373, 4.759}. */
    double L = 32.7429345;
    const double c9[9] = {0.189, 15.674, 32.370, 11.103, 26.588, 10.541, 22.018, 4.759, 21.455};
    const double want[9] = {0.189, 4.7597, 0.3729, 0.1887, 4.7594, 0.3733, 0.1894, 4.759, 0.3736};
    for (int i = 0; i < 9; i++)
        CHECK_NEAR(tr_symmetry_reduce(c9[i], L, NULL), want[i], 1e-4);
    int k;
    CHECK_NEAR(tr_symmetry_reduce(4.0 * L / 6.0 - 16.7467 + 4.0 * L / 6.0, L, &k), 4.0 * L / 6.0 - 16.7467, 1e-12);
    CHECK_NEAR(tr_symmetry_reduce(-0.1, L, &k), 0.1, 1e-12);
    CHECK(k == 5);
}

int main(void)
{
    test_torus_knot();
    test_reduce();
    return tr_test_finish("test_analysis_symmetry");
}
