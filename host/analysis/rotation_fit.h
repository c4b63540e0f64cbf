/* Best rotation about a fixed centre taking one point set onto another
 * (Horn's quaternion form of the Kabsch problem): the tool for testing a
 * knot's rotational symmetries. */
#ifndef TR_ROTATION_FIT_H
#define TR_ROTATION_FIT_H

#include <stddef.h>

typedef struct tr_rotation {
    double R[3][3];
    double axis[3];  /* unit; the rotation is by +angle about it (right-hand rule) */
    double angle;    /* in [0, pi] */
    double rms;      /* sqrt(mean |R(a_i - c) - (b_i - c)|^2) */
} tr_rotation;

/* a, b: n points each (3n doubles), centre c. Returns 0, or -1 if n == 0. */
int tr_rotation_fit(const double *a, const double *b, size_t n, const double *c, tr_rotation *out);

/* Rotation matrix by `angle` about unit `axis`. */
void tr_rotation_matrix(const double *axis, double angle, double R[3][3]);

#endif
