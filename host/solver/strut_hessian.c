/* This file contains the exact strut distance's gradient and Hessian
 * (strut_hessian.h has the derivation). */
#include "solver/strut_hessian.h"

#include <math.h>
#include <string.h>

#include "segment_distance.h"

/* Interior test for a closest-point parameter: away from the clamp by more
 * than rounding. */
#define PARAM_EPS 1e-12
/* (nearly) parallel: sin^2 of the angle below this, as segment_distance.h decides */
#define PARALLEL_SIN2 1e-10

double tr_strut_distance_derivs(const double *p0, const double *p1, const double *q0, const double *q1,
                                double *g, double *h)
{
    double s, t;
    double d = tr_segment_distance(p0, p1, q0, q1, &s, &t);
    if (!g && !h)
        return d;
    double d1[3], d2[3], D[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = p1[k] - p0[k];
        d2[k] = q1[k] - q0[k];
        D[k] = p0[k] + s * d1[k] - q0[k] - t * d2[k];
    }
    /* weights of the four points in D */
    const double W[4] = {1.0 - s, s, -(1.0 - t), -t};
    /* grad F = 2 W_k D on point k */
    double gF[12];
    for (int k = 0; k < 4; k++)
        for (int c = 0; c < 3; c++)
            gF[3 * k + c] = 2.0 * W[k] * D[c];
    if (g)
        for (int i = 0; i < 12; i++)
            g[i] = gF[i] / (2.0 * d);
    if (!h)
        return d;
    /* phi_xx = 2 (W W^T) (x) I3 */
    double H[144];
    memset(H, 0, sizeof H);
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            for (int c = 0; c < 3; c++)
                H[(3 * a + c) * 12 + 3 * b + c] = 2.0 * W[a] * W[b];
    /* phi_xs = 2 (dW/ds)_k D + 2 W_k d1;  phi_xt = 2 (dW/dt)_k D - 2 W_k d2 */
    const double Ws[4] = {-1.0, 1.0, 0.0, 0.0}, Wt[4] = {0.0, 0.0, 1.0, -1.0};
    double gs[12], gt[12];
    for (int k = 0; k < 4; k++)
        for (int c = 0; c < 3; c++) {
            gs[3 * k + c] = 2.0 * (Ws[k] * D[c] + W[k] * d1[c]);
            gt[3 * k + c] = 2.0 * (Wt[k] * D[c] - W[k] * d2[c]);
        }
    double a11 = 2.0 * (d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]);
    double a22 = 2.0 * (d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2]);
    double a12 = -2.0 * (d1[0] * d2[0] + d1[1] * d2[1] + d1[2] * d2[2]);
    int fs = s > PARAM_EPS && s < 1.0 - PARAM_EPS;
    int ft = t > PARAM_EPS && t < 1.0 - PARAM_EPS;
    if (fs && ft && a11 * a22 - a12 * a12 <= PARALLEL_SIN2 * a11 * a22)
        ft = 0;
    double i11 = 0, i22 = 0, i12 = 0;
    if (fs && ft) {
        double det = a11 * a22 - a12 * a12;
        i11 = a22 / det;
        i22 = a11 / det;
        i12 = -a12 / det;
    } else if (fs)
        i11 = 1.0 / a11;
    else if (ft)
        i22 = 1.0 / a22;
    for (int i = 0; i < 12; i++)
        for (int j = 0; j < 12; j++)
            H[i * 12 + j] -= i11 * gs[i] * gs[j] + i22 * gt[i] * gt[j] + i12 * (gs[i] * gt[j] + gt[i] * gs[j]);
    /* d = sqrt(F) */
    for (int i = 0; i < 12; i++)
        for (int j = 0; j < 12; j++)
            h[i * 12 + j] = H[i * 12 + j] / (2.0 * d) - gF[i] * gF[j] / (4.0 * d * d * d);
    return d;
}
