/* The start of a tr_tighten road (tighten.h): the route a loose start
 * takes, the centring of a start far from the origin, and the start made
 * ready for the engine: resampled (n), scaled (scale), densified when too
 * coarse for thickness 1, its open ends checked, shuffled or inflated as
 * its road says (roads.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curve/generate.h"
#include "oracle/thickness.h"
#include "tighten/tighten_internal.h"

/* A start at thickness 1 (after --scale) whose edges are longer than the
 * engine takes (a KnotPlot start of 101 vertices: edges of 1.31) is
 * resampled along a spline through its vertices to edges of about
 * COARSE_EDGE, and scaled to thickness 1 again (the spline changes it a
 * little), instead of being refused: the user asked for a rope, not for a
 * vertex count. --refine-to, if given, caps the count as long as the edges
 * stay below MAX_COARSE_EDGE. */
#define COARSE_EDGE 0.5
#define MAX_COARSE_EDGE 0.9
static int densify_coarse(const tt_opts *o, tr_curve *c, tr_error *err)
{
    for (int pass = 0; pass < 3; pass++) {
        int coarse = 0;
        size_t *per = malloc((size_t)c->ncomp * sizeof *per);
        if (!per)
            return tr_fail(err, TR_ENOMEM, "out of memory");
        for (int k = 0; k < c->ncomp; k++) {
            size_t nv = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
            double len = tr_comp_length(c, k);
            per[k] = nv;
            if (len / (double)ne < MAX_COARSE_EDGE)
                continue;
            coarse = 1;
            size_t want = (size_t)ceil(len / (o->coarse_edge > 0 ? o->coarse_edge : COARSE_EDGE)), least = (size_t)ceil(len / MAX_COARSE_EDGE) + 1;
            if (o->refine_to > 0 && want > (size_t)o->refine_to)
                want = (size_t)o->refine_to > least ? (size_t)o->refine_to : least;
            per[k] = want > nv ? want : nv + 1;
        }
        if (!coarse) {
            free(per);
            return TR_OK;
        }
        /* within the call's bound: the densified count is len / COARSE_EDGE
         * a component, and at 10^6 vertices and more a resampling or a
         * measure is seconds */
        tr_curve r;
        tr_deadline bound = tt_bound(o);
        tr_thickness_opts bounded = {.bound = &bound};
        int rc = tr_resample_within(c, per, 1, &bound, &r, err);
        free(per);
        if (rc)
            return tr_fail_wrap(err, rc, "%s (densified)", o->in);
        tr_curve_free(c);
        *c = r;
        tr_thickness t;
        if ((rc = tr_thickness_measure(c, &bounded, &t, NULL, err)))
            return tr_fail_wrap(err, rc, "%s (resampled)", o->in);
        if (!(t.thickness > 0 && isfinite(t.thickness)))
            return tr_fail(err, TR_EGEOMETRY, "%s: resampled along a spline, it has thickness %g", o->in,
                           t.thickness);
        tt_scale_curve(c, 1.0 / t.thickness);
        /* a shuffled road's rope is ours, coarse by design: no warning */
        if (!o->shuffled)
            tt_note(o, TR_TIGHTEN_WARNING, "%s: too coarse for thickness 1; resampled along a spline to %zu vertices",
                    o->in, c->nv);
    }
    return TR_OK;
}

/* Resamples c along a spline so that no component's edges are INFLATED_EDGE
 * or longer, with as few vertices as that takes (none added where they are
 * shorter already). */
#define INFLATED_EDGE 0.97
static int grow_count(tr_curve *c, double edge, const tr_deadline *bound, tr_error *err)
{
    size_t *per = malloc((size_t)c->ncomp * sizeof *per);
    if (!per)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    int grow = 0;
    for (int k = 0; k < c->ncomp; k++) {
        size_t nv = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
        double len = tr_comp_length(c, k);
        per[k] = nv;
        if (len / (double)ne >= edge) {
            per[k] = (size_t)ceil(len / edge) + (nv - ne) + 1;
            grow = 1;
        }
    }
    tr_curve r;
    int rc = grow ? tr_resample_within(c, per, 1, bound, &r, err) : TR_OK;
    free(per);
    if (grow && rc == TR_OK) {
        tr_curve_free(c);
        *c = r;
    }
    return rc;
}

/* A spline through a tight polygon bulges out between its vertices, so
 * strands that touched come closer than before (1.99835 for the 2 x 40 Hopf
 * link refined to 80): the added vertices are scaled back to the strut
 * distance of the curve they were resampled from, which ropelength does not
 * see. Constraint planes are fixed, so a constrained rope is left as it is;
 * a measure that fails or the bound leave it too. */
void tt_keep_strut_distance(const tr_curve *from, tr_curve *to, const tr_deadline *bound)
{
    tr_thickness before, after;
    tr_thickness_opts bounded = {.bound = bound};
    tr_error err;
    if (to->ncst == 0 && !tr_thickness_measure(from, &bounded, &before, NULL, &err) &&
        !tr_thickness_measure(to, &bounded, &after, NULL, &err) && isfinite(before.dcsd) &&
        after.dcsd < before.dcsd && after.dcsd > 0.5 * before.dcsd)
        tt_scale_curve(to, before.dcsd / after.dcsd);
}

/* Ropelength does not see where a knot is, but the engine's doubles do: a
 * trefoil moved to 1e6 tightened to 32.889 (KKT residual 0.45) where at
 * the origin it reaches 32.837 (1e-4), its differences of coordinates
 * losing six digits. So a start whose box does not hold the origin along an
 * axis is moved by the middle of its extent there (as the oracle measures,
 * curve.h), and the tight knot is written about the origin (said in its
 * comments). A box that holds the origin is left bit for bit as it is; a
 * constrained rope (a clasp) stays on its planes. */
void tt_start_shift(tt_opts *o)
{
    memset(o->shift, 0, sizeof o->shift);
    const tr_curve *c = o->start;
    if (o->resume || !c || !o->centre)
        return;
    if (c->ncst == 0 && c->nv > 0)
        for (int a = 0; a < 3; a++) {
            double lo = c->x[a], hi = c->x[a];
            for (size_t i = 1; i < c->nv; i++) {
                lo = fmin(lo, c->x[3 * i + (size_t)a]);
                hi = fmax(hi, c->x[3 * i + (size_t)a]);
            }
            if (lo > 0 || hi < 0)
                o->shift[a] = 0.5 * lo + 0.5 * hi;
        }
}

static void shift_curve(tr_curve *c, const double shift[3])
{
    for (size_t i = 0; i < c->nv; i++)
        for (int a = 0; a < 3; a++)
            c->x[3 * i + (size_t)a] -= shift[a];
}

/* Makes the road's start into c from the call's start, resampled with --n and scaled with
 * --scale, and checks that it can be tightened: its open ends are held and
 * its thickness is at a scale the engine can work in. */
int tt_read_start(const tt_opts *o, tr_curve *c, tr_error *err)
{
    const char *in = o->in;
    int rc;
    if (o->road_from) {
        /* a later road of --tries: the shortest result so far, moved off
         * its local minimum (it is at thickness 1 and at the run's N) */
        if ((rc = tr_curve_copy(c, o->road_from, err)) || (!o->road_as_is && (rc = tt_other_road(o, c, err))))
            tr_curve_free(c);
        return rc;
    }
    if (!o->start)
        return tr_fail(err, TR_EINVAL, "no start curve");
    rc = tr_curve_copy(c, o->start, err);
    if (rc != TR_OK)
        return rc;
    if (c->ncst == 0)
        shift_curve(c, o->shift);
    /* the start's measures are within the command's bound: at 10^7
     * vertices (--n) each is tens of seconds */
    tr_deadline bound = tt_bound(o);
    tr_thickness_opts bounded = {.bound = &bound};
    if (o->shuffled && (rc = tt_shuffle_start(o, c, err))) {
        tr_curve_free(c);
        return rc;
    }
    if (o->n > 0) {
        size_t *per = malloc((size_t)c->ncomp * sizeof *per);
        tr_curve r;
        if (!per) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory");
        } else {
            /* Adding vertices on the old straight edges would keep the
             * polygon's corners: MinRad falls like 1/N and a smooth
             * start is refused as bent too tight. Along a spline
             * through the vertices the start stays the smooth curve. */
            int adds = 0;
            for (int k = 0; k < c->ncomp; k++) {
                per[k] = (size_t)o->n;
                adds |= per[k] > c->start[k + 1] - c->start[k];
            }
            rc = tr_resample_within(c, per, adds, &bound, &r, err);
            free(per);
            if (rc == TR_EINTERRUPTED)
                rc = tr_fail(err, TR_EINTERRUPTED, "%s resampled to %ld vertices: %s", in, o->n,
                             tr_deadline_passed(&bound) == 2 ? "stopped by a signal" : "the time limit came");
            if (rc == TR_OK && adds)
                tt_keep_strut_distance(c, &r, &bound);
            if (rc == TR_OK) {
                tr_curve_free(c);
                *c = r;
            }
        }
    }
    /* Ropelength is scale free: --scale takes a start at another scale
     * (a tight knot from another code at thickness 0.99995, a file in
     * its own units) to the rope's radius 1. Constraint planes and points
     * are scaled with it about the origin (scale_curve), so a clasp's ends
     * stay on their planes (KnotPlot's simple_clasp is at thickness 0.5). */
    /* The oracle looks at the start first: a curve through itself has
     * no thickness at all, and one at a scale like 1e+-300 would lose
     * the engine's squared distances to under- or overflow (the oracle
     * measures it in a rescaled frame, curve.h). */
    /* An open rope with a free end shortens by pulling that end
     * through: it comes out untied. Its ends must be held. */
    for (int k = 0; rc == TR_OK && k < c->ncomp; k++) {
        size_t ends[2] = {c->start[k], c->start[k + 1] - 1};
        for (int q = 0; rc == TR_OK && !c->closed[k] && q < 2; q++)
            if (!c->vcst || c->vcst[ends[q]] < 0)
                rc = tr_fail(err, TR_EGEOMETRY,
                             "%s: component %d is open and its %s end (vertex %zu) is free: tightening would "
                             "pull it through and untie the rope; hold both ends with a constraint (a "
                             "'# Constraint 1 Plane 0 0 1 6' comment and '# Cst: 1' after the end vertex, "
                             "as tightrope make clasp writes)",
                             in, k, q ? "last" : "first", ends[q] - c->start[k]);
    }
    tr_thickness t0;
    if (rc == TR_OK && (rc = tr_thickness_measure(c, &bounded, &t0, NULL, err)))
        tr_fail_wrap(err, rc, "%s", in);
    if (rc == TR_OK && !o->scale && tr_curve_scale_exponent(c))
        rc = tr_fail(err, TR_EGEOMETRY,
                     "%s has thickness %.3g, too far from 1 to tighten in its own units (squared "
                     "distances would %s); --scale scales a start to thickness 1",
                     in, t0.thickness, tr_curve_scale_exponent(c) > 0 ? "overflow" : "underflow");
    /* a shuffled start is ours, at thickness 1 before --n resampled it: it
     * is brought back to thickness 1 as --scale would */
    if (rc == TR_OK && (o->scale || o->shuffled)) {
        if (!(t0.thickness > 0 && isfinite(t0.thickness)))
            rc = tr_fail(err, TR_EGEOMETRY, "--scale: %s has thickness %g; no scale makes it a rope", in,
                         t0.thickness);
        else if (!isfinite(1.0 / t0.thickness))
            rc = tr_fail(err, TR_EGEOMETRY, "--scale: %s has thickness %g, too thin for the factor 1/%g to be a "
                         "double; scale the file up first", in, t0.thickness, t0.thickness);
        if (rc == TR_OK)
            tt_scale_curve(c, 1.0 / t0.thickness);
        /* also after --n: a count too coarse for thickness 1 (a road of
         * --tries at a count below the start's length) is raised */
        if (rc == TR_OK)
            rc = densify_coarse(o, c, err);
    }
    /* an inflated road's edges grow with it: the count grows just enough
     * to keep them below INFLATED_EDGE (a coarse road is what it is for:
     * 5_2 from 100 vertices at KnotPlot's thickness 1.48, edges 0.97,
     * reaches 49.482; densified to edges of 0.5 it ends at 50.4079) */
    if (rc == TR_OK && o->inflate != 1.0) {
        tt_scale_curve(c, o->inflate);
        tr_deadline bound = tt_bound(o);
        rc = grow_count(c, INFLATED_EDGE, &bound, err);
    }
    if (rc != TR_OK)
        tr_curve_free(c);
    return rc;
}

/* The route for a loose start given without route flags (no --n, no
 * --refine-to): first-order steps need ~N^2 of them, so a loose start of
 * N >= AUTO_ROUTE_MIN_N vertices per component is tightened from N / 4 and
 * refined back to N, as `--n N/4 --refine-to N` would (the N = 400 trefoil
 * from `make torus 2 3`: 32.748648 in 5 s that way, 40.59 at N = 400
 * directly). Loose: fewer struts within 1e-3 of the shortest than a tenth
 * of the vertices (a tight knot has more than one per vertex). Closed,
 * unconstrained curves, or clasps (below), with the same N per component
 * only; --n N keeps the
 * start's N. A start that cannot be read is left to read_start to report. */
#define AUTO_ROUTE_MIN_N 200
/* A loose clasp (open ropes whose ends are held) of more than
 * CLASP_COARSE_N vertices per rope starts from CLASP_COARSE_N instead: the
 * first-order steps and the polish tighten a clasp there (13 s at 2 x 100)
 * but not at 2 x 1000, and every refined level goes to the second-order
 * solver (level_loop.c, is_solver_level). A clasp cannot be scaled, so it
 * is also loose at thickness above 1 (`make clasp`: 1.5, with each arch's
 * whole semicircle at the shortest distance from the other's tip, so the
 * strut count says nothing). */
#define CLASP_COARSE_N 100
/* The automatic roads (issue 47: one plain command finds the good basin).
 * A loose start on the route above, given a time limit T and no --tries or
 * --shuffles, is scouted by one road per AUTO_ROAD_SECONDS of T (at least
 * two from T = AUTO_ROADS_MIN_T on, at most AUTO_ROADS_MAX; under it one
 * road has T, as before): the first the start compacted (its own
 * conformation), the others shuffled (the scouts stop at half of T:
 * tighten.c), and the
 * shortest scout is refined to AUTO_N_PER_LENGTH vertices per unit of its
 * ropelength instead of the start's count. Why: a start made from notation
 * (`make knot`, a braid closure, 3.5 times longer than tight) slides into
 * the basin its diagram lies in; the shuffled roads leave it. 5_2 made by
 * name (848 vertices), T = 200 s at load 5: the three unshuffled roads ended
 * at 58.36, 59.88, 58.37, the shuffled ones at 49.53, 49.54, 54.85, and
 * the shortest refined to 2400 at 49.4658, below KnotInfo's 49.4701; the
 * plain route of before ended at 56.17 in 45 s. The fine count: the
 * polygon's excess over its limit goes as c L^2 / N^2 with c ~ 0.85 (the
 * trefoil's 914 / N^2 over L = 32.74), so N = 48 L leaves ~4e-4, below
 * the 4 decimals KnotInfo gives (the trefoil at 32.7433 against its
 * 32.7436). A scout has AUTO_ROAD_SECONDS / 2: a shuffle costs ~10 s of
 * CPU for a nine-crossing knot (120 000 crankshaft moves, each checked by
 * the oracle), and at 25 s a road 9_1 (T = 300, load 5) got 3 scouts in
 * its half, two of them finished (86.0, 87.6), the refinement 75.632
 * against KnotInfo's 75.546. */
#define AUTO_ROAD_SECONDS 50.0
#define AUTO_ROADS_MIN_T 50.0
#define AUTO_ROADS_MAX 16
#define AUTO_N_PER_LENGTH 48.0
long tt_auto_refine_n(const tt_opts *o, double scout_ropelength)
{
    /* refine_to counts the vertices of each component: a link's length is
     * shared among its components */
    int ncomp = o->start && o->start->ncomp > 0 ? o->start->ncomp : 1;
    /* not the provisional count (the start's): a start's vertices are its
     * drawing's, not the knot's (9_3 from KnotInfo's PD code, drawn with
     * 12 063 vertices, was refined to them from a scout of 460 and stopped
     * far from tight at the time limit) */
    if (!isfinite(scout_ropelength))
        return o->refine_to;
    long n = lround(AUTO_N_PER_LENGTH * scout_ropelength / ncomp);
    return n < 64 ? 64 : n;
}

static void choose_roads(tt_opts *o)
{
    if (!o->auto_roads || !(o->time_limit > 0) || o->start->ncst > 0)
        return;
    if (o->time_limit < AUTO_ROADS_MIN_T)
        return; /* one road has the whole time */
    long k = lround(floor(o->time_limit / AUTO_ROAD_SECONDS));
    if (k < 2)
        k = 2;
    if (k > AUTO_ROADS_MAX)
        k = AUTO_ROADS_MAX;
    o->tries = k;
    o->shuffles = k - 1; /* one road from the start as it is */
    o->refine_auto = 1;
    /* the second-order solver in the polish's place at every road's finest
     * level and on every level from SOLVER_LEVEL_MIN_N of the refinement
     * (--newton): the spline's overshoot at the refined levels, rescaled
     * to thickness 1, left 9_40 (made by name, T = 300 at load 7) at 90.3
     * for the last level and 81.9019 at 3930 vertices; with it 81.6367
     * (KnotInfo: 81.6474) */
    if (!o->no_newton)
        o->newton = 1;
}

void tt_choose_route(tt_opts *o)
{
    if (o->resume || o->n > 0 || o->refine_to > 0 || !o->start || !o->auto_route)
        return;
    const tr_curve c = *o->start; /* read only */
    tr_error err;
    size_t nper = tr_comp_nv(&c, 0);
    int simple = c.ncst == 0, clasp = c.ncst > 0;
    for (int k = 0; k < c.ncomp; k++) {
        simple = simple && c.closed[k] && tr_comp_nv(&c, k) == nper;
        clasp = clasp && !c.closed[k] && tr_comp_nv(&c, k) == nper;
    }
    tr_thickness th;
    tr_strut_list sl = {0};
    tr_thickness_opts to = {.strut_rel_tol = 1e-3};
    if ((simple || (clasp && nper > CLASP_COARSE_N)) && nper >= AUTO_ROUTE_MIN_N &&
        !tr_thickness_measure(&c, &to, &th, &sl, &err) && th.thickness > 0 &&
        ((double)sl.n < 0.1 * (double)c.nv || (clasp && th.thickness > 1.0 + 1e-3))) {
        o->n = clasp ? CLASP_COARSE_N : (long)(nper / 4 > 64 ? nper / 4 : 64);
        o->refine_to = (long)nper;
        if (!clasp)
            choose_roads(o);
        /* the start's N is the run's goal, as if --refine-to N had been
         * given (usage.md): a clasp of 2 x 3200 whose refinement the
         * solver did not take came back at 2 x 800 with exit 0, and so
         * did a loose knot stopped by --steps at its coarse N. The
         * automatic roads choose their N themselves, from the scouts
         * (tt_auto_refine_n): a choice, not the caller's goal. */
        o->refine_given = o->refine_implied = !o->refine_auto;
        if (o->refine_auto) {
            tt_note(o, TR_TIGHTEN_INFO, "%s is loose (%zu struts within 1e-3 of the shortest, %zu vertices)",
                    o->in, sl.n, c.nv);
            tt_note(o, TR_TIGHTEN_INFO,
                    "the automatic roads for a time limit of %g s: up to %ld scouts in half of it (the start "
                    "compacted, then %ld shuffled), the shortest refined to %.0f vertices per unit of its "
                    "ropelength%s (--tries or --shuffles choose the roads yourself)",
                    o->time_limit, o->tries, o->shuffles, AUTO_N_PER_LENGTH,
                    o->newton ? " with the second-order solver" : "");
        } else
            tt_note(o, TR_TIGHTEN_INFO,
                    "%s is loose (%zu struts within 1e-3 of the shortest, %zu vertices): "
                    "tightening from %ld vertices and refining to %zu (--n %zu keeps them all)",
                    o->in, sl.n, c.nv, o->n, nper, nper);
    }
    tr_strut_list_free(&sl);
}
