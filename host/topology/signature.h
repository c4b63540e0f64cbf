/* The signature of a knot from a PD code, by Gordon and Litherland's
 * theorem (Invent. Math. 47 (1978) 53): colour the diagram's faces like a
 * chessboard; the Goeritz matrix G of the shaded faces (one struck out)
 * and the correction mu over the crossings of type II give
 *     sigma(K) = signature(G) - mu(D).
 * The faces come from the PD code's cyclic order at each crossing. Sign
 * convention: KnotInfo's (the positive trefoil, braid 1,1,1, has -2); the
 * mirror image has the opposite signature, so unlike the Alexander
 * polynomial it tells many knots from their mirror images. */
#ifndef TR_SIGNATURE_H
#define TR_SIGNATURE_H

#include "util/error.h"

/* The signature of the knot with PD code pd[0..n-1] (as alexander.h takes
 * it; n = 0 and n = 1 are the unknot, 0). TR_EINVAL for a code whose faces
 * do not make a plane diagram. */
int tr_signature_from_pd(const int (*pd)[4], int n, int *signature, tr_error *err);

#endif
