/* This file contains the tube pictures' surface: the decimated core, its
 * rings (tube_mesh.h's rotation-minimising frames) and the marks of the
 * kappa = 1 stretches and the contacts (tube_picture.h). */
#include "analysis/tube_picture.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/tube_mesh.h"
#include "curve/polyline.h"
#include "util/vec3.h"

/* A contact mark's radius on the surface: a strut's midpoint is where the
 * two tubes touch; the ring vertices within this distance of it are
 * marked. Wider than half the rings' spacing (0.05) and half the sides'
 * (2 pi / 24 / 2 = 0.13), so every strut marks at least one vertex and the
 * struts along a contact line draw a continuous stripe. */
#define CONTACT_MARK_RADIUS 0.17

size_t tr_tube_picture_default_rings(size_t n, double L)
{
    double want = ceil(L / 0.05);
    size_t r = !(want >= 64.0) ? 64 : want > 2000.0 ? 2000 : (size_t)want;
    return r < n ? r : n;
}

void tr_tube_picture_free(tr_tube_picture *tp)
{
    if (!tp)
        return;
    free(tp->core), free(tp->s), free(tp->p), free(tp->kappa), free(tp->mark), free(tp->strut);
    memset(tp, 0, sizeof *tp);
}

/* Whether l (from the origin) lies on plateau pl, whose ends may wrap
 * through the origin. */
static int on_plateau(const tr_plateau *pl, const tr_arc_profile *prof, double l)
{
    if (pl->first == 0 && pl->last + 1 == prof->n) /* the whole curve */
        return 1;
    return pl->l1 <= pl->l2 ? l >= pl->l1 && l <= pl->l2 : l >= pl->l1 || l <= pl->l2;
}

/* Marks the vertices of the rings near input arclength l that lie within
 * CONTACT_MARK_RADIUS of the strut midpoint mid. The rings searched run
 * from the one at l outwards while their centres are within three radii of
 * l along the core (closer than the radius in space needs less than that,
 * as a bend's inside cannot be tighter than the tube's radius). */
static void mark_contact(tr_tube_picture *tp, double l, const double *mid)
{
    size_t R = tp->rings, K = tp->sides;
    size_t lo = 0, hi = R; /* the last ring with s <= l: s[0] = 0 <= l */
    while (hi - lo > 1) {
        size_t c = lo + (hi - lo) / 2;
        if (tp->s[c] <= l)
            lo = c;
        else
            hi = c;
    }
    for (int dir = -1; dir <= 1; dir += 2)
        for (size_t step = dir < 0 ? 0 : 1; step <= R / 2; step++) {
            size_t r = dir < 0 ? (lo + R - step % R) % R : (lo + step) % R;
            if (step > 1 && fabs(tr_wrap_signed(tp->s[r] - l, tp->L)) > 3.0 * CONTACT_MARK_RADIUS)
                break;
            for (size_t j = 0; j < K; j++) {
                const double *q = tp->p + 3 * (r * K + j);
                if (v3_dist2(q, mid) < CONTACT_MARK_RADIUS * CONTACT_MARK_RADIUS &&
                    tp->mark[r * K + j] != TR_TUBE_CONTACT) {
                    tp->mark[r * K + j] = TR_TUBE_CONTACT;
                    tp->contact_marks++;
                }
            }
        }
}

int tr_tube_picture_build(const double *x, size_t n, const tr_analysis *a, size_t rings, size_t sides,
                          tr_tube_picture *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (n < 3)
        return tr_fail(err, TR_EINVAL, "a tube picture needs a closed polygon of at least 3 vertices");
    double *sx = malloc((n + 1) * sizeof *sx);
    if (!sx)
        return tr_fail(err, TR_ENOMEM, "out of memory for the tube picture");
    tr_polyline_arclength(x, n, sx);
    double L = sx[n];
    if (!rings)
        rings = tr_tube_picture_default_rings(n, L);
    if (rings < 3 || rings > n || sides < 3 || sides > 64) {
        free(sx);
        return tr_fail(err, TR_EINVAL, "a tube picture needs 3 to %zu rings and 3 to 64 sides, got %zu and %zu",
                       n, rings, sides);
    }
    out->rings = rings, out->sides = sides, out->L = L;
    out->core = malloc(3 * rings * sizeof *out->core);
    out->s = malloc(rings * sizeof *out->s);
    out->kappa = malloc(rings * sizeof *out->kappa);
    out->mark = calloc(rings * sides, 1);
    /* every strut, or every stride-th of them in the analysis's order */
    size_t stride = (a->npairs + TR_TUBE_STRUTS_MAX - 1) / TR_TUBE_STRUTS_MAX;
    out->strut = malloc((a->npairs ? 6 * TR_TUBE_STRUTS_MAX : 1) * sizeof *out->strut);
    tr_tube_mesh m = {0};
    int rc = TR_OK;
    if (!out->core || !out->s || !out->kappa || !out->mark || !out->strut) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory for the tube picture");
        goto out;
    }
    /* The core: the polygon itself when it is coarse enough, else points at
     * equal arclength on it (so the picture's core never leaves the rope's). */
    for (size_t r = 0; r < rings; r++) {
        if (rings == n) {
            memcpy(out->core + 3 * r, x + 3 * r, 3 * sizeof *x);
            out->s[r] = sx[r];
        } else {
            out->s[r] = L * (double)r / (double)rings;
            tr_polyline_point_at(x, n, sx, out->s[r], out->core + 3 * r);
        }
    }
    if ((rc = tr_tube_mesh_add(&m, out->core, rings, 1, 1.0, sides, err)) != TR_OK)
        goto out;
    out->p = m.v, m.v = NULL; /* the rings; the mesh's triangles are not needed */

    /* Curvature and the kappa = 1 stretches, from the analysis's profile
     * (positions from its origin). */
    const tr_arc_profile *prof = &a->prof;
    for (size_t r = 0; r < rings; r++) {
        double l = tr_symmetry_from_origin(&a->sym, out->s[r]), best = INFINITY;
        out->kappa[r] = 0.0;
        for (size_t k = 0; k < prof->n; k++) {
            double d = fabs(tr_wrap_signed(prof->pos[k] - l, a->L));
            if (d < best)
                best = d, out->kappa[r] = prof->kappa[k];
        }
        int minrad = 0;
        for (size_t i = 0; i < a->nplateaus && !minrad; i++)
            minrad = on_plateau(&a->plateaus[i], prof, l);
        if (minrad) {
            memset(out->mark + r * sides, TR_TUBE_MINRAD, sides);
            out->minrad_rings++;
        }
    }
    /* Contacts: each strut touches the surface at its midpoint; both ends'
     * rings are searched. */
    double origin = isnan(a->sym.origin) ? 0.0 : a->sym.origin;
    for (size_t k = 0; k < a->npairs; k++) {
        double li = tr_wrap(a->pairs[k].li + origin, L), lj = tr_wrap(a->pairs[k].lj + origin, L);
        double pi[3], pj[3], mid[3];
        tr_polyline_point_at(x, n, sx, li, pi);
        tr_polyline_point_at(x, n, sx, lj, pj);
        v3_add(mid, pi, pj);
        v3_scale(mid, 0.5, mid);
        mark_contact(out, li, mid);
        mark_contact(out, lj, mid);
        if (k % stride == 0 && out->nstruts < TR_TUBE_STRUTS_MAX) {
            memcpy(out->strut + 6 * out->nstruts, pi, sizeof pi);
            memcpy(out->strut + 6 * out->nstruts + 3, pj, sizeof pj);
            out->nstruts++;
        }
    }
out:
    tr_tube_mesh_free(&m);
    free(sx);
    if (rc != TR_OK)
        tr_tube_picture_free(out);
    return rc;
}
