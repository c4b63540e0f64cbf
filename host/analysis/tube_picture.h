/* The surface the tube pictures draw (tube_script.h): rings of radius 1
 * around a decimated core curve, each ring vertex marked by what the
 * analysis says of it: plain rope, a kappa = 1 stretch (MinRad active: the
 * rope bent as tightly as its thickness allows), or a contact (where a strut
 * meets the surface, i.e. where the rope touches another part of itself).
 * Drawing every vertex of a fine polygon would give gnuplot hundreds of
 * thousands of quads to sort for nothing a picture can show, so the core is
 * resampled to about one ring per 0.05 of length. */
#ifndef TR_TUBE_PICTURE_H
#define TR_TUBE_PICTURE_H

#include <stddef.h>

#include "analysis/portrait.h"
#include "util/error.h"

enum { TR_TUBE_ROPE = 0, TR_TUBE_MINRAD = 1, TR_TUBE_CONTACT = 2 };

/* The struts' picture draws at most this many (a tight knot has tens of
 * thousands at high N; a few hundred show the contact structure, more
 * turn the picture into a solid web). */
#define TR_TUBE_STRUTS_MAX 240

typedef struct tr_tube_picture {
    size_t rings, sides;   /* rings around the core, vertices per ring */
    double L;              /* the input polygon's length */
    double *core;          /* 3 rings: the core curve, closed, on the input polygon */
    double *s;             /* rings: input arclength of ring r's centre */
    double *p;             /* 3 rings sides: vertex j of ring r at p + 3 (r sides + j) */
    double *kappa;         /* rings: the analysis's curvature nearest each ring */
    unsigned char *mark;   /* rings sides: TR_TUBE_* (contact over kappa = 1 over rope) */
    double *strut;         /* 6 nstruts: the two ends of each strut drawn */
    size_t nstruts;        /* struts drawn: every one, or an even selection of TR_TUBE_STRUTS_MAX */
    size_t minrad_rings;   /* rings on a kappa = 1 stretch */
    size_t contact_marks;  /* vertices marked as contacts */
} tr_tube_picture;

/* The default ring count for a closed polygon of n vertices and length L:
 * one ring per 0.05 of length (a kappa = 1 stretch of the tight trefoil,
 * 0.15 long, gets three), at least 64 and at most 2000, and never more
 * than n. */
size_t tr_tube_picture_default_rings(size_t n, double L);

/* x: the closed component of n vertices the analysis a was made of (rope
 * radius 1); rings: 3 to n (0: the default), sides: 3 to 64. TR_EINVAL for
 * counts out of range, TR_EGEOMETRY for a core the tube cannot follow,
 * TR_ENOMEM. */
int tr_tube_picture_build(const double *x, size_t n, const tr_analysis *a, size_t rings, size_t sides,
                          tr_tube_picture *out, tr_error *err);
void tr_tube_picture_free(tr_tube_picture *tp);

#endif
