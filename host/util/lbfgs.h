/* Limited-memory BFGS (Nocedal & Wright, Numerical Optimization, alg. 7.4
 * and 7.5): two-loop recursion and a weak-Wolfe bisection line search
 * (Lewis & Overton). Written here rather than taken from liblbfgs because
 * the polish stage (polish.h) needs a per-vertex cap on every step: no group
 * of `group` consecutive variables (a vertex, group = 3) may move further
 * than max_move in one iteration, which is what keeps strands from jumping
 * through each other between accepted iterates. */
#ifndef TR_LBFGS_H
#define TR_LBFGS_H

#include <stddef.h>

#include "util/error.h"

/* Returns f(x) and writes its gradient into g (n entries). */
typedef double (*tr_lbfgs_fn)(void *ctx, const double *x, double *g);
/* Called after every accepted iterate; a non-zero return stops the run
 * (the iterate is kept). */
typedef int (*tr_lbfgs_iter_fn)(void *ctx, const double *x, double f, const double *g, int iter);

typedef struct tr_lbfgs_params {
    int m;           /* stored pairs (e.g. 10) */
    int max_iter;    /* iterations */
    double gtol;     /* stop when max |g_i| <= gtol */
    double ftol;     /* stop when the decrease of f over an iteration <= ftol (1 + |f|) */
    double max_move; /* cap on the norm of every group of the step (INFINITY: none) */
    int group;       /* group size for max_move (>= 1) */
    int max_ls;      /* function evaluations per line search */
} tr_lbfgs_params;

void tr_lbfgs_params_default(tr_lbfgs_params *p);

typedef enum tr_lbfgs_reason {
    TR_LBFGS_GTOL = 1,
    TR_LBFGS_FTOL,
    TR_LBFGS_MAX_ITER,
    TR_LBFGS_STOPPED,     /* the iteration callback asked */
    TR_LBFGS_LINE_SEARCH  /* no step decreased f: at a minimum to rounding */
} tr_lbfgs_reason;

typedef struct tr_lbfgs_result {
    int iters, evals;
    double f;
    double gmax;
    tr_lbfgs_reason reason;
} tr_lbfgs_result;

/* Minimises from x (overwritten with the last accepted iterate). iter may be NULL. */
int tr_lbfgs_minimize(size_t n, double *x, const tr_lbfgs_params *p, tr_lbfgs_fn fn, tr_lbfgs_iter_fn iter,
                      void *ctx, tr_lbfgs_result *out, tr_error *err);

#endif
