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

#undef TR_SHARED_FN
#undef TR_OPENCL_C
#endif
