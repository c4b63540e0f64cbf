/* This file contains arclength bookkeeping on one closed polygon: cumulative lengths and the
 * point at an arclength (polyline.h). */
#include "curve/polyline.h"


#include "util/compensated_sum.h"
#include "util/vec3.h"

void tr_polyline_arclength(const double *x, size_t n, double *s)
{
    tr_csum sum = {0.0, 0.0};
    s[0] = 0.0;
    for (size_t i = 0; i < n; i++) {
        tr_csum_add(&sum, sqrt(v3_dist2(x + 3 * i, x + 3 * ((i + 1) % n))));
        s[i + 1] = tr_csum_value(&sum);
    }
}

void tr_polyline_point_at(const double *x, size_t n, const double *s, double l, double *p)
{
    double L = s[n];
    double t = tr_wrap(l, L);
    /* largest i with s[i] <= t */
    size_t lo = 0, hi = n;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (s[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    double e = s[lo + 1] - s[lo];
    double f = e > 0 ? (t - s[lo]) / e : 0.0;
    const double *a = x + 3 * lo, *b = x + 3 * ((lo + 1) % n);
    for (int d = 0; d < 3; d++)
        p[d] = a[d] + f * (b[d] - a[d]);
}
