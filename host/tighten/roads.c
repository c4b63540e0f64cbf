/* The roads of tr_tighten (tighten.h): tries on one level (the shortest
 * result kicked off its local minimum), scouts on a route of levels (the
 * start again from other coarse counts, some inflated), and the shuffled
 * roads (the start walked by crankshaft moves, shuffle.h). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "curve/generate.h"
#include "curve/perturb.h"
#include "oracle/thickness.h"
#include "tighten/shuffle.h"
#include "tighten/tighten_internal.h"

/* --tries: road o->try_index starts from the shortest result so far moved
 * by a smooth displacement of at most TRY_AMPLITUDE of its thickness
 * (perturb.h) and scaled back to its thickness (basin hopping). Every strand
 * moves less than half the distance 2t between strands, so along the
 * straight path from the result no two strands meet: the knot is the same,
 * only the road differs. */
#define TRY_AMPLITUDE 0.9
int tt_other_road(const tt_opts *o, tr_curve *c, tr_error *err)
{
    if (c->ncst > 0)
        return tr_fail(err, TR_EINVAL, "--tries: %s has constraints; a clasp's ends on their planes leave it one road",
                       o->in);
    tr_thickness t0, t1;
    int rc = tr_thickness_measure(c, NULL, &t0, NULL, err);
    if (rc)
        return rc;
    tr_curve moved = {0};
    /* a coarse polygon bends at its vertices under the displacement: the
     * amplitude is halved until the thickness keeps half its value, so
     * that scaling back does not stretch the edges past what the engine
     * takes (a 72-gon trefoil lost 4.8 times its thickness at 0.9) */
    double amp = TRY_AMPLITUDE;
    for (int attempt = 0; attempt < 6; attempt++, amp *= 0.5) {
        tr_curve_free(&moved);
        uint64_t seed = (uint64_t)o->seed * 1000003u + (uint64_t)o->try_index;
        if ((rc = tr_curve_copy(&moved, c, err)) || (tr_curve_drop_lo(&moved), 0) ||
            (rc = tr_curve_perturb(&moved, amp * t0.thickness, seed, err)) ||
            (rc = tr_thickness_measure(&moved, NULL, &t1, NULL, err))) {
            tr_curve_free(&moved);
            return rc;
        }
        if (t1.thickness >= 0.5 * t0.thickness && isfinite(t1.thickness))
            break;
    }
    if (!(t1.thickness > 0 && isfinite(t1.thickness))) {
        tr_curve_free(&moved);
        return tr_fail(err, TR_EGEOMETRY, "--tries: road %d's start has no thickness", o->try_index + 1);
    }
    tt_scale_curve(&moved, t0.thickness / t1.thickness);
    tr_curve_free(c);
    *c = moved;
    return TR_OK;
}

/* --tries on a route of levels (--refine-to above the coarse count): the
 * local minimum a knot ends in is chosen on its coarse level, by the road
 * the first-order steps take there, and a kick smaller than the rope's
 * radius (other_road) does not leave it (5_2 from KnotPlot: four kicked roads
 * all ended at 50.4078, the TightKnot table has 49.484). Another coarse count
 * is another road from the same start: 4_1 from --n 90 ends at 45.13, from
 * 100, 110 and 128 near 42.2; 5_2 from 100 reaches 49.482. So road t >= 1
 * starts afresh from IN at the coarse count base * ROADS[t - 1].factor,
 * base being --n or else a quarter of the finest count (at least 64), some
 * roads from the start inflated by ROAD_INFLATE: a looser start has room to
 * slide before its strands meet, and takes another road (5_2 at --n 100:
 * 50.4077 from thickness 1, 49.4822 from KnotPlot's own 1.48). The roads
 * listed first are those that found the table's minimum where others did
 * not: 5_2 (1, inflated), 7_4 (1: 64.82 at 114 vertices, the others 64.88 to
 * 65.56), 6_2 (1.5 and 0.6: 57.22 and 57.23, the others 57.6 to 58.3); past
 * the list the factors repeat, 5 % larger each round. */
static const struct {
    double factor;
    int inflated;
} ROADS[] = {{1.0, 1},  {1.0, 0},  {1.5, 0},  {0.6, 0},  {1.25, 0}, {0.8, 1},  {0.8, 0},
             {0.67, 0}, {1.12, 0}, {0.9, 0},  {1.75, 0}, {1.37, 0}, {1.25, 1}, {1.5, 1}};
#define ROAD_COUNT ((int)(sizeof ROADS / sizeof ROADS[0]))
#define ROAD_INFLATE 1.5
/* Scouting: the local minimum is chosen on the coarse level, and a coarse
 * level costs a few seconds where the route to the finest count costs
 * minutes, so with --tries on a route of levels every road stops at its
 * coarse level, in this share of the time, and only the shortest of them is
 * refined. Measured on the KnotPlot starts
 * (bench/notes/2026-11-25-batch-8-crossings-scouts.md): 6_2 at N =
 * 407, ten scouts in 101 s, the shortest (152 vertices, 57.22 where the
 * others ended at 57.6 to 58.3) refined in 104 s to 57.0440, against 57.8283
 * for three full roads in 200 s; 7_4 at 459: 64.2908 against 65.1461. */
/* (TT_SCOUT_SHARE, tighten_internal.h: 0.5) */

int tt_multi_level(const tt_opts *o) { return o->refine_to > 0 && !o->resume && o->start; }

long tt_road_coarse_n(const tt_opts *o, int t)
{
    long base = o->n > 0 ? o->n : (o->refine_to / 4 > 64 ? o->refine_to / 4 : 64);
    double f = ROADS[(t - 1) % ROAD_COUNT].factor * (1.0 + 0.05 * (double)((t - 1) / ROAD_COUNT));
    long n = lround((double)base * f);
    if (n >= o->refine_to)
        n = o->refine_to / 2;
    return n < 16 ? 16 : n;
}

/* Whether every component of c has the --refine-to count (0: no such count). */
int tt_at_refine_n(const tt_opts *o, const tr_curve *c)
{
    if (o->refine_to <= 0)
        return 0;
    for (int k = 0; k < c->ncomp; k++)
        if ((long)tr_comp_nv(c, k) != o->refine_to)
            return 0;
    return 1;
}

/* A scout the engine gave more vertices than --refine-to asks for in some
 * component (a short knot at small N: the inflated roads add vertices),
 * resampled to that N into *out instead of refused, and at thickness 1
 * again (fewer vertices cut the tight polygon's corners; a constrained rope
 * as it is). On the automatic roads every scout goes to the fine count
 * this way, along a spline through its vertices: the rope stays tight, and
 * the second-order solver takes it at that count first (tighten.c,
 * open_start), where the level loop's low-pass doublings bent it (the
 * rope rescaled to thickness 1 7 % longer: 9_2's scout 78.13 at N 508 came
 * to the last level at 83.93) and, with the first-order steps between,
 * left it longer than the scout at the time limit (9_8: 81.00 at N 476,
 * 85.79 at 3888; 9_7 80.71, 81.80); 9_3's scout of 79.36 at N 480 so:
 * 79.3079 at 3809 in 112 s of the solver. Returns 1 with *out filled; 0
 * when nothing is resampled, or (said on stderr) when it cannot be: the
 * scout is refined as it is. */
int tt_scout_at_refine_n(const tt_opts *o, const tr_curve *scout, tr_curve *out)
{
    int finer = 0, adds = 0;
    size_t *per = malloc((size_t)scout->ncomp * sizeof *per);
    for (int k = 0; per && k < scout->ncomp; k++) {
        per[k] = tr_comp_nv(scout, k);
        if ((long)per[k] > o->refine_to || (o->refine_auto && (long)per[k] != o->refine_to)) {
            adds |= (long)per[k] < o->refine_to;
            per[k] = (size_t)o->refine_to;
            finer = 1;
        }
    }
    tr_error err;
    tr_thickness th;
    tr_deadline bound = tt_bound(o);
    int rc = finer ? tr_resample_within(scout, per, adds, &bound, out, &err) : TR_OK;
    free(per);
    if (rc != TR_OK)
        tt_note(o, TR_TIGHTEN_WARNING, "warning: the scout could not be resampled to N %ld: %s", o->refine_to,
                err.msg);
    if (!finer || rc != TR_OK)
        return 0;
    /* the added vertices back at the scout's strut distance, as --n does */
    if (adds)
        tt_keep_strut_distance(scout, out, &bound);
    /* and only a coarsened scout is scaled to thickness 1: a spline through
     * a tight polygon bends past MinRad where the polygon's turning angles
     * are uneven, and scaled for that, 9_7's scout (80.69 at N 480) came to
     * the solver at 115.6 and 9_8's at 107; as --n leaves it (MinRad a
     * little under 1 at a few vertices), the solver takes it from 80.68 */
    if (!adds && out->ncst == 0 && tr_thickness_measure(out, NULL, &th, NULL, &err) == TR_OK && th.thickness > 0 &&
        isfinite(th.thickness))
        tt_scale_curve(out, 1.0 / th.thickness);
    return 1;
}

double tt_road_inflate(int t) { return ROADS[(t - 1) % ROAD_COUNT].inflated ? ROAD_INFLATE : 1.0; }

/* --shuffles: another kind of road, for knots whose every coarse road
 * above ends in the same local minimum. Smooth starts at other counts, kicks
 * under the rope's radius and random walks of the rope inflated 1.3 and 2
 * times at fixed thickness all left 8_4 at 76.98-77.7 (the TightKnot table:
 * 72.03): the start's conformation, not its discretisation, picks the
 * basin. Ours had writhe 1.95 where the table's has 1.62 (in absolute value;
 * ACN 15.4 against 14.6), so the way out goes through other conformations.
 * A shuffled road makes one: the start, resampled along a spline to
 * SHUFFLE_N vertices per component, is inflated (4 times in the first
 * recipe below: the rope is then thin against the knot's size) and walked by `moves`
 * crankshaft moves that keep its thickness at least 1 and the knot type
 * (engine/shuffle.h), which loses the start's shape; then
 * `anneal` more moves, each kept only if the thickness stays at least
 * `ratchet` times the largest reached (a ratchet: the walk compacts the
 * knot again, to ropelength about 110-120 for 8_4, where the engine takes
 * over in seconds). The same --seed and road number, the same start.
 * Measured (bench/notes/2026-11-27-shuffled-roads.md): 8_4 from KnotPlot, four such
 * starts (made by hand, seeds 1-4) tightened at --n 128 for 25 s: 71.67
 * (N 280), 77.13, 77.02, 76.90; the first refined to N = 514: 71.5865,
 * writhe 1.635. --scale --refine-to N --time-limit 240 --tries 10
 * --shuffles 5: 8_4 71.5869 (table 72.0301), 8_11 72.9185 (73.5029), and
 * 7_1, 7_6, 8_7, 8_21 below the table, all from shuffled roads, where every
 * road of before ended above; 8_1, 8_5, 8_8, 8_12, 8_13, 8_17 stayed above
 * (8_12 and 8_17 went below with --shuffles 9 --seed 2, 8_5 and 8_13 with
 * --shuffles 9 --seed 3, 8_8 with --tries 12 --shuffles 11 --seed 5; 8_1
 * with none tried). */
#define SHUFFLE_N 96
typedef struct shuffle_recipe {
    double inflate;
    long moves, anneal;
    double ratchet;
} shuffle_recipe;
/* The shuffled roads take these in turn. The second walks a thinner rope
 * (inflated 6 times) and compacts it twice as long with a tighter ratchet
 * (0.995): a more compact start, which reached other basins. Measured
 * (bench/notes/2026-11-27-shuffle-recipes.md): 8_1 and 8_2 ended above the table
 * from every road of the first recipe over five seeds (+0.045 % and
 * +0.164 %, the same conformations each time); with the second,
 * --tries 8 --shuffles 7 --seed 11, 8_1 71.0372 (road 3) and 8_2 71.4304
 * (road 8), both below the table's 71.0484 and 71.4327. Recipes with
 * SHUFFLE_N 128 or 64 were not kept: the crumpled polygon's edges could not
 * be made equal for the engine (the road skipped).
 * Since the oracle's gate made a move six times cheaper (shuffle.c), the first
 * recipe and the compaction below anneal as long and as tight as the second
 * (200 000 moves at 0.995; 4-6 s for a nine-crossing knot): a scout's engine
 * then starts near its basin. 9_7 made by name: the compaction of before
 * (100 000 at 0.98) left ropelength 115.2, the first recipe's 129.8, the
 * second's 93.2; a start at 115 tightened at N = 200 for 25 s reached 86.6,
 * the one at 93 81.5 in 10 s; now the compaction leaves 94.0 and the first
 * recipe 94 to 96 (bench/notes/2026-11-30-shuffle-gate.md). */
static const shuffle_recipe SHUFFLE_RECIPES[] = {
    {4.0, 20000, 200000, 0.995},
    {6.0, 20000, 200000, 0.995},
};

/* The start compacted, its conformation kept: the second phase of the
 * recipes above alone, at the start's own scale (the automatic roads'
 * first scout, tighten.c): inflated by a hair only, as the walk's gate is
 * thickness 1 and a rope scaled to thickness 1 measures 1 - 1e-16. */
static const shuffle_recipe COMPACT_RECIPE = {1.01, 0, 200000, 0.995};

int tt_shuffle_start(const tt_opts *o, tr_curve *c, tr_error *err)
{
    if (c->ncst > 0)
        return tr_fail(err, TR_EINVAL, "--shuffles: %s has constraints; a clasp's ends on their planes cannot be "
                                       "shuffled", o->in);
    size_t *per = malloc((size_t)c->ncomp * sizeof *per);
    if (!per)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    for (int k = 0; k < c->ncomp; k++)
        per[k] = SHUFFLE_N;
    tr_curve r;
    int rc = tr_resample_smooth(c, per, &r, err);
    free(per);
    if (rc)
        return rc;
    tr_thickness t;
    uint64_t seed = (uint64_t)o->seed * 1000003u + (uint64_t)o->try_index;
    if ((rc = tr_thickness_measure(&r, NULL, &t, NULL, err)))
        goto out;
    if (!(t.thickness > 0 && isfinite(t.thickness))) {
        rc = tr_fail(err, TR_EGEOMETRY, "--shuffles: %s resampled to %d vertices has thickness %g", o->in, SHUFFLE_N,
                     t.thickness);
        goto out;
    }
    const size_t nrecipes = sizeof SHUFFLE_RECIPES / sizeof *SHUFFLE_RECIPES;
    const shuffle_recipe *sr = o->compacted ? &COMPACT_RECIPE : &SHUFFLE_RECIPES[(size_t)o->shuffle_index % nrecipes];
    tt_scale_curve(&r, sr->inflate / t.thickness);
    tr_deadline bound = tt_bound(o);
    if (o->compacted && o->compact_until > 0 && (bound.at == 0 || o->compact_until < bound.at))
        bound.at = o->compact_until;
    rc = tr_curve_shuffle(&r, sr->moves, 1.0, 0.0, seed, &bound, NULL, err);
    if (!rc)
        rc = tr_curve_shuffle(&r, sr->anneal, 1.0, sr->ratchet, seed + 7, &bound, NULL, err);
    /* a compaction the bound or a signal stops is a start all the same
     * (every kept move kept the rope thick and the knot), and the first
     * road of the automatic ones has no other: the run goes on with it,
     * and stops at once, keeping it (Ctrl-C in the first seconds once
     * left no curve at all) */
    if (rc == TR_EINTERRUPTED && o->compacted)
        rc = TR_OK;
    if (rc || (rc = tr_thickness_measure(&r, NULL, &t, NULL, err)))
        goto out;
    tt_scale_curve(&r, 1.0 / t.thickness);
out:
    if (rc) {
        tr_curve_free(&r);
        return rc;
    }
    tr_curve_free(c);
    *c = r;
    return TR_OK;
}

/* A scout of the automatic roads starts coarse and climbs levels: its
 * shuffled or compacted rope (SHUFFLE_N vertices, edges about 1) is
 * resampled to edges of about SCOUT_EDGE, not start.c's 0.5, and refined
 * by the level loop to SCOUT_LEVELS times that count within its share.
 * At the densified count (edges 0.5, N ~ 200) the first-order steps crawl
 * and jam and the second-order solver crawls after them (9_15: 90.0 after
 * 18 s, 87.24 at the share's end; the solver given 60 s more, 83.17 and
 * still 1e-4 a step), while coarser levels slide before they are refined.
 * Measured on one core, 25 s a scout, the same shuffled starts
 * (bench/notes/2026-11-30-scout-levels.md): 9_15 87.24 / 87.30 ->
 * 82.21 / 86.39, 9_7 81.63 -> 80.69, 9_3 79.64 / 79.67 -> 79.36 / 79.36
 * (N 200 -> 480); from 150 to 600 82.81, from 200 to 400 84.91, from 250
 * to 500 86.06. */
#define SCOUT_EDGE 0.8
#define SCOUT_LEVELS 4

void tt_scout_levels(tt_opts *o)
{
    if (!o->refine_auto)
        return;
    o->coarse_edge = SCOUT_EDGE;
    o->scout_levels = SCOUT_LEVELS;
}
