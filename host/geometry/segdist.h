/* Closest points of two segments: the one definition of "strut" geometry that
 * the serial reference and the OpenCL kernels share (the kernels carry a
 * line-by-line copy; keep them in step). Scalars only, no pointers to
 * structs, so the body compiles unchanged as OpenCL C.
 *
 * Segments P(s) = p0 + s (p1 - p0), Q(t) = q0 + t (q1 - q0), s, t in [0,1].
 * Algorithm: Ericson, Real-Time Collision Detection, 5.1.9, with the
 * parallel test made scale-free: segments whose sin^2(angle) <= 1e-12 are
 * treated as parallel (s = 0 first), so both backends take the same branch
 * except within rounding of that threshold. Both segments must have
 * non-zero length (the engine keeps edges equal, so they do). */
#ifndef TR_SEGDIST_H
#define TR_SEGDIST_H

#include <math.h>

static inline double tr_clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

/* Returns the distance; writes the parameters of the closest points. */
static inline double tr_segment_distance(const double *p0, const double *p1, const double *q0,
                                         const double *q1, double *s_out, double *t_out)
{
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = p1[k] - p0[k];
        d2[k] = q1[k] - q0[k];
        r[k] = p0[k] - q0[k];
    }
    double a = d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2];
    double e = d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2];
    double f = d2[0] * r[0] + d2[1] * r[1] + d2[2] * r[2];
    double c = d1[0] * r[0] + d1[1] * r[1] + d1[2] * r[2];
    double b = d1[0] * d2[0] + d1[1] * d2[1] + d1[2] * d2[2];
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
    double dx = r[0] + s * d1[0] - t * d2[0];
    double dy = r[1] + s * d1[1] - t * d2[1];
    double dz = r[2] + s * d1[2] - t * d2[2];
    *s_out = s;
    *t_out = t;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Is the closest-point connector c = P(s) - Q(t) (s, t, d as returned by
 * tr_segment_distance) within `tilt` (a sine) of both segments' normal
 * planes: |c.d1| <= tilt d |d1| and |c.d2| <= tilt d |d2|? A strut of a
 * tight rope is normal to both strands (a local minimum of the distance
 * along both has c in the normal slab or wedge of each edge, so it passes
 * once tilt >= the sine of the largest turning angle); this is what lets
 * the contact list skip the many nearly parallel pairs within the cutoff. */
static inline int tr_segment_nearly_normal(const double *p0, const double *p1, const double *q0,
                                           const double *q1, double s, double t, double d, double tilt)
{
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = p1[k] - p0[k];
        d2[k] = q1[k] - q0[k];
        r[k] = p0[k] - q0[k];
    }
    double cx = r[0] + s * d1[0] - t * d2[0];
    double cy = r[1] + s * d1[1] - t * d2[1];
    double cz = r[2] + s * d1[2] - t * d2[2];
    double ca = cx * d1[0] + cy * d1[1] + cz * d1[2];
    double cb = cx * d2[0] + cy * d2[1] + cz * d2[2];
    double la = sqrt(d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]);
    double lb = sqrt(d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2]);
    return fabs(ca) <= tilt * d * la && fabs(cb) <= tilt * d * lb;
}

#endif
