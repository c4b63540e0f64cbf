/* This file contains the test helpers: failure counting, reports, near-equality and data paths
 * (testlib.h). */
#include "testlib.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int tr_test_failures = 0;

void tr_test_report(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
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
    printf("skipped, no reference data at %s: %s\n", TR_SHARED_DIR, what);
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
