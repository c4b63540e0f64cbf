/* L-BFGS on closed-form problems: the Rosenbrock function (minimiser
 * (1, 1), f = 0) and the extended Rosenbrock function in 20 variables
 * (minimiser all ones), from the standard start (-1.2, 1); a strictly
 * convex quadratic with known minimiser; the per-group step cap is obeyed
 * on every iteration. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "util/lbfgs.h"
#include "testlib.h"

/* sum over pairs of 100 (x_{2k+1} - x_{2k}^2)^2 + (1 - x_{2k})^2 */
static double rosenbrock(void *ctx, const double *x, double *g)
{
    size_t n = *(const size_t *)ctx;
    double f = 0.0;
    for (size_t k = 0; k + 1 < n; k += 2) {
        double a = x[k + 1] - x[k] * x[k], b = 1.0 - x[k];
        f += 100.0 * a * a + b * b;
        g[k] = -400.0 * a * x[k] - 2.0 * b;
        g[k + 1] = 200.0 * a;
    }
    return f;
}

typedef struct cap_ctx {
    size_t n;
    double prev[6];
    double worst;
} cap_ctx;

/* f = sum_i (i+1) (x_i - i)^2, minimiser x_i = i */
static double quadratic(void *ctx, const double *x, double *g)
{
    cap_ctx *c = ctx;
    double f = 0.0;
    for (size_t i = 0; i < c->n; i++) {
        double d = x[i] - (double)i;
        f += (double)(i + 1) * d * d;
        g[i] = 2.0 * (double)(i + 1) * d;
    }
    return f;
}

static int watch_steps(void *ctx, const double *x, double f, const double *g, int it)
{
    (void)f;
    (void)g;
    (void)it;
    cap_ctx *c = ctx;
    for (size_t k = 0; k < c->n; k += 3) {
        double s = 0.0;
        for (int a = 0; a < 3; a++)
            s += (x[k + a] - c->prev[k + a]) * (x[k + a] - c->prev[k + a]);
        if (sqrt(s) > c->worst)
            c->worst = sqrt(s);
    }
    memcpy(c->prev, x, c->n * sizeof *x);
    return 0;
}

int main(void)
{
    tr_error err;
    tr_lbfgs_params p;
    tr_lbfgs_result r;
    for (size_t n = 2; n <= 20; n += 18) {
        double x[20];
        for (size_t k = 0; k < n; k += 2) {
            x[k] = -1.2;
            x[k + 1] = 1.0;
        }
        tr_lbfgs_params_default(&p);
        p.gtol = 1e-10;
        p.max_iter = 2000;
        CHECK_OK(tr_lbfgs_minimize(n, x, &p, rosenbrock, NULL, &n, &r, &err));
        printf("rosenbrock n=%zu: %d iterations, %d evaluations, f %.3g, reason %d\n", n, r.iters, r.evals, r.f,
               (int)r.reason);
        CHECK(r.reason == TR_LBFGS_GTOL || r.reason == TR_LBFGS_LINE_SEARCH);
        for (size_t k = 0; k < n; k++)
            CHECK_NEAR(x[k], 1.0, 1e-7);
        CHECK(r.f < 1e-14);
    }
    /* the step cap: no vertex (group of 3) moves further than max_move */
    cap_ctx c = {.n = 6};
    double x[6] = {0};
    tr_lbfgs_params_default(&p);
    p.group = 3;
    p.max_move = 0.25;
    p.gtol = 1e-10;
    CHECK_OK(tr_lbfgs_minimize(6, x, &p, quadratic, watch_steps, &c, &r, &err));
    printf("capped quadratic: %d iterations, largest vertex step %.6f\n", r.iters, c.worst);
    for (size_t i = 0; i < 6; i++)
        CHECK_NEAR(x[i], (double)i, 1e-9);
    CHECK(c.worst <= 0.25 * (1.0 + 1e-12));
    CHECK(r.iters >= 5 / 0.25 / 2); /* the far vertex is ~7.1 away: the cap was binding */
    return tr_test_finish("test_lbfgs");
}
