/* Small inline 3-vector helpers on double[3]; header-only so the compiler
 * inlines them into the hot loops of the oracle and the reference backend. */
#ifndef TR_VEC3_H
#define TR_VEC3_H

#include <math.h>

static inline double v3_dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void v3_sub(double *r, const double *a, const double *b)
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}
static inline void v3_add(double *r, const double *a, const double *b)
{
    r[0] = a[0] + b[0];
    r[1] = a[1] + b[1];
    r[2] = a[2] + b[2];
}
static inline void v3_scale(double *r, double s, const double *a)
{
    r[0] = s * a[0];
    r[1] = s * a[1];
    r[2] = s * a[2];
}
static inline void v3_axpy(double *r, double s, const double *a)
{
    r[0] += s * a[0];
    r[1] += s * a[1];
    r[2] += s * a[2];
}
static inline void v3_cross(double *r, const double *a, const double *b)
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    r[0] = x;
    r[1] = y;
    r[2] = z;
}
static inline double v3_norm(const double *a) { return sqrt(v3_dot(a, a)); }
static inline double v3_dist2(const double *a, const double *b)
{
    double d[3];
    v3_sub(d, a, b);
    return v3_dot(d, d);
}

#endif
