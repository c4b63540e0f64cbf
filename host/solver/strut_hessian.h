/* The exact segment-segment distance of a strut as a smooth function of its
 * four vertices, with gradient and Hessian: what the second-order solver
 * (newton.h) needs of the strut rows d(a, b) >= 2.
 *
 * d(x) = min over s, t in [0, 1] of |P(s) - Q(t)|, P(s) = p0 + s (p1 - p0),
 * Q(t) = q0 + t (q1 - q0), x = (p0, p1, q0, q1) in R^12. With F = d^2 and
 * phi(x, s, t) = |P(s) - Q(t)|^2, the closest-point parameters (s*, t*) are
 * recomputed at every x (kernels/segment_distance.h), so the rope cannot slip between
 * frozen sample points (a frozen-parameter distance lets a strand pass the
 * other between them: d_frozen - d_true grows like edge^2 / 8). By the
 * envelope theorem grad F = phi_x at (s*, t*); the Hessian is
 *   F_xx = phi_xx - phi_x theta (phi_theta theta)^-1 phi_theta x
 * over the parameters theta that are interior (a parameter at 0 or 1 stays
 * there under a small motion, unless strict complementarity fails, which is
 * a set of measure zero). For (nearly) parallel segments phi_theta theta is
 * (nearly) singular: the closest points form a segment and only s is kept
 * free. Then grad d = grad F / (2 d), d_xx = F_xx / (2 d) - grad F grad F^T / (4 d^3). */
#ifndef TR_STRUT_HESSIAN_H
#define TR_STRUT_HESSIAN_H

/* Returns d; g[12] = grad d (may be NULL), h[144] = Hessian of d, row major
 * (may be NULL). Coordinates are ordered p0, p1, q0, q1. d must be > 0. */
double tr_strut_distance_derivs(const double *p0, const double *p1, const double *q0, const double *q1,
                                double *g, double *h);

#endif
