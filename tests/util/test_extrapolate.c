/* This file contains the tests of the extrapolation fitter
 * (util/extrapolate.h) on synthetic ladders with a known limit: exact data
 * give the limit to rounding, noisy data give it within the error bar the
 * fitter reports, a missing 1/N^4 term shows as the model error, and an
 * unconverged point shows in chi^2 and the leave-one-out. */
#include <math.h>
#include <stdint.h>

#include "testlib.h"
#include "util/extrapolate.h"

#define LINF 32.7429345
#define C2 915.0

/* splitmix64 -> standard normal (Box-Muller): deterministic noise */
static uint64_t rng_state = 12345;
static double uniform01(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) / 9007199254740992.0;
}
static double gauss(void)
{
    return sqrt(-2.0 * log(uniform01())) * cos(6.283185307179586 * uniform01());
}

static const double ladder[] = {2400, 4800, 9600, 19200};
static const int pw246[3] = {2, 4, 6};

static void exact_data(void)
{
    double n[4], l[4], s[4];
    for (int i = 0; i < 4; i++) {
        n[i] = ladder[i];
        l[i] = LINF + C2 / (n[i] * n[i]);
        s[i] = 1e-9;
    }
    tr_extrap_report r;
    CHECK_OK(tr_extrap_report_make(n, l, s, 4, pw246, 3, &r));
    CHECK(r.selected == 0);
    CHECK_NEAR(r.linf, LINF, 1e-12);
    CHECK_NEAR(r.fit[0].coef[1], C2, 1e-4);
    CHECK(r.fit[0].chi2 < 1e-6);
    CHECK(r.nfits == 3 && r.model_checked);
    CHECK_NEAR(r.fit[1].coef[0], LINF, 1e-12);
    CHECK(r.model_err < 1e-12);
    /* a bar of 1e-9 on each point: L_inf = (4 L(19200) - L(9600)) / 3 at
     * best, so its error is of the order of the points' */
    CHECK(r.fit[0].sigma[0] > 5e-10 && r.fit[0].sigma[0] < 2e-9);
    CHECK(r.total_err < 3e-9);
    /* two points: determined, no leave-one-out, no next power */
    tr_extrap_report r2;
    CHECK_OK(tr_extrap_report_make(n + 2, l + 2, s + 2, 2, pw246, 3, &r2));
    CHECK_NEAR(r2.linf, LINF, 1e-12);
    CHECK(r2.nfits == 1 && !r2.model_checked && r2.loo_worst == -1);
    /* one point: undetermined */
    CHECK(tr_extrap_report_make(n, l, s, 1, pw246, 3, &r2) != 0);
}

/* The two-point closed form: L_inf = (N2^2 L2 - N1^2 L1) / (N2^2 - N1^2) for
 * any data, and its error sqrt(N2^4 s2^2 + N1^4 s1^2) / (N2^2 - N1^2). */
static void two_point_closed_form(void)
{
    double n[2] = {3000, 7000}, l[2] = {32.8, 32.75}, s[2] = {2e-7, 5e-7};
    tr_extrap_fit f;
    int pw[1] = {2};
    CHECK_OK(tr_extrap_fit_powers(n, l, s, NULL, 2, pw, 1, &f));
    double a = n[0] * n[0], b = n[1] * n[1];
    CHECK_NEAR(f.coef[0], (b * l[1] - a * l[0]) / (b - a), 1e-11);
    CHECK_NEAR(f.sigma[0], sqrt(b * b * s[1] * s[1] + a * a * s[0] * s[0]) / (b - a), 1e-15);
    CHECK(f.dof == 0);
}

/* Noisy ladders with a 1/N^4 term: over 200 draws the selected fit's
 * reported total error covers the truth at least as often as a standard
 * error should (the model error is part of it), and the fit with 1/N^4 is
 * unbiased. */
static void noisy_coverage(void)
{
    const double d4 = -3.0e8; /* 1/N^4 term: -9e-6 at 2400, -2.2e-9 at 19200 */
    const double nn[6] = {1200, 2400, 4800, 9600, 19200, 38400};
    double sig[6] = {3e-8, 5e-8, 1e-7, 2e-7, 4e-7, 8e-7};
    int inside1 = 0, inside2 = 0, draws = 200;
    double mean_next = 0.0;
    for (int t = 0; t < draws; t++) {
        double n[6], l[6];
        for (int i = 0; i < 6; i++) {
            n[i] = nn[i];
            l[i] = LINF + C2 / (n[i] * n[i]) + d4 / pow(n[i], 4) + sig[i] * gauss();
        }
        tr_extrap_report r;
        CHECK_OK(tr_extrap_report_make(n, l, sig, 6, pw246, 3, &r));
        if (fabs(r.linf - LINF) < r.total_err)
            inside1++;
        if (fabs(r.linf - LINF) < 2.0 * r.total_err)
            inside2++;
        mean_next += r.fit[1].coef[0];
    }
    mean_next /= draws;
    /* one standard error covers 68 %, two 95 %: allow for the model error
     * making the bar conservative, and for sampling (200 draws) */
    CHECK(inside1 >= 120);
    CHECK(inside2 >= 180);
    CHECK_NEAR(mean_next, LINF, 3e-7);
}

/* The missing term: data with a large 1/N^4 part leave c/N^2 alone with a
 * large chi^2 and a model error that covers its bias; the data ask for the
 * second power, and that fit finds the limit. */
static void model_error(void)
{
    double n[4], l[4], s[4];
    for (int i = 0; i < 4; i++) {
        n[i] = ladder[i] / 4; /* 600 .. 4800, where 1/N^4 matters */
        l[i] = LINF + C2 / (n[i] * n[i]) + 5e7 / pow(n[i], 4);
        s[i] = 1e-9;
    }
    tr_extrap_report r;
    CHECK_OK(tr_extrap_report_make(n, l, s, 4, pw246, 3, &r));
    CHECK(r.fit[0].birge > 10.0);
    CHECK(r.selected == 1);
    CHECK_NEAR(r.linf, LINF, 1e-11);
    CHECK(r.total_err < 1e-8);
    /* c/N^2 alone, as the first fit of a two-power report: its model error
     * covers its bias */
    tr_extrap_report r1;
    int pw24[2] = {2, 4};
    CHECK_OK(tr_extrap_report_make(n, l, s, 4, pw24, 2, &r1));
    CHECK(r1.selected == 1);
    CHECK(fabs(r.fit[0].coef[0] - LINF) > 1e-7);
    CHECK(fabs(r1.fit[1].coef[0] - r1.fit[0].coef[0]) > 0.9 * fabs(r.fit[0].coef[0] - LINF));
}

/* An unconverged point (the N = 19 200 run 8e-6 above its converged value,
 * its own bar claiming 1e-7): chi^2 says the bars are wrong, the error is
 * scaled up, and the leave-one-out names that point. */
static void unconverged_point(void)
{
    double n[5], l[5], s[5];
    const double nn[5] = {1200, 2400, 4800, 9600, 19200};
    for (int i = 0; i < 5; i++) {
        n[i] = nn[i];
        l[i] = LINF + C2 / (n[i] * n[i]);
        s[i] = 1e-7;
    }
    l[4] += 8e-6;
    tr_extrap_report r;
    CHECK_OK(tr_extrap_report_make(n, l, s, 5, pw246, 1, &r));
    CHECK(r.fit[0].birge > 10.0);
    CHECK(r.loo_worst == 4);
    CHECK(r.total_err > 2e-6); /* the bars alone would say 5.5e-8 */
    CHECK(fabs(r.linf - LINF) <= 2.0 * r.total_err);
    CHECK(r.loo_max - r.loo_min > 1e-6);
}

static void bad_input(void)
{
    double n[3] = {1000, 2000, 4000}, l[3] = {1, 1, 1}, s[3] = {1e-9, 0.0, 1e-9};
    tr_extrap_fit f;
    int pw[1] = {2};
    CHECK(tr_extrap_fit_powers(n, l, s, NULL, 3, pw, 1, &f) != 0); /* s = 0 */
    s[1] = 1e-9;
    n[1] = n[0] = 1000;
    double n2[2] = {1000, 1000};
    CHECK(tr_extrap_fit_powers(n2, l, s, NULL, 2, pw, 1, &f) != 0); /* one N twice: singular */
}

int main(void)
{
    exact_data();
    two_point_closed_form();
    noisy_coverage();
    model_error();
    unconverged_point();
    bad_input();
    return tr_test_finish("test_extrapolate");
}
