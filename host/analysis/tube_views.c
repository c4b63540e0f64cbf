/* This file contains the choice of the tube pictures' cameras: the symmetry
 * axis or the principal axes of gyration (tube_views.h). */
#include "analysis/tube_views.h"

#include <math.h>
#include <string.h>

#include "util/vec3.h"

/* Eigenvectors of the symmetric 3x3 matrix A by cyclic Jacobi rotations:
 * on return the columns of V are unit eigenvectors, lam the eigenvalues,
 * sorted ascending. A 3x3 gyration tensor converges in a few sweeps. */
static void eigen3(double A[3][3], double V[3][3], double lam[3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            V[i][j] = i == j;
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = fabs(A[0][1]) + fabs(A[0][2]) + fabs(A[1][2]);
        if (off <= 1e-15 * (fabs(A[0][0]) + fabs(A[1][1]) + fabs(A[2][2])) || off == 0.0)
            break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                if (A[p][q] == 0.0)
                    continue;
                double th = 0.5 * (A[q][q] - A[p][p]) / A[p][q];
                double t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
                double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < 3; k++) { /* A <- A J */
                    double akp = A[k][p], akq = A[k][q];
                    A[k][p] = c * akp - s * akq, A[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) { /* A <- J^T A */
                    double apk = A[p][k], aqk = A[q][k];
                    A[p][k] = c * apk - s * aqk, A[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) {
                    double vkp = V[k][p], vkq = V[k][q];
                    V[k][p] = c * vkp - s * vkq, V[k][q] = s * vkp + c * vkq;
                }
            }
    }
    int idx[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (A[idx[j]][idx[j]] < A[idx[i]][idx[i]]) {
                int t = idx[i];
                idx[i] = idx[j], idx[j] = t;
            }
    double W[3][3];
    for (int j = 0; j < 3; j++) {
        lam[j] = A[idx[j]][idx[j]];
        for (int i = 0; i < 3; i++)
            W[i][j] = V[i][idx[j]];
    }
    memcpy(V, W, sizeof W);
}

/* u minus its part along unit t, made unit; 0 if too little is left. */
static int perpendicular(double *out, const double *u, const double *t)
{
    memcpy(out, u, 3 * sizeof *out);
    v3_axpy(out, -v3_dot(u, t), t);
    double l = v3_norm(out);
    if (!(l > 1e-6))
        return 0;
    v3_scale(out, 1.0 / l, out);
    return 1;
}

void tr_tube_views_choose(const double *x, size_t n, const tr_symmetry *sym, tr_tube_views *out)
{
    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < n; i++)
        v3_axpy(out->centre, 1.0 / (double)n, x + 3 * i);
    double A[3][3] = {{0}}, V[3][3], lam[3], ev[3][3];
    for (size_t i = 0; i < n; i++) {
        double d[3];
        v3_sub(d, x + 3 * i, out->centre);
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                A[a][b] += d[a] * d[b] / (double)n;
    }
    eigen3(A, V, lam);
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++)
            ev[j][i] = V[i][j]; /* ev[0]: thinnest direction, ev[2]: longest */

    /* Front: along the threefold axis; else along the thinnest direction
     * (a twofold axis of a knot without a threefold one mostly lies in its
     * plane: a torus knot seen along it is seen edge-on), called a twofold
     * axis when one lies within 10 degrees of it. */
    tr_view *f = &out->v[TR_VIEW_FRONT];
    int twofold = sym && sym->n_twofold > 0;
    if (sym && sym->has_c3) {
        memcpy(f->toward, sym->c3.axis, sizeof f->toward);
        out->front_axis = "the threefold axis";
    } else {
        memcpy(f->toward, ev[0], sizeof f->toward);
        out->front_axis = "the smallest principal axis";
        for (size_t i = 0; twofold && i < sym->n_twofold; i++)
            if (fabs(v3_dot(sym->twofold[i].axis, ev[0])) > cos(10.0 * 3.14159265358979323846 / 180.0)) {
                memcpy(f->toward, sym->twofold[i].axis, sizeof f->toward);
                out->front_axis = "a twofold axis";
                break;
            }
    }
    /* Up: a twofold axis across the front one (the picture shows the
     * symmetry upright), else the longest principal direction left. */
    int have_up = 0;
    for (size_t i = 0; twofold && i < sym->n_twofold && !have_up; i++)
        have_up = fabs(v3_dot(sym->twofold[i].axis, f->toward)) < 1e-3 &&
                  perpendicular(f->up, sym->twofold[i].axis, f->toward);
    for (int j = 2; j >= 0 && !have_up; j--)
        have_up = perpendicular(f->up, ev[j], f->toward);
    if (!have_up) { /* a degenerate tensor (all points on one line): any normal */
        double e[3] = {fabs(f->toward[0]) < 0.9, fabs(f->toward[0]) >= 0.9, 0.0};
        perpendicular(f->up, e, f->toward);
    }
    v3_cross(f->right, f->up, f->toward);

    /* Top: from above, the front view's viewer at the bottom of the image;
     * side: from the front view's right. Both stay right-handed. */
    tr_view *t = &out->v[TR_VIEW_TOP], *s = &out->v[TR_VIEW_SIDE];
    memcpy(t->toward, f->up, sizeof t->toward);
    v3_scale(t->up, -1.0, f->toward);
    memcpy(t->right, f->right, sizeof t->right);
    memcpy(s->toward, f->right, sizeof s->toward);
    memcpy(s->up, f->up, sizeof s->up);
    v3_scale(s->right, -1.0, f->toward);
}
