/* bench/vertex_contacts: a closed polygon measured as SP-FEM measures it
 * (Przybyl & Pieranski: contact beams join vertices, REFERENCE.md 1.2-1.4),
 * for comparing with the paper's lengths, which are not Rawdon's.
 *   vertex_contacts FILE
 * FILE: one closed component, any format tightrope reads (a plain "x y z"
 * list included). Prints
 *   N, K = ceil(pi / e) (pairs closer along the chain are excluded, e = L / N),
 *   L_p and Rawdon's MinRad (the thickness oracle's), the edges' spread,
 *   the least distance between vertices >= K apart (all pairs, brute force:
 *   independent of the solver's lists and searches; O(N^2), seconds at 1e5),
 *   and L_p / min(MinRad, dmin / 2), the length at vertex thickness 1.
 * `tightrope measure` gives the same curve's Rawdon ropelength (the least
 * *segment* distance), which is larger wherever edges dip between vertices.
 * Exit 2 on bad input. */
#include <math.h>
#include <stdio.h>

#include "curve/curve_io.h"
#include "oracle/thickness.h"
#include "util/vec3.h"

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
    /* L_p and MinRad as `measure` has them; only the contacts are SP-FEM's */
    tr_thickness rawdon;
    if (tr_thickness_measure(&c, NULL, &rawdon, NULL, &err)) {
        fprintf(stderr, "vertex_contacts: %s: %s\n", argv[1], err.msg);
        tr_curve_free(&c);
        return 2;
    }
    const double *x = c.x;
    double sum = rawdon.length, minrad = rawdon.minrad, emin = INFINITY, emax = 0.0;
    for (size_t i = 0; i < n; i++) {
        double le = sqrt(v3_dist2(x + 3 * ((i + 1) % n), x + 3 * i));
        emin = fmin(emin, le);
        emax = fmax(emax, le);
    }
    size_t K = (size_t)ceil(M_PI / (sum / (double)n));
    double d2min = INFINITY;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + K; j < n && n - (j - i) >= K; j++)
            d2min = fmin(d2min, v3_dist2(x + 3 * i, x + 3 * j));
    double dmin = sqrt(d2min), th = fmin(minrad, 0.5 * dmin);
    printf("N %zu K %zu L_p %.10f edge spread %.2e MinRad %.12f vertex dmin %.12f vertex ropelength %.10f\n", n, K,
           sum, emax - emin, minrad, dmin, sum / th);
    tr_curve_free(&c);
    return 0;
}
