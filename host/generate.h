/* Start curves: torus knots, circles, the Hopf link and the simple clasp. */
#ifndef TR_GENERATE_H
#define TR_GENERATE_H

#include "curve.h"

/* Torus knot T(p,q) on a torus of radii (R, r) scaled so the curve is
 * embedded with room to tighten; n vertices, equilateral (resampled by
 * arclength). gcd(p,q) must be 1. */
int tr_make_torus(tr_curve *out, int p, int q, size_t n, tr_error *err);

/* Circle of the given radius in the xy plane, n vertices. */
int tr_make_circle(tr_curve *out, double radius, size_t n, tr_error *err);

/* Hopf link: two round circles through each other's centre, n vertices each. */
int tr_make_hopf(tr_curve *out, size_t n, tr_error *err);

/* Simple clasp (REFERENCE.md 6.1): two open ropes hooked in perpendicular
 * planes, end vertices of rope A on plane z = +h, of rope B on z = -h;
 * n vertices per rope, minimum non-local distance >= 2 at the start. */
int tr_make_clasp(tr_curve *out, size_t n, double h, tr_error *err);

/* Resamples every component to the given number of vertices at equal
 * arclength (closed components equilateral to rounding; open components keep
 * their end vertices and constraints). n_per_comp may be NULL to keep counts. */
int tr_resample(const tr_curve *in, const size_t *n_per_comp, tr_curve *out, tr_error *err);

/* As tr_resample, but along an interpolating cubic spline through the
 * vertices (parametrised by chord length; periodic for closed components,
 * natural for open ones) instead of along the polygon itself: refining a
 * smooth curve this way keeps it smooth (new vertices do not sit on the old
 * straight edges). The spline passes through every old vertex; open
 * components keep their end vertices and constraints. */
int tr_resample_smooth(const tr_curve *in, const size_t *n_per_comp, tr_curve *out, tr_error *err);

#endif
