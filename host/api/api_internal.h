/* What the public API's files share (include/tightrope/tightrope.h is the
 * interface): the curve handle is a tr_curve, and every failure reaches
 * the caller's tightrope_error through one function. */
#ifndef TR_API_INTERNAL_H
#define TR_API_INTERNAL_H

#include "curve/curve.h"
#include "tightrope/tightrope.h"
#include "util/error.h"

struct tightrope_curve {
    tr_curve c;
};

/* Copies the internal error's status and message into the caller's
 * (which may be NULL) and returns the status. */
int tr_api_fail(tightrope_error *out, int status, const tr_error *err);

/* A handle taking over c (its arrays move into the handle; c is left
 * empty). TIGHTROPE_ENOMEM frees c. */
int tr_api_wrap(tr_curve *c, tightrope_curve **out, tightrope_error *err);

#endif
