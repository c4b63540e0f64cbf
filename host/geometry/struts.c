/* This file contains the exclusion gap and the strut gradient (struts.h). */
#include "geometry/struts.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

int tr_exclusion_gap(double radius, double ebar)
{
    if (!(ebar > 0))
        return 2;
    double g = ceil(M_PI * radius / ebar);
    return g < 2.0 ? 2 : (g > 1e9 ? 1000000000 : (int)g);
}

void tr_strut_gradient(const double c[3], double s, double t, double d, double scale,
                       double g[4][3])
{
    for (int k = 0; k < 3; k++) {
        double n = scale * c[k] / d;
        g[0][k] = (1.0 - s) * n;
        g[1][k] = s * n;
        g[2][k] = -(1.0 - t) * n;
        g[3][k] = -t * n;
    }
}
