/* This file contains the best rotation taking one point set onto another, Horn's quaternion form
 * (rotation_fit.h). */
#include "analysis/rotation_fit.h"

#include <math.h>
#include <string.h>

#include "util/vec3.h"

/* Cyclic Jacobi for a symmetric 4x4 matrix: A is destroyed (diagonal left
 * with the eigenvalues), V receives the eigenvectors as columns. */
static void jacobi4(double A[4][4], double V[4][4])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            V[i][j] = i == j;
    for (int sweep = 0; sweep < 60; sweep++) {
        double off = 0.0, diag = 0.0;
        for (int i = 0; i < 4; i++) {
            diag += A[i][i] * A[i][i];
            for (int j = i + 1; j < 4; j++)
                off += A[i][j] * A[i][j];
        }
        if (off <= 1e-32 * diag || off == 0.0)
            break;
        for (int p = 0; p < 4; p++)
            for (int q = p + 1; q < 4; q++) {
                if (A[p][q] == 0.0)
                    continue;
                double th = (A[q][q] - A[p][p]) / (2.0 * A[p][q]);
                double t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
                double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < 4; k++) {
                    double akp = A[k][p], akq = A[k][q];
                    A[k][p] = c * akp - s * akq;
                    A[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 4; k++) {
                    double apk = A[p][k], aqk = A[q][k];
                    A[p][k] = c * apk - s * aqk;
                    A[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 4; k++) {
                    double vkp = V[k][p], vkq = V[k][q];
                    V[k][p] = c * vkp - s * vkq;
                    V[k][q] = s * vkp + c * vkq;
                }
            }
    }
}

void tr_rotation_matrix(const double *u, double a, double R[3][3])
{
    double c = cos(a), s = sin(a), C = 1.0 - c;
    R[0][0] = c + u[0] * u[0] * C;
    R[0][1] = u[0] * u[1] * C - u[2] * s;
    R[0][2] = u[0] * u[2] * C + u[1] * s;
    R[1][0] = u[1] * u[0] * C + u[2] * s;
    R[1][1] = c + u[1] * u[1] * C;
    R[1][2] = u[1] * u[2] * C - u[0] * s;
    R[2][0] = u[2] * u[0] * C - u[1] * s;
    R[2][1] = u[2] * u[1] * C + u[0] * s;
    R[2][2] = c + u[2] * u[2] * C;
}

int tr_rotation_fit(const double *a, const double *b, size_t n, const double *c, tr_rotation *out)
{
    memset(out, 0, sizeof *out);
    if (n == 0)
        return -1;
    double S[3][3] = {{0}};
    for (size_t i = 0; i < n; i++) {
        double p[3], q[3];
        v3_sub(p, a + 3 * i, c);
        v3_sub(q, b + 3 * i, c);
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < 3; k++)
                S[r][k] += p[r] * q[k];
    }
    double N[4][4] = {
        {S[0][0] + S[1][1] + S[2][2], S[1][2] - S[2][1], S[2][0] - S[0][2], S[0][1] - S[1][0]},
        {S[1][2] - S[2][1], S[0][0] - S[1][1] - S[2][2], S[0][1] + S[1][0], S[2][0] + S[0][2]},
        {S[2][0] - S[0][2], S[0][1] + S[1][0], -S[0][0] + S[1][1] - S[2][2], S[1][2] + S[2][1]},
        {S[0][1] - S[1][0], S[2][0] + S[0][2], S[1][2] + S[2][1], -S[0][0] - S[1][1] + S[2][2]}};
    double V[4][4];
    jacobi4(N, V);
    int best = 0;
    for (int k = 1; k < 4; k++)
        if (N[k][k] > N[best][best])
            best = k;
    double q[4] = {V[0][best], V[1][best], V[2][best], V[3][best]};
    double qn = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; k++)
        q[k] /= qn;
    if (q[0] < 0)
        for (int k = 0; k < 4; k++)
            q[k] = -q[k];
    double vn = sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    out->angle = 2.0 * atan2(vn, q[0]);
    if (vn > 0) {
        out->axis[0] = q[1] / vn, out->axis[1] = q[2] / vn, out->axis[2] = q[3] / vn;
    } else {
        out->axis[2] = 1.0;
    }
    tr_rotation_matrix(out->axis, out->angle, out->R);
    double ss = 0.0;
    for (size_t i = 0; i < n; i++) {
        double p[3], q3[3], r[3];
        v3_sub(p, a + 3 * i, c);
        v3_sub(q3, b + 3 * i, c);
        for (int k = 0; k < 3; k++)
            r[k] = out->R[k][0] * p[0] + out->R[k][1] * p[1] + out->R[k][2] * p[2] - q3[k];
        ss += v3_dot(r, r);
    }
    out->rms = sqrt(ss / (double)n);
    return 0;
}
