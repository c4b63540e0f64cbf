/* This file contains the closest points of two segments: the one definition
 * of "strut" geometry that the serial reference and the OpenCL kernels
 * share. It is valid C and valid OpenCL C: the host includes it
 * ("segment_distance.h"; kernels/ is on the include path) and every program
 * gets it as a source string after common.clh (tr_cl_build), so both
 * compile the same lines. The shared bodies take scalars (no pointers to
 * host structs or device vectors); the host's form takes double[3] points,
 * the kernels' real3, and both unpack them into the same body.
 *
 * Segments P(s) = p0 + s (p1 - p0), Q(t) = q0 + t (q1 - q0), s, t in [0,1].
 * Algorithm: Ericson, Real-Time Collision Detection, 5.1.9, with the
 * parallel test made scale-free: segments whose sin^2(angle) <= 1e-12 are
 * treated as parallel (s = 0 first), so both backends take the same branch
 * except within rounding of that threshold. Both segments must have
 * non-zero length (the engine keeps edges equal, so they do). */
#ifndef TR_SEGMENT_DISTANCE_H
#define TR_SEGMENT_DISTANCE_H

#if defined(__OPENCL_C_VERSION__) || defined(__OPENCL_VERSION__)
#define TR_OPENCL_C 1
#define TR_SHARED_FN inline /* OpenCL C: double needs common.clh's fp64 pragma first */
#else
#include <math.h>
#define TR_SHARED_FN static inline
#endif

TR_SHARED_FN double tr_clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

/* The distance of the segments p0 p1 and q0 q1 given by coordinates;
 * writes the parameters of the closest points. */
TR_SHARED_FN double tr_segment_distance_xyz(double p0x, double p0y, double p0z, double p1x,
                                            double p1y, double p1z, double q0x, double q0y,
                                            double q0z, double q1x, double q1y, double q1z,
                                            double *s_out, double *t_out)
{
    double d1x = p1x - p0x, d1y = p1y - p0y, d1z = p1z - p0z;
    double d2x = q1x - q0x, d2y = q1y - q0y, d2z = q1z - q0z;
    double rx = p0x - q0x, ry = p0y - q0y, rz = p0z - q0z;
    double a = d1x * d1x + d1y * d1y + d1z * d1z;
    double e = d2x * d2x + d2y * d2y + d2z * d2z;
    double f = d2x * rx + d2y * ry + d2z * rz;
    double c = d1x * rx + d1y * ry + d1z * rz;
    double b = d1x * d2x + d1y * d2y + d1z * d2z;
    double denom = a * e - b * b;
    double s = 0.0, t;
    if (denom > 1e-12 * a * e)
        s = tr_clamp01((b * f - c * e) / denom);
    t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = tr_clamp01(-c / a);
    } else if (t > 1.0) {
        t = 1.0;
        s = tr_clamp01((b - c) / a);
    }
    double dx = rx + s * d1x - t * d2x;
    double dy = ry + s * d1y - t * d2y;
    double dz = rz + s * d1z - t * d2z;
    *s_out = s;
    *t_out = t;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Is the closest-point connector c = P(s) - Q(t) (s, t, d as returned by
 * the distance) within `tilt` (a sine) of both segments' normal planes:
 * |c.d1| <= tilt d |d1| and |c.d2| <= tilt d |d2|? A strut of a tight rope
 * is normal to both strands (a local minimum of the distance along both has
 * c in the normal slab or wedge of each edge, so it passes once tilt >= the
 * sine of the largest turning angle); this is what lets the contact list
 * skip the many nearly parallel pairs within the cutoff. */
TR_SHARED_FN int tr_segment_nearly_normal_xyz(double p0x, double p0y, double p0z, double p1x,
                                              double p1y, double p1z, double q0x, double q0y,
                                              double q0z, double q1x, double q1y, double q1z,
                                              double s, double t, double d, double tilt)
{
    double d1x = p1x - p0x, d1y = p1y - p0y, d1z = p1z - p0z;
    double d2x = q1x - q0x, d2y = q1y - q0y, d2z = q1z - q0z;
    double rx = p0x - q0x, ry = p0y - q0y, rz = p0z - q0z;
    double cx = rx + s * d1x - t * d2x;
    double cy = ry + s * d1y - t * d2y;
    double cz = rz + s * d1z - t * d2z;
    double ca = cx * d1x + cy * d1y + cz * d1z;
    double cb = cx * d2x + cy * d2y + cz * d2z;
    double la = sqrt(d1x * d1x + d1y * d1y + d1z * d1z);
    double lb = sqrt(d2x * d2x + d2y * d2y + d2z * d2z);
    return fabs(ca) <= tilt * d * la && fabs(cb) <= tilt * d * lb;
}

#ifdef TR_OPENCL_C
/* The kernels' form: points as real3. */
inline real tr_segment_distance(real3 p0, real3 p1, real3 q0, real3 q1, real *s_out, real *t_out)
{
    return tr_segment_distance_xyz(p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, q0.x, q0.y, q0.z, q1.x, q1.y,
                                   q1.z, s_out, t_out);
}
inline int tr_segment_nearly_normal(real3 p0, real3 p1, real3 q0, real3 q1, real s, real t, real d,
                                    real tilt)
{
    return tr_segment_nearly_normal_xyz(p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, q0.x, q0.y, q0.z, q1.x,
                                        q1.y, q1.z, s, t, d, tilt);
}
#else
/* The host's form: points as double[3]. */
static inline double tr_segment_distance(const double *p0, const double *p1, const double *q0,
                                         const double *q1, double *s_out, double *t_out)
{
    return tr_segment_distance_xyz(p0[0], p0[1], p0[2], p1[0], p1[1], p1[2], q0[0], q0[1], q0[2],
                                   q1[0], q1[1], q1[2], s_out, t_out);
}
static inline int tr_segment_nearly_normal(const double *p0, const double *p1, const double *q0,
                                           const double *q1, double s, double t, double d,
                                           double tilt)
{
    return tr_segment_nearly_normal_xyz(p0[0], p0[1], p0[2], p1[0], p1[1], p1[2], q0[0], q0[1],
                                        q0[2], q1[0], q1[1], q1[2], s, t, d, tilt);
}
#endif

/* The exact strut distance as a smooth function of its four vertices, with
 * gradient and Hessian: the second-order solver's strut row d(a, b) >= 2
 * (host/solver/strut_hessian.h has the derivation; host/solver/strut_hessian.c
 * and the kernels of kernels/solver_rows.cl both call this one body, so the
 * serial path, the reference backend and the device do the same arithmetic).
 * x: p0, p1, q0, q1 (12 reals, private); writes g[12] = grad d when want_g
 * and h[144] = the Hessian of d, row major, when want_h (g, h in global
 * memory on the device: the rows' output buffers). d must be > 0.
 * The Hessian is written entry by entry, phi_xx's entry minus the Schur
 * complement's, over 2 d, minus grad F grad F^T / (4 d^3): the same
 * operations in the same order as a 144-entry scratch block would take,
 * without the 1.1 KiB of private memory per work-item. */
#ifdef TR_OPENCL_C
#define TR_SHARED_OUT __global
#else
#define TR_SHARED_OUT
#endif
/* interior test for a closest-point parameter: away from the clamp by more
 * than rounding */
#define TR_STRUT_PARAM_EPS 1e-12
/* (nearly) parallel: sin^2 of the angle below this, as the distance decides */
#define TR_STRUT_PARALLEL_SIN2 1e-10
TR_SHARED_FN double tr_strut_row_derivs(const double *x, TR_SHARED_OUT double *g,
                                        TR_SHARED_OUT double *h, int want_g, int want_h)
{
    double s, t;
    double d = tr_segment_distance_xyz(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8], x[9],
                                       x[10], x[11], &s, &t);
    if (!want_g && !want_h)
        return d;
    double d1[3], d2[3], D[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = x[3 + k] - x[k];
        d2[k] = x[9 + k] - x[6 + k];
        D[k] = x[k] + s * d1[k] - x[6 + k] - t * d2[k];
    }
    /* weights of the four points in D */
    const double W[4] = {1.0 - s, s, -(1.0 - t), -t};
    /* grad F = 2 W_k D on point k */
    double gF[12];
    for (int k = 0; k < 4; k++)
        for (int c = 0; c < 3; c++)
            gF[3 * k + c] = 2.0 * W[k] * D[c];
    if (want_g)
        for (int i = 0; i < 12; i++)
            g[i] = gF[i] / (2.0 * d);
    if (!want_h)
        return d;
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
    int fs = s > TR_STRUT_PARAM_EPS && s < 1.0 - TR_STRUT_PARAM_EPS;
    int ft = t > TR_STRUT_PARAM_EPS && t < 1.0 - TR_STRUT_PARAM_EPS;
    if (fs && ft && a11 * a22 - a12 * a12 <= TR_STRUT_PARALLEL_SIN2 * a11 * a22)
        ft = 0;
    double i11 = 0.0, i22 = 0.0, i12 = 0.0;
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
        for (int j = 0; j < 12; j++) {
            /* phi_xx = 2 (W W^T) (x) I3, less the Schur complement */
            double H = i % 3 == j % 3 ? 2.0 * W[i / 3] * W[j / 3] : 0.0;
            H -= i11 * gs[i] * gs[j] + i22 * gt[i] * gt[j] + i12 * (gs[i] * gt[j] + gt[i] * gs[j]);
            /* d = sqrt(F) */
            h[i * 12 + j] = H / (2.0 * d) - gF[i] * gF[j] / (4.0 * d * d * d);
        }
    return d;
}

/* The augmented Lagrangian's term of an inequality row g >= 0 with
 * multiplier lam and penalty mu (host/solver/newton.h, PHR): its value;
 * *pi = max(0, lam - mu g), the multiplier estimate. */
TR_SHARED_FN double tr_phr_ineq_term(double g, double lam, double mu, double *pi)
{
    if (lam - mu * g > 0.0) {
        *pi = lam - mu * g;
        return -lam * g + 0.5 * mu * g * g;
    }
    *pi = 0.0;
    return -lam * lam / (2.0 * mu);
}
#undef TR_SHARED_OUT

#undef TR_SHARED_FN
#undef TR_OPENCL_C
#endif
