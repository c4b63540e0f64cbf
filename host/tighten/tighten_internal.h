/* What the tightening layer's files share (not its interface: tighten.h):
 * one road's options, as the call's options (tighten.h) make them for the
 * road, and the start's preparation (start.c) and the roads (roads.c). */
#ifndef TR_TIGHTEN_INTERNAL_H
#define TR_TIGHTEN_INTERNAL_H

#include "curve/curve.h"
#include "tighten/tighten.h"
#include "util/clock.h"
#include "util/error.h"

/* The call's options, made effective (a resumed run's goals, the route
 * chosen), and what makes one road of it. */
typedef struct tt_opts {
    const tr_tighten_options *call; /* the caller's: callbacks, cancel flag */
    const char *in;                 /* the start's name in messages */
    const tr_curve *start;          /* NULL: resumed from a checkpoint */
    const char *out, *ckpt, *resume, *device;
    long n, refine_to, steps, device_from, tries, seed, shuffles;
    int try_index; /* which of the tries this road is (0: the start as given) */
    double inflate; /* tries: the start scaled up by this after scale (1: not) */
    const tr_curve *road_from; /* tries: the shortest result so far, this road's start */
    int road_as_is; /* road_from is refined as it is, not moved off its minimum */
    int shuffled; /* shuffles: this road starts from the start shuffled (tt_shuffle_start) */
    int shuffle_index; /* which of the shuffled roads (0: the first), so which recipe */
    int compacted; /* with shuffled: the start compacted only, not inflated and walked first */
    /* a start too coarse for thickness 1 is resampled to edges of about
     * this (0: start.c's COARSE_EDGE) */
    double coarse_edge;
    /* a scout of the automatic roads: refined by the level loop to this
     * many times its start's count per component (0: its coarse level only;
     * roads.c, SCOUT_LEVELS) */
    int scout_levels;
    int roads;    /* roads in all, for the progress callback */
    double target, residual, time_limit, ckpt_every;
    /* time_limit as a clock time (tr_clock_seconds; 0: none): the hard
     * bound of the whole call, which the roads' shares divide */
    double bound_at;
    /* the compaction of a compacted road stops here too (0: none), and
     * goes on with what it reached (roads.c) */
    double compact_until;
    int residual_given; /* the default residual is a stopping rule, not a goal */
    int refine_given;   /* refine_to given (or taken from a checkpoint): a goal */
    int refine_implied; /* the goal is the loose start's own N (tt_choose_route) */
    /* subtracted from the start's coordinates (tt_start_shift): a knot far
     * from the origin is tightened about it (0: as it is) */
    double shift[3];
    int no_polish, newton, no_newton, scale, kkt; /* kkt -1: up to TR_TIGHTEN_KKT_AUTO_MAX_N */
    int auto_route, centre;
    /* no tries or shuffles given: a loose start on the automatic route with
     * a time limit takes the automatic roads (tt_choose_route) */
    int auto_roads;
    /* the automatic roads: refine_to is provisional until the scouts are
     * done, then chosen from the shortest scout's length (tt_auto_refine_n) */
    int refine_auto;
    /* a resumed run: the checkpoint's knot type, taken as the engine opens
     * it (knot_type.h), for the result's check; NULL otherwise */
    struct tt_knot_type *resume_type;
} tt_opts;

/* A note to the caller (tighten.h, note), printf-style. */
void tt_note(const tt_opts *o, int kind, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The call's hard bound: its time limit and the cancel flag. */
tr_deadline tt_bound(const tt_opts *o);

/* Whether the cancel flag is raised. */
int tt_cancelled(const tt_opts *o);

/* Scales the curve about the origin by f, constraints included. */
void tt_scale_curve(tr_curve *c, double f);

/* start.c: the route for a loose start (n and refine_to from it), the
 * centring shift, and a road's start made from the call's start. */
void tt_choose_route(tt_opts *o);
void tt_start_shift(tt_opts *o);
int tt_read_start(const tt_opts *o, tr_curve *c, tr_error *err);

/* start.c: the automatic roads' finest count, from the shortest scout's
 * ropelength (refine_auto). */
long tt_auto_refine_n(const tt_opts *o, double scout_ropelength);

/* roads.c: the roads of tries and shuffles. */
int tt_multi_level(const tt_opts *o);
long tt_road_coarse_n(const tt_opts *o, int t);
double tt_road_inflate(int t);
int tt_at_refine_n(const tt_opts *o, const tr_curve *c);
int tt_scout_at_refine_n(const tt_opts *o, const tr_curve *scout, tr_curve *out);
int tt_other_road(const tt_opts *o, tr_curve *c, tr_error *err);
int tt_shuffle_start(const tt_opts *o, tr_curve *c, tr_error *err);
/* start.c: a curve resampled along a spline from `from` scaled back to
 * its strut distance */
void tt_keep_strut_distance(const tr_curve *from, tr_curve *to, const tr_deadline *bound);
/* an automatic road's scout: coarse edges and levels (roads.c) */
void tt_scout_levels(tt_opts *o);
/* vertex_route.c: the whole call in the vertex contact model (contacts
 * TR_CONTACTS_VERTEX): res filled (its type not yet checked), or the error
 * with res->failed_at */
int tt_tighten_vertex(const tt_opts *o, tr_tighten_result *res, tr_error *err);

/* the share of the time the scouts take on a route of levels */
#define TT_SCOUT_SHARE 0.5

#endif
