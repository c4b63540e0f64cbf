/* Out-of-range options of the shape analysis are refused with TR_EINVAL by
 * the library itself (not only by the command line), and the contact
 * functions stay exact at the finest bin they accept. A bin of 1e-300 once
 * turned into a bin count beyond size_t and a division by zero (SIGFPE).
 * The contact set is the one of test_analysis_contacts.c: struts (l,
 * sigma(l)) of the map sigma(l) = l + L/9 + a L/(18 pi) sin(18 pi l/L). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/contact_functions.h"
#include "curve/generate.h"
#include "analysis/portrait.h"
#include "curve/polyline.h"
#include "testlib.h"

#define PI 3.14159265358979323846

static const double L = 32.7429345, A = 0.3;

static double sigma(double l) { return l + L / 9.0 + A * L / (18.0 * PI) * sin(18.0 * PI * l / L); }

static void check_bin_refused(const tr_contact_pair *p, size_t np, double len, double bin)
{
    tr_error err;
    tr_contact_fn m, pl;
    CHECK(tr_contact_functions_build(p, np, len, bin, &m, &pl, &err) == TR_EINVAL);
    CHECK(m.l == NULL && pl.l == NULL);
}

int main(void)
{
    tr_error err;
    size_t np = 6000;
    tr_contact_pair *p = malloc(np * sizeof *p);
    for (size_t k = 0; k < np; k++) {
        double x = fmod((double)k * 0.6180339887498949 * L, L);
        p[k] = (tr_contact_pair){x, fmod(sigma(x), L), 2.0};
    }
    check_bin_refused(p, np, L, 1e-300);
    check_bin_refused(p, np, L, 0.0);
    check_bin_refused(p, np, L, -1.0);
    check_bin_refused(p, np, L, NAN);
    check_bin_refused(p, np, L, INFINITY);
    check_bin_refused(p, np, L, 0.99 * TR_CONTACT_BIN_MIN_REL * L);
    check_bin_refused(p, np, L, 1.01 * TR_CONTACT_BIN_MAX_REL * L);
    check_bin_refused(p, np, 0.0, 1.0);
    check_bin_refused(p, np, NAN, 1.0);
    check_bin_refused(p, np, INFINITY, 1.0);

    /* The finest accepted bin is refused as geometry, not as memory: the two
     * pixels of a strut, (l, sigma(l)) and (sigma(l), l), lie L apart in
     * t = l + partner (mod 2L), and no other pixel shares so fine a bin, so
     * no point shows two partners. Only occupied bins may be stored (2e7
     * bins of the former dense layout were ~1.6 GB). */
    tr_contact_fn m, pl;
    CHECK(tr_contact_functions_build(p, np, L, 1.0001 * TR_CONTACT_BIN_MIN_REL * L, &m, &pl, &err) ==
          TR_EGEOMETRY);
    /* A bin of L/20000 holds a pixel of each branch only ~2% of the time:
     * nearly every bin has one cluster and is given to the branch of the
     * nearest two-cluster bin (ahead or behind, around the circle). Every
     * sample lies exactly on its branch, so a wrong assignment would show as
     * an error of order L/9, while a right one leaves the interpolation
     * error (L/6000)^2/8 * a (18 pi/L) ~ 6e-6; sigma+ is then the exact
     * inverse at the same samples. */
    CHECK_OK(tr_contact_functions_build(p, np, L, L / 20000.0, &m, &pl, &err));
    double e1 = 0.0, e2 = 0.0;
    for (int k = 0; k < 997; k++) {
        double x = (k + 0.5) * L / 997.0;
        e1 = fmax(e1, fabs(tr_contact_fn_lift(&m, x) - sigma(x)));
        e2 = fmax(e2, fabs(tr_wrap_signed(tr_contact_fn_eval(&pl, tr_contact_fn_eval(&m, x)) - x, L)));
    }
    CHECK(e1 < 3e-5);
    CHECK(e2 < 1e-6);

    /* Functional powers outside [1, TR_CONTACT_POWER_MAX], too small a grid. */
    tr_fixed_point *fp;
    tr_cycle *cy;
    size_t nfp, ncy;
    CHECK(tr_power_fixed_points(&m, 0, 20000, &fp, &nfp, &cy, &ncy, &err) == TR_EINVAL);
    CHECK(tr_power_fixed_points(&m, -9, 20000, &fp, &nfp, &cy, &ncy, &err) == TR_EINVAL);
    CHECK(tr_power_fixed_points(&m, TR_CONTACT_POWER_MAX + 1, 20000, &fp, &nfp, &cy, &ncy, &err) ==
          TR_EINVAL);
    CHECK(tr_power_fixed_points(&m, 9, 7, &fp, &nfp, &cy, &ncy, &err) == TR_EINVAL);
    CHECK(fp == NULL && cy == NULL && nfp == 0 && ncy == 0);
    /* sigma^9 = h^9 has the 18 fixed points j L/18 (test_analysis_contacts.c) */
    CHECK_OK(tr_power_fixed_points(&m, 9, 20000, &fp, &nfp, &cy, &ncy, &err));
    CHECK(nfp == 18);
    free(fp), free(cy);
    tr_contact_fn_free(&m);
    tr_contact_fn_free(&pl);

    /* The whole analysis refuses the same values (and a plateau level <= 0). */
    tr_curve c;
    CHECK_OK(tr_make_torus(&c, 2, 3, 200, &err));
    tr_analysis a;
    tr_analysis_opts bad[] = {
        {.contact_bin = 1e-300},
        {.contact_bin = 1e300},
        {.power = TR_CONTACT_POWER_MAX + 1},
        {.power = -1},
        {.plateau_eps = 1.0},
        {.plateau_min = 201},
        {.m = 51}, /* fewer than 4 averaged vertices */
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        int rc = tr_analyze_component(c.x, c.nv, NULL, 0, &bad[i], &a, &err);
        if (rc != TR_EINVAL)
            fprintf(stderr, "options case %zu: status %d, want TR_EINVAL\n", i, rc);
        CHECK(rc == TR_EINVAL);
        if (rc == TR_OK)
            tr_analysis_free(&a);
    }
    tr_analysis_opts good = {.contact_bin = 0.01, .power = TR_CONTACT_POWER_MAX, .plateau_min = 200};
    CHECK_OK(tr_analyze_component(c.x, c.nv, NULL, 0, &good, &a, &err));
    tr_analysis_free(&a);
    tr_curve_free(&c);
    free(p);
    return tr_test_finish("test_analysis_options");
}
