/* Start curves: torus knots, circles, the Hopf link and the simple clasp. */
#ifndef TR_GENERATE_H
#define TR_GENERATE_H

#include "curve/curve.h"
#include "util/clock.h"

/* Torus knot T(p,q): winds p times around the z axis and q times around the
 * core circle of a torus whose radii balance the two strand spacings; scaled
 * so that its radius of curvature is >= 2 and points more than pi apart
 * along it are >= 3 apart (a rope of radius 1 would touch at 2), so it is
 * embedded with room to tighten. n vertices, equilateral (equal chords to
 * ~1e-13 relative). gcd(p,q) must be 1 and 2 <= |p|,|q| <= 1000; a negative
 * p or q gives the mirror image. TR_EINVAL if n makes edges longer than 1. */
int tr_make_torus(tr_curve *out, int p, int q, size_t n, tr_error *err);

/* Circle of the given radius in the xy plane, n vertices. */
int tr_make_circle(tr_curve *out, double radius, size_t n, tr_error *err);

/* Hopf link: two round circles through each other's centre, n vertices each. */
int tr_make_hopf(tr_curve *out, size_t n, tr_error *err);

/* Simple clasp (docs/physics.md 6.1): two open ropes hooked in perpendicular
 * planes. Rope A (component 0) lies in the plane y = 0: a half circle of
 * radius 3 centred at (0, 0, 1.5), opening upwards, with vertical legs from
 * (+-3, 0, 1.5) up to z = +h; rope B (component 1) is the same turned upside
 * down in the plane x = 0 (centre (0, 0, -1.5), legs down to z = -h). Each
 * arch's tip sits at the other's centre, so the ropes come no closer than 3.
 * The end vertices of A carry constraint 0 (TR_CST_PLANE z = h, file id 1),
 * those of B constraint 1 (z = -h, id 2). n vertices per rope, equal edges;
 * h >= 1.5. TR_EINVAL if n makes edges longer than 1. */
int tr_make_clasp(tr_curve *out, size_t n, double h, tr_error *err);

/* The resamplers. There are three, and they differ on purpose:
 *  - tr_resample: new vertices on the old polygon, with equal chords (the
 *    engine wants equal edges). What tighten --n uses to remove vertices.
 *  - tr_resample_smooth: the same along a cubic spline through the old
 *    vertices, so that added vertices do not sit on straight old edges
 *    (their kept corners would put MinRad at ~1/N). What tighten --n uses to
 *    add vertices.
 *  - tr_refine_lowpass (engine/refine_lowpass.h): equal arclength, then a
 *    Fourier low-pass, for the refinement between levels of a tightened
 *    curve, whose vertex-level curvature noise neither of the above removes;
 *    the engine re-equalises the edges afterwards.
 *
 * tr_resample: every component to the given number of vertices, equal
 * chords along the polygon (closed components equilateral to rounding; open
 * components keep their end vertices and constraints). n_per_comp may be
 * NULL to keep counts. */
int tr_resample(const tr_curve *in, const size_t *n_per_comp, tr_curve *out, tr_error *err);

/* As tr_resample, but along an interpolating cubic spline through the
 * vertices (parametrised by chord length; periodic for closed components,
 * natural for open ones) instead of along the polygon itself: refining a
 * smooth curve this way keeps it smooth (new vertices do not sit on the old
 * straight edges). The spline passes through every old vertex; open
 * components keep their end vertices and constraints. */
int tr_resample_smooth(const tr_curve *in, const size_t *n_per_comp, tr_curve *out, tr_error *err);

/* tr_resample (smooth 0) or tr_resample_smooth (smooth 1) within a bound
 * (NULL: none), looked at once a sweep of the equal-chord iteration: at
 * 10^6 vertices and more a resampling takes seconds (below TR_DEADLINE_WORK
 * vertices, util/clock.h, it is not looked at). TR_EINTERRUPTED, out
 * left empty, once the bound has passed. */
int tr_resample_within(const tr_curve *in, const size_t *n_per_comp, int smooth, const tr_deadline *bound,
                       tr_curve *out, tr_error *err);

#endif
