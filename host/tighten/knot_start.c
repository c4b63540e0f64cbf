/* Starts from braid words, and the type check (knot_start.h). */
#include "tighten/knot_start.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/braid_closure.h"
#include "curve/generate.h"
#include "curve/pd_layout.h"
#include "geometry/relax.h"
#include "oracle/thickness.h"
#include "topology/linking.h"
#include "topology/signature.h"

/* Vertices per slot and strand of the dense closure the start is resampled
 * from: its polygon's corners turn by a few degrees, so its thickness is
 * the smooth curve's to a percent, and the equal chords taken along it
 * keep that smoothness at the start's coarser edges. */
#define DENSE_SAMPLES 48
#define MIN_PER_COMPONENT 8

/* m gets the oracle's measure of c; a curve of thickness 0 (one that
 * touches itself) is refused, what naming it */
static int measure_thick(const tr_curve *c, const char *what, tr_thickness *m, tr_error *err)
{
    tr_thickness_opts opts = {0};
    int rc = tr_thickness_measure(c, &opts, m, NULL, err);
    if (rc == 0 && !(m->thickness > 0))
        rc = tr_fail(err, TR_EGEOMETRY, "the curve to %s has thickness 0 (it touches itself)", what);
    return rc;
}

/* The relaxation (geometry/relax.h) runs on a polygon of edges this many
 * times the dense curve's thickness (9_3's braid closure: 90 vertices): its
 * chords then stay within 0.75 of a thickness of the curve, and no chord
 * meets another strand. A curve that needs more than RELAX_MAX_N vertices
 * so (a crowded PD drawing) is left as drawn: the relaxation's cost grows
 * as their square. RELAX_STEPS steps; the relaxed polygon is drawn along a
 * spline with RELAX_SPLINE_SAMPLES points an edge. */
#define RELAX_EDGE_OF_THICKNESS 2.45
#define RELAX_MAX_N 320
#define RELAX_STEPS 3000
#define RELAX_SPLINE_SAMPLES 40

int tr_knot_start_relaxed(const tr_curve *dense, tr_curve *out, int *relaxed, tr_error *err)
{
    memset(out, 0, sizeof *out);
    *relaxed = 0;
    tr_thickness m;
    int rc = measure_thick(dense, "relax", &m, err);
    if (rc)
        return rc;
    int nc = dense->ncomp;
    double edge = RELAX_EDGE_OF_THICKNESS * m.thickness;
    if (m.length / edge > RELAX_MAX_N)
        return tr_curve_copy(out, dense, err);
    size_t *per = malloc((size_t)nc * sizeof *per);
    if (!per)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    for (int k = 0; k < nc; k++) {
        per[k] = (size_t)lround(tr_comp_length(dense, k) / edge);
        if (per[k] < MIN_PER_COMPONENT)
            per[k] = MIN_PER_COMPONENT;
    }
    tr_curve coarse = {0};
    rc = tr_resample(dense, per, &coarse, err);
    if (rc == 0)
        rc = tr_curve_relax(&coarse, RELAX_STEPS, err);
    for (int k = 0; k < nc; k++)
        per[k] *= RELAX_SPLINE_SAMPLES;
    if (rc == 0 && (rc = tr_resample_smooth(&coarse, per, out, err)) == 0)
        *relaxed = 1;
    free(per);
    tr_curve_free(&coarse);
    return rc;
}

/* A crowded drawing's exact polygon (a PD code's lifted straight-line
 * drawing, curve/pd_layout.h) relaxed instead of its spline: the polygon
 * is cut, each edge into pieces of about 1 / POLY_RELAX_PER_VERTEX of the
 * mean edge (a cut polygon is the same polygon: no strand moves), and
 * relaxed, where the relaxation's guard keeps every strand from another,
 * so the relaxed polygon is the code's knot whatever the drawing's
 * crowding (Tutte's drawing of 9_15 drawn along a spline: 39 969 vertices
 * at thickness 1.25, where the relaxed polygon makes 681). Then drawn
 * densely along a spline. The relaxation's cost grows as the cube of the
 * count (its pairs, and steps of a twentieth of an edge): measured with
 * two tightenings beside it on the 2 cores, 9_3 / 9_15 / 10_165 made at
 * 1.5 per vertex and 4000 steps in 0.14-0.44 s, lengths 140 / 150 / 141
 * at thickness 1.25; at 3 per vertex and 6000 steps 0.8-1.1 s, 167 / 158
 * / 166 (not yet settled: 12 000 steps, 2.3 s, 156 / 148 / 158). */
#define POLY_RELAX_PER_VERTEX 1.5
#define POLY_RELAX_STEPS 4000

/* the pieces edge a-b is cut into: its length in pieces of `piece`, at least 1 */
static long pieces_of(const double *a, const double *b, double piece)
{
    double len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
    long pieces = lround(len / piece);
    return pieces < 1 ? 1 : pieces;
}

int tr_knot_start_polygon_relaxed(const tr_curve *poly, tr_curve *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    int nc = poly->ncomp;
    size_t *per = malloc((size_t)nc * sizeof *per);
    tr_curve cut = {0};
    if (!per)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    double piece = tr_curve_length(poly) / (double)poly->nv / POLY_RELAX_PER_VERTEX;
    for (int k = 0; k < nc; k++) {
        size_t s = poly->start[k], n = tr_comp_nv(poly, k);
        per[k] = 0;
        for (size_t i = 0; i < n; i++)
            per[k] += (size_t)pieces_of(poly->x + 3 * (s + i), poly->x + 3 * (s + (i + 1) % n), piece);
    }
    int rc = tr_curve_alloc(&cut, nc, per, NULL, err);
    for (int k = 0; rc == 0 && k < nc; k++) {
        size_t s = poly->start[k], n = tr_comp_nv(poly, k);
        double *p = cut.x + 3 * cut.start[k];
        cut.closed[k] = 1;
        for (size_t i = 0; i < n; i++) {
            const double *a = poly->x + 3 * (s + i), *b = poly->x + 3 * (s + (i + 1) % n);
            long pieces = pieces_of(a, b, piece);
            for (long q = 0; q < pieces; q++, p += 3)
                for (int d = 0; d < 3; d++)
                    p[d] = a[d] + (b[d] - a[d]) * (double)q / (double)pieces;
        }
    }
    if (rc == 0)
        rc = tr_curve_relax(&cut, POLY_RELAX_STEPS, err);
    for (int k = 0; k < nc; k++)
        per[k] = tr_comp_nv(&cut, k) * RELAX_SPLINE_SAMPLES;
    if (rc == 0)
        rc = tr_resample_smooth(&cut, per, out, err);
    free(per);
    tr_curve_free(&cut);
    return rc;
}

int tr_knot_start_from_braid(const tr_braid *b, size_t n, int relax, tr_curve *out, double *thickness, int *relaxed,
                             tr_error *err)
{
    memset(out, 0, sizeof *out);
    tr_curve dense, moved = {0};
    int rc = tr_make_braid_closure(&dense, b->strands, b->word, b->len, DENSE_SAMPLES, err);
    *relaxed = 0;
    if (rc)
        return rc;
    if (relax && (rc = tr_knot_start_relaxed(&dense, &moved, relaxed, err)) == 0)
        rc = tr_knot_start_from_curve(&moved, n, out, thickness, err);
    else if (!relax)
        rc = tr_knot_start_from_curve(&dense, n, out, thickness, err);
    tr_curve_free(&moved);
    tr_curve_free(&dense);
    return rc;
}

/* One try at n vertices (0: the default); *need gets the count that would
 * make the edges <= 1 when these n do not. */
static int start_once(const tr_curve *dense, size_t n, tr_curve *out, double *thickness, size_t *need, tr_error *err)
{
    memset(out, 0, sizeof *out);
    *need = 0;
    tr_thickness m;
    tr_thickness_opts opts = {0};
    int rc = measure_thick(dense, "start from", &m, err);
    if (rc)
        return rc;
    /* the scaled length sets the default count; shared by length */
    double total = m.length * TR_KNOT_START_THICKNESS / m.thickness;
    if (n == 0)
        n = (size_t)ceil(total / TR_KNOT_START_EDGE);
    if (!(total / TR_KNOT_START_EDGE < 1e6))
        return tr_fail(err, TR_EGEOMETRY, "the start would need %.3g vertices (its thickness is %.3g of its length): "
                       "too crowded a layout", total / TR_KNOT_START_EDGE, m.thickness / m.length);
    int nc = dense->ncomp;
    if (n < (size_t)nc * MIN_PER_COMPONENT) {
        return tr_fail(err, TR_EINVAL, "%zu vertices are too few for %d component%s (at least %d each)", n, nc,
                       nc == 1 ? "" : "s", MIN_PER_COMPONENT);
    }
    size_t *per = malloc((size_t)nc * sizeof *per);
    if (!per) {
        return tr_fail(err, TR_ENOMEM, "out of memory");
    }
    size_t given = 0;
    for (int k = 0; k < nc; k++) {
        per[k] = (size_t)floor((double)n * tr_comp_length(dense, k) / m.length);
        if (per[k] < MIN_PER_COMPONENT)
            per[k] = MIN_PER_COMPONENT;
        given += per[k];
    }
    /* the rest one each in turn (or the excess taken back), so the total
     * is n */
    for (int k = 0; given < n; k = (k + 1) % nc, given++)
        per[k]++;
    for (int k = 0; given > n && k < nc; k++)
        while (given > n && per[k] > MIN_PER_COMPONENT) {
            per[k]--;
            given--;
        }
    rc = tr_resample(dense, per, out, err);
    free(per);
    if (rc)
        return rc;
    /* scale the polygon itself (its corners count in MinRad) */
    rc = tr_thickness_measure(out, &opts, &m, NULL, err);
    if (rc == 0 && !(m.thickness > 0))
        rc = tr_fail(err, TR_EINVAL, "%zu vertices are too few for this braid: the polygon has thickness 0", n);
    if (rc == 0) {
        tr_curve_scale_by(out, TR_KNOT_START_THICKNESS / m.thickness);
        rc = tr_thickness_measure(out, &opts, &m, NULL, err);
    }
    if (rc == 0 && !(m.thickness >= 1.0))
        rc = tr_fail(err, TR_EGEOMETRY, "the scaled start has thickness %.6g, below 1 (internal)", m.thickness);
    double longest = 0;
    for (int k = 0; rc == 0 && k < out->ncomp; k++) {
        size_t s = out->start[k], nv = tr_comp_nv(out, k);
        for (size_t i = 0; i < nv; i++) {
            const double *a = out->x + 3 * (s + i), *q = out->x + 3 * (s + (i + 1) % nv);
            longest = fmax(longest, sqrt((a[0] - q[0]) * (a[0] - q[0]) + (a[1] - q[1]) * (a[1] - q[1]) +
                                         (a[2] - q[2]) * (a[2] - q[2])));
        }
    }
    if (rc == 0 && longest > 1.0) {
        *need = (size_t)ceil((double)n * longest);
        rc = tr_fail(err, TR_EINVAL, "%zu vertices make edges %.3g long at thickness %.3g; at least %zu are needed "
                     "(edges <= 1)", n, longest, m.thickness, *need);
    }
    if (rc) {
        tr_curve_free(out);
        return rc;
    }
    *thickness = m.thickness;
    return 0;
}

int tr_knot_start_from_curve(const tr_curve *dense, size_t n, tr_curve *out, double *thickness, tr_error *err)
{
    size_t need = 0;
    int rc = start_once(dense, n, out, thickness, &need, err);
    /* the default count comes from the dense curve's thickness; where the
     * coarser polygon's corners cost more than that foresaw, more vertices */
    for (int tries = 0; n == 0 && rc == TR_EINVAL && need > 0 && tries < 3; tries++)
        rc = start_once(dense, need + need / 8, out, thickness, &need, err);
    return rc;
}

int tr_type_check_of(const tr_curve *c, tr_type_check *tc, tr_error *err)
{
    memset(tc, 0, sizeof *tc);
    tc->components = c->ncomp;
    if (c->ncomp == 1)
        return tr_knot_invariants_of(c, &tc->inv, err);
    if (c->ncomp > TR_TYPE_CHECK_MAX_COMPONENTS)
        return tr_fail(err, TR_EUNSUPPORTED, "%d components: the check takes at most %d", c->ncomp,
                       TR_TYPE_CHECK_MAX_COMPONENTS);
    int lk[TR_TYPE_CHECK_MAX_COMPONENTS * TR_TYPE_CHECK_MAX_COMPONENTS];
    int rc = tr_linking_numbers(c, lk, err);
    if (rc)
        return rc;
    for (int i = 0; i < c->ncomp; i++)
        for (int j = i + 1; j < c->ncomp; j++)
            tc->linking[tc->npairs++] = lk[i * c->ncomp + j];
    /* each component alone: a strand of one component passed through
     * another strand of the same one changes no linking number, and may
     * change that component's knot (a view of its vertices, no copy). One
     * that cannot be computed is left out, not the link's failure: the
     * name's check (tr_type_matches) does not use them */
    for (int k = 0; k < c->ncomp; k++) {
        size_t start[2] = {0, tr_comp_nv(c, k)};
        unsigned char closed = c->closed[k];
        tr_curve one = {.nv = start[1], .x = c->x + 3 * c->start[k], .ncomp = 1, .start = start, .closed = &closed};
        tr_error sub;
        tc->comp_known[k] = tr_knot_invariants_of(&one, &tc->comp[k], &sub) == TR_OK;
    }
    return 0;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

static void sorted_abs(const int *v, int n, int *out)
{
    for (int k = 0; k < n; k++)
        out[k] = abs(v[k]);
    qsort(out, (size_t)n, sizeof *out, cmp_int);
}

static void alexander_text(const tr_alexander *a, char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = 0;
    for (int k = 0; k <= a->span && used < size; k++)
        used += (size_t)snprintf(buf + used, size - used, "%s%lld", k ? " " : "", a->coef[k]);
}

int tr_type_matches(const tr_type_check *tc, const tr_table_entry *e, char *why, size_t whysize)
{
    why[0] = 0;
    if (tc->components != e->components) {
        snprintf(why, whysize, "%d component%s, %s has %d", tc->components, tc->components == 1 ? "" : "s", e->name,
                 e->components);
        return 0;
    }
    if (!e->is_link) {
        char got[512], want[512];
        alexander_text(&tc->inv.alexander, got, sizeof got);
        alexander_text(&e->alexander, want, sizeof want);
        if (!tr_alexander_equal(&tc->inv.alexander, &e->alexander)) {
            snprintf(why, whysize, "Alexander polynomial %s, %s's is %s", got, e->name, want);
            return 0;
        }
        if (tc->inv.alexander.determinant != e->determinant) {
            snprintf(why, whysize, "determinant %lld, %s's is %lld", tc->inv.alexander.determinant, e->name,
                     e->determinant);
            return 0;
        }
        /* a name stands for the knot and its mirror image (Rolfsen's and
         * KnotInfo's tables list one of the two), whose signature is the
         * opposite */
        if (e->has_signature && abs(tc->inv.signature) != abs(e->signature)) {
            snprintf(why, whysize, "signature %d, %s's is %d (or %d, its mirror image's)", tc->inv.signature,
                     e->name, e->signature, -e->signature);
            return 0;
        }
        return 1;
    }
    int a[TR_TABLE_MAX_PAIRS], b[TR_TABLE_MAX_PAIRS];
    sorted_abs(tc->linking, tc->npairs, a);
    sorted_abs(e->linking, e->npairs, b);
    if (tc->npairs != e->npairs || memcmp(a, b, (size_t)tc->npairs * sizeof *a)) {
        char got[128], want[128];
        size_t u = 0, w = 0;
        got[0] = want[0] = 0;
        for (int k = 0; k < tc->npairs; k++)
            u += (size_t)snprintf(got + u, sizeof got - u, "%s%d", k ? " " : "", a[k]);
        for (int k = 0; k < e->npairs; k++)
            w += (size_t)snprintf(want + w, sizeof want - w, "%s%d", k ? " " : "", b[k]);
        snprintf(why, whysize, "|linking numbers| %s, %s's are %s", got, e->name, want);
        return 0;
    }
    return 1;
}

int tr_type_is_mirror(const tr_type_check *tc, const tr_table_entry *e)
{
    return !e->is_link && e->has_signature && e->signature != 0 && tc->inv.signature == -e->signature;
}

void tr_type_describe(const tr_type_check *tc, char *buf, size_t bufsize)
{
    if (tc->components == 1) {
        char a[512];
        alexander_text(&tc->inv.alexander, a, sizeof a);
        snprintf(buf, bufsize, "Alexander polynomial %s, determinant %lld, signature %d", a,
                 tc->inv.alexander.determinant, tc->inv.signature);
        return;
    }
    size_t u = (size_t)snprintf(buf, bufsize, "%d components, linking numbers", tc->components);
    for (int k = 0; k < tc->npairs && u < bufsize; k++)
        u += (size_t)snprintf(buf + u, bufsize - u, " %d", tc->linking[k]);
    /* each component's determinant and signature ("?" where not known):
     * a component mirrored keeps its determinant, not its signature */
    if (u < bufsize)
        u += (size_t)snprintf(buf + u, bufsize - u, ", components' determinants and signatures");
    for (int k = 0; k < tc->components && u < bufsize; k++)
        u += tc->comp_known[k] ? (size_t)snprintf(buf + u, bufsize - u, " %lld/%d", tc->comp[k].alexander.determinant,
                                                  tc->comp[k].signature)
                               : (size_t)snprintf(buf + u, bufsize - u, " ?");
}

int tr_pd_type_matches(const tr_type_check *tc, const tr_pd *pd, tr_error *err)
{
    tr_alexander want;
    int want_sig = 0;
    if (tr_alexander_from_pd((const int(*)[4])pd->x, pd->n, &want, err) ||
        tr_signature_from_pd((const int(*)[4])pd->x, pd->n, &want_sig, err))
        return -1;
    return tc->components == 1 && tr_alexander_equal(&want, &tc->inv.alexander) && want_sig == tc->inv.signature;
}
