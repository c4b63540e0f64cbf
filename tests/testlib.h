/* Minimal test helpers: checks that count failures and print where they were,
 * norm-wise comparison with an explicit finiteness check, and paths to data. */
#ifndef TR_TESTLIB_H
#define TR_TESTLIB_H

#include <stddef.h>

extern int tr_test_failures;

#define TR_SKIP 77

#define CHECK(cond)                                                                    \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            tr_test_report(__FILE__, __LINE__, "check failed: %s", #cond);             \
        }                                                                              \
    } while (0)

/* |got - want| <= tol, and both finite (NaN passes naive comparisons). */
#define CHECK_NEAR(got, want, tol)                                                     \
    do {                                                                               \
        double g_ = (got), w_ = (want), t_ = (tol);                                    \
        if (!tr_test_near(g_, w_, t_)) {                                               \
            tr_test_report(__FILE__, __LINE__, "%s = %.17g, want %.17g +- %.3g", #got, \
                           g_, w_, t_);                                                \
        }                                                                              \
    } while (0)

#define CHECK_OK(expr)                                                                 \
    do {                                                                               \
        int rc_ = (expr);                                                              \
        if (rc_ != 0) {                                                                \
            tr_test_report(__FILE__, __LINE__, "%s returned %d", #expr, rc_);          \
        }                                                                              \
    } while (0)

/* CHECK_OK for a step the rest of a void test function needs (a file read): on
 * failure the function returns instead of running on an uninitialised value. */
#define REQUIRE_OK(expr)                                                               \
    do {                                                                               \
        int rc_ = (expr);                                                              \
        if (rc_ != 0) {                                                                \
            tr_test_report(__FILE__, __LINE__, "%s returned %d (test stops)", #expr, rc_); \
            return;                                                                    \
        }                                                                              \
    } while (0)

/* A failed check: counted (tr_test_failures) and printed with where it was. */
void tr_test_report(const char *file, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
int tr_test_near(double got, double want, double tol);

/* Norm-wise: max|got-want| <= rtol*max|want| + atol, every element finite. */
int tr_test_allclose(const double *got, const double *want, size_t n, double rtol, double atol,
                     double *maxdiff);

/* Prints "N passed, N failed"-style summary for this executable and returns its exit code. */
int tr_test_finish(const char *name);

/* 1 when the reference data (TR_SHARED_DIR/data, the project's ../shared)
 * is there; else prints that it is not, naming `what`, and returns 0. The
 * tests that use it fall back to the repository's own few files of it
 * (tests/data): every test runs on a clone of the repository alone. */
int tr_have_shared(const char *what);

/* 1 when TIGHTROPE_TEST_SMALL is set (and not "0"): the OpenCL tests then
 * run fewer and smaller cases, for a simulator that runs every work-item
 * one by one (Oclgrind, scripts/test.sh --oclgrind); the same code paths,
 * multi-group launches included, are kept. */
int tr_test_small(void);

/* Announces on stdout an OpenCL error that the test provokes on purpose,
 * named as Oclgrind's --check-api names it ("clFinish",
 * "CL_INVALID_COMMAND_QUEUE"): scripts/oclgrind_run.sh accepts exactly the
 * announced reports, as many as announced, and fails on any other. */
void tr_test_expect_cl_error(const char *function, const char *error);

/* Gauss linking number of two closed polygons (n0 and n1 vertices, 3 n
 * coordinates each), exactly, as a sum of the signed solid angles of
 * segment pairs (Klenin & Langowski 2000, eq. 15): a knot invariant the
 * engine does not compute, for checking that a link stayed the same. */
double tr_test_linking_number(const double *x0, size_t n0, const double *x1, size_t n1);

/* Writes "dir/name" into buf; dir is TR_SHARED_DIR or TR_SOURCE_DIR. */
const char *tr_shared_path(char *buf, size_t n, const char *rel);
const char *tr_source_path(char *buf, size_t n, const char *rel);

#endif
