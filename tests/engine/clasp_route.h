/* The clasp tests' coarse start (test_clasp_newton.c, test_clasp_prolong.c):
 * a simple clasp tightened by the engine's first-order route alone. */
#ifndef TR_TEST_CLASP_ROUTE_H
#define TR_TEST_CLASP_ROUTE_H

#include "curve/generate.h"
#include "engine/engine.h"

/* A clasp of n vertices a rope, ends on the planes z = +-h, tightened by
 * first-order steps and polish with no time limit (so the result does not
 * depend on the machine's speed), into *out; the first failure's status. */
static inline int clasp_first_order(size_t n, double h, tr_curve *out, tr_error *err)
{
    tr_curve s;
    int rc = tr_make_clasp(&s, n, h, err);
    if (rc)
        return rc;
    tr_engine *e;
    tr_engine_params ep;
    tr_engine_params_default(&ep);
    ep.newton_tight = 0; /* the coarse start by the first-order route alone */
    rc = tr_engine_create(&e, &s, "reference", &ep, err);
    tr_curve_free(&s);
    if (rc)
        return rc;
    tr_engine_limits lim = {.residual = 1e-4, .max_steps = 50000};
    tr_stop_reason why;
    rc = tr_engine_run(e, &lim, &why, err);
    if (rc == TR_OK)
        rc = tr_engine_get_curve(e, out, err);
    tr_engine_destroy(e);
    return rc;
}

#endif
