/* This file contains the seeded smooth perturbation of a start curve
 * (perturb.h). */
#include "curve/perturb.h"

#include <math.h>
#include <stdlib.h>

#include "curve/polyline.h"
#include "util/splitmix64.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* uniform in [-1, 1] */
static double uniform(uint64_t *state)
{
    return (double)(tr_splitmix64(state) >> 11) * 0x1.0p-52 - 1.0;
}

int tr_curve_perturb(tr_curve *c, double amplitude, uint64_t seed, tr_error *err)
{
    if (!(amplitude >= 0.0) || !isfinite(amplitude))
        return tr_fail(err, TR_EINVAL, "perturbation amplitude %g", amplitude);
    tr_curve_drop_lo(c); /* the vertices move in doubles */
    uint64_t state = seed;
    for (int k = 0; k < c->ncomp; k++) {
        if (!c->closed[k])
            continue;
        size_t n = tr_comp_nv(c, k);
        double *x = c->x + 3 * c->start[k];
        double *s = malloc((n + 1) * sizeof *s), *d = malloc(3 * n * sizeof *d);
        if (!s || !d) {
            free(s);
            free(d);
            return tr_fail(err, TR_ENOMEM, "out of memory (perturbation)");
        }
        tr_polyline_arclength(x, n, s);
        double len = s[n], dmax = 0.0;
        double a[TR_PERTURB_MODES][2][3];
        for (int m = 0; m < TR_PERTURB_MODES; m++)
            for (int q = 0; q < 2; q++)
                for (int r = 0; r < 3; r++)
                    a[m][q][r] = uniform(&state) / (double)(m + 1);
        for (size_t i = 0; i < n; i++) {
            double t = 2.0 * M_PI * s[i] / len;
            for (int r = 0; r < 3; r++) {
                double v = 0.0;
                for (int m = 0; m < TR_PERTURB_MODES; m++)
                    v += a[m][0][r] * cos((m + 1) * t) + a[m][1][r] * sin((m + 1) * t);
                d[3 * i + (size_t)r] = v;
            }
            dmax = fmax(dmax, sqrt(d[3 * i] * d[3 * i] + d[3 * i + 1] * d[3 * i + 1] + d[3 * i + 2] * d[3 * i + 2]));
        }
        double f = dmax > 0.0 ? amplitude / dmax : 0.0;
        for (size_t i = 0; i < 3 * n; i++)
            x[i] += f * d[i];
        free(s);
        free(d);
    }
    return TR_OK;
}
