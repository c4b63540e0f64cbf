/* A curve's low parts (curve.h lo): a fine regular polygon whose vertices
 * are computed in long double is measured by the oracle against its closed
 * forms (MinRad R cos(pi / N), length 2 N R sin(pi / N)) to the accuracy
 * the low parts carry, where its vertices rounded to doubles are off by
 * their rounding over l0^2; a file written with them reads back the same
 * vertices; a file of 17-digit numbers has none. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/curve.h"
#include "curve/curve_io.h"
#include "oracle/thickness.h"
#include "testlib.h"

/* 2^18 vertices on a circle of radius 3: edges 7.2e-5, so a vertex rounded
 * to doubles (2.2e-16 at R) moves its turning angle by ~4e-8 of itself */
#define N_FINE ((size_t)1 << 18)
#define RADIUS 3.0L

static const long double PI_L = 3.141592653589793238462643383279502884L;

/* the N-gon of radius R about (cx, 0, 0), in long double, split into the
 * curve's x and lo (or rounded to x alone: with_lo 0) */
static void put_ngon(tr_curve *c, long double cx, int with_lo)
{
    size_t n = c->nv;
    for (size_t i = 0; i < n; i++) {
        long double a = 2.0L * PI_L * (long double)i / (long double)n;
        long double v[3] = {cx + RADIUS * cosl(a), RADIUS * sinl(a), 0.0L};
        for (int d = 0; d < 3; d++) {
            if (with_lo)
                tr_split_long_double(v[d], &c->x[3 * i + (size_t)d], &c->lo[3 * i + (size_t)d]);
            else
                c->x[3 * i + (size_t)d] = (double)v[d];
        }
    }
}

static double minrad_exact(void) { return (double)(RADIUS * cosl(PI_L / (long double)N_FINE)); }
static double length_exact(void) { return (double)(2.0L * (long double)N_FINE * RADIUS * sinl(PI_L / (long double)N_FINE)); }

static void test_oracle_uses_low_parts(long double cx)
{
    if (LDBL_MANT_DIG <= DBL_MANT_DIG) {
        printf("long double is no wider than double here: nothing to test\n");
        return;
    }
    size_t n = N_FINE;
    tr_curve with, without;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&with, 1, &n, NULL, &err));
    REQUIRE_OK(tr_curve_want_lo(&with, &err));
    REQUIRE_OK(tr_curve_alloc(&without, 1, &n, NULL, &err));
    put_ngon(&with, cx, 1);
    put_ngon(&without, cx, 0);
    tr_thickness tw, to;
    CHECK_OK(tr_thickness_measure(&with, NULL, &tw, NULL, &err));
    CHECK_OK(tr_thickness_measure(&without, NULL, &to, NULL, &err));
    double mr = minrad_exact(), len = length_exact();
    printf("centre %.1Lf: MinRad with low parts %.3e off, rounded to doubles %.3e off; length %.3e, %.3e\n", cx,
           fabs(tw.minrad / mr - 1.0), fabs(to.minrad / mr - 1.0), fabs(tw.length / len - 1.0),
           fabs(to.length / len - 1.0));
    /* long double vertices: 5e-20 R over l0^2 = 5.2e-9 is 3e-11 */
    CHECK_NEAR(tw.minrad / mr, 1.0, 2e-9);
    CHECK_NEAR(tw.length / len, 1.0, 1e-13);
    /* the same polygon in doubles: its worst vertex of 2^18 is off by
     * several times 4e-8; so the low parts are what the first check saw */
    CHECK(fabs(to.minrad / mr - 1.0) > 2e-8);
    tr_curve_free(&with);
    tr_curve_free(&without);
}

static void test_files_keep_low_parts(void)
{
    size_t n = 4096;
    tr_curve c, back, plain;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    REQUIRE_OK(tr_curve_want_lo(&c, &err));
    put_ngon(&c, 0.0L, 1);
    int some = 0;
    for (size_t q = 0; q < 3 * n; q++)
        some |= c.lo[q] != 0.0;
    CHECK(some || LDBL_MANT_DIG <= DBL_MANT_DIG);
    const tr_format fmts[] = {TR_FORMAT_VECT, TR_FORMAT_TSV, TR_FORMAT_KNOTPLOT};
    for (size_t f = 0; f < sizeof fmts / sizeof *fmts; f++) {
        char *text = NULL;
        size_t len = 0;
        REQUIRE_OK(tr_curve_format(&c, fmts[f], "low parts", &text, &len, &err));
        REQUIRE_OK(tr_curve_parse("lo.txt", text, len, fmts[f], &back, &err));
        free(text);
        CHECK(back.nv == n);
        CHECK(back.lo != NULL || !some);
        size_t worse = 0;
        for (size_t q = 0; q < 3 * n && back.nv == n; q++) {
            long double a = (long double)c.x[q] + c.lo[q], b = (long double)back.x[q] + (back.lo ? back.lo[q] : 0.0);
            /* 21 digits hold a 64-bit long double exactly */
            /* (x may differ by a step where lo was half of one: the
             * decimal rounds to the other double, lo takes the rest) */
            worse += a != b;
        }
        CHECK(worse == 0);
        tr_curve_free(&back);
    }
    /* the same curve without its low parts: 17 digits, none read back */
    tr_curve_drop_lo(&c);
    char *text = NULL;
    size_t len = 0;
    REQUIRE_OK(tr_curve_format(&c, TR_FORMAT_VECT, NULL, &text, &len, &err));
    REQUIRE_OK(tr_curve_parse("plain.vect", text, len, TR_FORMAT_VECT, &plain, &err));
    free(text);
    CHECK(plain.lo == NULL);
    for (size_t q = 0; q < 3 * n && plain.nv == n; q++)
        CHECK(plain.x[q] == c.x[q]);
    tr_curve_free(&plain);
    tr_curve_free(&c);
}

/* Scaling carries the low parts: the scaled polygon's MinRad is the closed
 * form's times the factor, to the low parts' accuracy. */
static void test_scale_keeps_low_parts(void)
{
    if (LDBL_MANT_DIG <= DBL_MANT_DIG)
        return;
    size_t n = N_FINE;
    tr_curve c;
    tr_error err;
    REQUIRE_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    REQUIRE_OK(tr_curve_want_lo(&c, &err));
    put_ngon(&c, 0.0L, 1);
    const double f = 1.0 / 2.9999999;
    tr_curve_scale_by(&c, f);
    tr_thickness t;
    CHECK_OK(tr_thickness_measure(&c, NULL, &t, NULL, &err));
    CHECK_NEAR(t.minrad / (minrad_exact() * f), 1.0, 2e-9);
    tr_curve_free(&c);
}

int main(void)
{
    test_oracle_uses_low_parts(0.0L);
    /* off the origin: the oracle's frame moves the curve, its rounding
     * into the low parts */
    test_oracle_uses_low_parts(5.0L);
    test_files_keep_low_parts();
    test_scale_keeps_low_parts();
    return tr_test_finish("test_low_parts");
}
