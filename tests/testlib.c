/* This file contains the test helpers: failure counting, reports, near-equality and data paths
 * (testlib.h). */
#include "testlib.h"

#include "util/vec3.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int tr_test_failures = 0;

void tr_test_report(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    tr_test_failures++;
    va_start(ap, fmt);
    fprintf(stderr, "%s:%d: ", file, line);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

int tr_test_near(double got, double want, double tol)
{
    return isfinite(got) && isfinite(want) && fabs(got - want) <= tol;
}

int tr_test_allclose(const double *got, const double *want, size_t n, double rtol, double atol,
                     double *maxdiff)
{
    double scale = 0.0, diff = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(got[i]) || !isfinite(want[i])) {
            if (maxdiff)
                *maxdiff = INFINITY;
            return 0;
        }
        if (fabs(want[i]) > scale)
            scale = fabs(want[i]);
        if (fabs(got[i] - want[i]) > diff)
            diff = fabs(got[i] - want[i]);
    }
    if (maxdiff)
        *maxdiff = diff;
    return diff <= rtol * scale + atol;
}

int tr_test_finish(const char *name)
{
    if (tr_test_failures) {
        fprintf(stderr, "%s: %d check(s) failed\n", name, tr_test_failures);
        return 1;
    }
    printf("%s: all checks passed\n", name);
    return 0;
}

int tr_have_shared(const char *what)
{
    char path[4096];
    FILE *f = fopen(tr_shared_path(path, sizeof path, "data/tightknot_ropelength.tsv"), "r");
    if (f) {
        fclose(f);
        return 1;
    }
    printf("no reference data at %s: %s\n", TR_SHARED_DIR, what);
    return 0;
}

const char *tr_shared_path(char *buf, size_t n, const char *rel)
{
    snprintf(buf, n, "%s/%s", TR_SHARED_DIR, rel);
    return buf;
}

const char *tr_source_path(char *buf, size_t n, const char *rel)
{
    snprintf(buf, n, "%s/%s", TR_SOURCE_DIR, rel);
    return buf;
}

int tr_test_small(void)
{
    const char *v = getenv("TIGHTROPE_TEST_SMALL");
    return v && *v && strcmp(v, "0") != 0;
}

void tr_test_expect_cl_error(const char *function, const char *error)
{
    printf("oclgrind-expect: %s %s\n", function, error);
    fflush(stdout);
}

double tr_test_linking_number(const double *x0, size_t n0, const double *x1, size_t n1)
{
    double sum = 0.0;
    for (size_t i = 0; i < n0; i++)
        for (size_t j = 0; j < n1; j++) {
            const double *p1 = x0 + 3 * i, *p2 = x0 + 3 * ((i + 1) % n0);
            const double *p3 = x1 + 3 * j, *p4 = x1 + 3 * ((j + 1) % n1);
            double r13[3], r14[3], r23[3], r24[3], r12[3], r34[3], n[4][3];
            v3_sub(r13, p3, p1);
            v3_sub(r14, p4, p1);
            v3_sub(r23, p3, p2);
            v3_sub(r24, p4, p2);
            v3_sub(r12, p2, p1);
            v3_sub(r34, p4, p3);
            v3_cross(n[0], r13, r14);
            v3_cross(n[1], r14, r24);
            v3_cross(n[2], r24, r23);
            v3_cross(n[3], r23, r13);
            double om = 0.0;
            int ok = 1;
            for (int k = 0; k < 4; k++) {
                double l = v3_norm(n[k]);
                if (l == 0.0)
                    ok = 0;
                else
                    v3_scale(n[k], 1.0 / l, n[k]);
            }
            if (!ok)
                continue;
            for (int k = 0; k < 4; k++) {
                double d = v3_dot(n[k], n[(k + 1) % 4]);
                om += asin(d > 1 ? 1 : (d < -1 ? -1 : d));
            }
            double cr[3];
            v3_cross(cr, r34, r12);
            sum += v3_dot(cr, r13) > 0 ? om : -om;
        }
    return sum / (4.0 * 3.14159265358979323846);
}
