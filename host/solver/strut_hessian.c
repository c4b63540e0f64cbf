/* This file contains the exact strut distance's gradient and Hessian
 * (strut_hessian.h has the derivation; the body is kernels/segment_distance.h
 * tr_strut_row_derivs, which the backends' strut rows share). */
#include "solver/strut_hessian.h"

#include <stddef.h>

#include "segment_distance.h"

double tr_strut_distance_derivs(const double *p0, const double *p1, const double *q0, const double *q1,
                                double *g, double *h)
{
    double x[12];
    for (int c = 0; c < 3; c++) {
        x[c] = p0[c];
        x[3 + c] = p1[c];
        x[6 + c] = q0[c];
        x[9 + c] = q1[c];
    }
    return tr_strut_row_derivs(x, g, h, g != NULL, h != NULL);
}
