/* Contact functions and the fixed points of their ninth power on a map with
 * known answers: sigma(l) = h(l) + L/9 with h(l) = l + a L/(18 pi) sin(18 pi l/L).
 * h commutes with the shift by L/9, so sigma^9 = h^9 (mod L), whose fixed
 * points are those of h: l = j L/18, j = 0..17, with (sigma^9)' = (1 +- a)^9
 * (h' = 1 + a cos(j pi) along the whole orbit l + k L/9). Even j form one
 * unstable 9-cycle, odd j one stable 9-cycle: the structure the paper finds
 * for the tight trefoil. */
#include <math.h>
#include <stdlib.h>

#include "analysis/contact_functions.h"
#include "curve/polyline.h"
#include "testlib.h"

#define PI 3.14159265358979323846

static const double L = 32.7429345, A = 0.3;

static double sigma(double l) { return l + L / 9.0 + A * L / (18.0 * PI) * sin(18.0 * PI * l / L); }

static void check_fixed_points(const tr_contact_fn *f, double tol)
{
    tr_error err;
    tr_fixed_point *fp;
    tr_cycle *cy;
    size_t nfp, ncy;
    CHECK_OK(tr_power_fixed_points(f, 9, 20000, &fp, &nfp, &cy, &ncy, &err));
    CHECK(nfp == 18);
    CHECK(ncy == 2);
    int nstable = 0;
    for (size_t i = 0; i < nfp && nfp == 18; i++) {
        double j = fp[i].l / (L / 18.0);
        CHECK_NEAR(fp[i].l, round(j) * L / 18.0, tol);
        int odd = ((long)round(j)) % 2 != 0;
        CHECK(fp[i].stable == odd);
        nstable += fp[i].stable;
        double want = pow(odd ? 1.0 - A : 1.0 + A, 9);
        CHECK_NEAR(fp[i].slope, want, 0.02 * want);
    }
    CHECK(nstable == 9);
    for (size_t c = 0; c < ncy && ncy == 2; c++) {
        CHECK(cy[c].period == 9);
        CHECK(cy[c].stable == 0 || cy[c].stable == 1);
        /* listed in the order of successive sigma actions: member with order
         * k sits at first + k L/9 */
        for (size_t i = 0; i < nfp; i++)
            if (fp[i].cycle == (int)c) {
                double want = fp[cy[c].first].l + fp[i].order * L / 9.0;
                CHECK_NEAR(fmod(want, L), fp[i].l, 2 * tol);
            }
    }
    free(fp);
    free(cy);
}

int main(void)
{
    tr_error err;
    /* The map itself, sampled densely. */
    size_t n = 9000;
    double *l = malloc(n * sizeof *l), *u = malloc(n * sizeof *u);
    for (size_t k = 0; k < n; k++) {
        l[k] = (k + 0.25) * L / n;
        u[k] = sigma(l[k]);
    }
    tr_contact_fn f;
    CHECK_OK(tr_contact_fn_from_samples(l, u, n, L, &f, &err));
    /* Linear interpolation error: (L/n)^2/8 * max|sigma''| = (L/n)^2/8 * A (18 pi/L) ~ 4e-6 */
    double emax = 0.0;
    for (int k = 0; k < 1000; k++) {
        double x = (k + 0.37) * L / 1000.0;
        emax = fmax(emax, fabs(tr_contact_fn_lift(&f, x) - sigma(x)));
    }
    CHECK(emax < 1e-5);
    CHECK_NEAR(tr_contact_fn_lift(&f, 3.0 * L + 1.0), sigma(1.0) + 3.0 * L, 1e-5);
    check_fixed_points(&f, 1e-9 * L);
    tr_contact_fn_free(&f);

    /* Isotonic regression removes a dip: a non-monotone sample is pooled. */
    double ls[4] = {0.0, 1.0, 2.0, 3.0}, us[4] = {5.0, 7.0, 6.0, 8.0};
    CHECK_OK(tr_contact_fn_from_samples(ls, us, 4, 10.0, &f, &err));
    CHECK_NEAR(f.u[1], 6.5, 1e-15);
    CHECK_NEAR(f.u[2], 6.5, 1e-15);
    tr_contact_fn_free(&f);

    /* A synthetic contact set: struts (l, sigma(l)) at scattered l. Each
     * point then has partners sigma(l) (forward offset ~ L/9) and
     * sigma^-1(l) (offset ~ 8L/9): sigma- must come out as sigma and sigma+
     * as its inverse. */
    size_t np = 6000;
    tr_contact_pair *p = malloc(np * sizeof *p);
    for (size_t k = 0; k < np; k++) {
        double x = fmod((double)k * 0.6180339887498949 * L, L); /* golden-ratio scatter */
        p[k] = (tr_contact_pair){x, fmod(sigma(x), L), 2.0};
    }
    tr_contact_fn m, pl;
    CHECK_OK(tr_contact_functions_build(p, np, L, L / 1500.0, &m, &pl, &err));
    double e1 = 0.0, e2 = 0.0, e3 = 0.0;
    for (int k = 0; k < 997; k++) {
        double x = (k + 0.5) * L / 997.0;
        e1 = fmax(e1, fabs(tr_contact_fn_lift(&m, x) - sigma(x)));
        e2 = fmax(e2, fabs(tr_wrap_signed(tr_contact_fn_eval(&pl, tr_contact_fn_eval(&m, x)) - x, L)));
        e3 = fmax(e3, fabs(tr_wrap_signed(tr_contact_fn_eval(&m, tr_contact_fn_eval(&pl, x)) - x, L)));
    }
    /* Bin averages over L/1500 with slope up to 1.3: errors ~ (bin)^2 A (18pi/L) ~ 1e-4 */
    CHECK(e1 < 1e-3);
    CHECK(e2 < 2e-3);
    CHECK(e3 < 2e-3);
    check_fixed_points(&m, 2e-3);
    tr_contact_fn_free(&m);
    tr_contact_fn_free(&pl);
    free(p);
    free(l);
    free(u);
    return tr_test_finish("test_analysis_contacts");
}
