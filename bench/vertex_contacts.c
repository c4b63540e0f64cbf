/* bench/vertex_contacts: a closed polygon measured as SP-FEM measures it
 * (Przybyl & Pieranski: contact beams join vertices, REFERENCE.md 1.2-1.4),
 * for comparing with the paper's lengths, which are not Rawdon's.
 *   vertex_contacts FILE
 * FILE: one closed component, any format tightrope reads (a plain "x y z"
 * list included). Prints
 *   N, K = ceil(pi / e) (pairs closer along the chain are excluded, e = L / N),
 *   L_p (compensated sum), the edges' spread, Rawdon's MinRad,
 *   the least distance between vertices >= K apart (all pairs, brute force:
 *   independent of the solver's lists and searches; O(N^2), seconds at 1e5),
 *   and L_p / min(MinRad, dmin / 2), the length at vertex thickness 1.
 * `tightrope measure` gives the same curve's Rawdon ropelength (the least
 * *segment* distance), which is larger wherever edges dip between vertices.
 * Exit 2 on bad input. */
#include <math.h>
#include <stdio.h>

#include "curve/curve_io.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: vertex_contacts FILE\n");
        return 2;
    }
    tr_curve c;
    tr_error err;
    if (tr_curve_read(argv[1], TR_FORMAT_AUTO, &c, &err)) {
        fprintf(stderr, "vertex_contacts: %s\n", err.msg);
        return 2;
    }
    size_t n = c.nv;
    if (c.ncomp != 1 || !c.closed[0] || n < 4) {
        fprintf(stderr, "vertex_contacts: %s: one closed component of at least 4 vertices wanted\n", argv[1]);
        tr_curve_free(&c);
        return 2;
    }
    const double *x = c.x;
    /* Kahan: a sum of 2e5 edges of 1.6e-4 would lose the 1e-10 digits */
    double sum = 0.0, comp = 0.0, emin = INFINITY, emax = 0.0, minrad = INFINITY;
    for (size_t i = 0; i < n; i++) {
        size_t j = (i + 1) % n, h = (i + n - 1) % n;
        double e[3], p[3];
        for (int k = 0; k < 3; k++) {
            e[k] = x[3 * j + k] - x[3 * i + k];
            p[k] = x[3 * i + k] - x[3 * h + k];
        }
        double le = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        double lp = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        double yk = le - comp, t = sum + yk;
        comp = (t - sum) - yk;
        sum = t;
        emin = fmin(emin, le);
        emax = fmax(emax, le);
        double cr[3] = {p[1] * e[2] - p[2] * e[1], p[2] * e[0] - p[0] * e[2], p[0] * e[1] - p[1] * e[0]};
        double th = atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), p[0] * e[0] + p[1] * e[1] + p[2] * e[2]);
        minrad = fmin(minrad, fmin(le, lp) / (2.0 * tan(0.5 * th)));
    }
    size_t K = (size_t)ceil(M_PI / (sum / (double)n));
    double d2min = INFINITY;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + K; j < n && n - (j - i) >= K; j++) {
            double dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1], dz = x[3 * i + 2] - x[3 * j + 2];
            d2min = fmin(d2min, dx * dx + dy * dy + dz * dz);
        }
    double dmin = sqrt(d2min), th = fmin(minrad, 0.5 * dmin);
    printf("N %zu K %zu L_p %.10f edge spread %.2e MinRad %.12f vertex dmin %.12f vertex ropelength %.10f\n", n, K,
           sum, emax - emin, minrad, dmin, sum / th);
    tr_curve_free(&c);
    return 0;
}
