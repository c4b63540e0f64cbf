/* The tightening engine: drives a backend (backend.h) through constrained
 * gradient steps on the rope length, with step control, topology guards,
 * multi-resolution refinement and exact checkpoints. It never touches the
 * device and never prints: progress goes to a callback.
 *
 * One step (all arithmetic in the backend):
 *   save; tension_step (move along -grad L, low-passed, per-vertex capped);
 *   correct (coupled Gauss-Newton projection back onto: equal edges,
 *   segment-segment struts >= 2, curvature chords <=> MinRad >= 1);
 *   measure. The step is accepted only if the correction converged, the
 *   length went down, no vertex moved more than guard_move, the shortest
 *   non-local distance stayed >= 2 (within tolerance) and MinRad >= 1
 *   (within tolerance); otherwise the state is restored and h halved.
 *   After those tests the contact list is rebuilt at the new state, and
 *   its shortest strut must hold as well (the list the step ran on may have
 *   lost a contact that slid further than the list's tilt allowed for).
 * Why no strand can pass (the knot never changes): between two accepted
 * states every vertex moves at most guard_move < 1/2 along a straight line,
 * so the distance of any two non-excluded segments changes by at most
 * 2 guard_move < 1 while it started >= 2 - tol: at an accepted state the
 * closest non-excluded pair is either a local minimum of the distance along
 * both strands, whose strut is within the list's tilt of both normal planes
 * (tilt >= 1.25 ebar / MinRad > the largest turning angle
 * 2 atan(ebar / (2 MinRad))), so it
 * was in the list just checked, or it borders the excluded arc, and such
 * pairs lie arclength ~pi apart on a curve of curvature <= 1, hence about 2
 * apart (Schur's comparison); excluded pairs cannot self-intersect there. */
#ifndef TR_ENGINE_H
#define TR_ENGINE_H

#include <signal.h>
#include <stddef.h>

#include "backend/backend.h"
#include "curve/curve.h"
#include "util/clock.h"
#include "util/error.h"

/* What a run was asked for (tighten's options; 0: not asked), kept in
 * its checkpoints so that a resumed run goes on to the same ends: an
 * interrupted --refine-to 2400 once resumed and stopped at the N = 400 it
 * had reached. refine_to is also kept when the route chose it (a loose
 * start tightened from N/4); refine_given and residual_given say whether
 * the user asked (a goal the exit status answers for) or the default did. */
typedef struct tr_engine_goals {
    long refine_to;
    int refine_given;
    double target, residual;
    int residual_given;
    long steps;
    double time_limit;
} tr_engine_goals;

typedef struct tr_engine_params {
    /* contact list cutoff = 2 + min(skin, max(skin_min, skin_motion * the
     * last step's largest vertex motion)): two strands close by at most twice
     * that per step, and the list is rebuilt after every step */
    double skin, skin_min, skin_motion;
    /* The contact list keeps only pairs whose strut is within a tilt of both
     * edges' normal planes (backend.h), tilt = tilt_edges * (longest edge) /
     * min(1, MinRad) + tilt_motion * (the last step's largest vertex
     * motion), capped at 1 (no test): the first term is above the largest
     * turning angle, 2 atan(ebar / (2 MinRad)) <= ebar / MinRad, so every
     * local minimum of the distance is held; the second would add the pairs
     * a step like the last one can slide into. It is 0 by default: the
     * check after each step rejects a step that lost a contact, and on the
     * N = 2400 trefoil both settings take the same steps, the smaller list
     * faster (bench/notes/2026-11-23-contact-list-tree-walk.md). The list
     * stays linear in N. */
    double tilt_edges, tilt_motion;
    double max_move;       /* per-vertex cap of the tension move */
    double guard_move;     /* reject a step that moved any vertex further */
    int smooth_passes;     /* low-pass passes on the tension force */
    double h_min, h_max;   /* step length bounds (h starts at ebar) */
    double grow, shrink;   /* h *= grow after an accepted step, *= shrink after a rejected one */
    double accept_viol;    /* accept only if the correction left violations <= this */
    double minrad_tol;     /* MinRad >= 1 - minrad_tol */
    double max_edge;       /* "too coarse": edges must be shorter than this (rope radius units) */
    tr_correct_params correct;
    int project;             /* project the force onto the active tangent cone first */
    tr_correct_params proj;  /* its solver settings (max_newton = release passes) */
    /* The polish stage (polish.h) at the finest level: runs serially on the
     * host on the downloaded curve, once, when the finest level would stop
     * (jammed, residual reached) or, under a time limit, for the last
     * polish_share of the time left when the finest level began. It honours
     * the stop flag; no periodic checkpoint is written while it runs. */
    int polish;
    double polish_share;
    int polish_coarse; /* also polish every coarse level before refining it */
    /* The second-order solver (solver/newton.h) in the polish's place and
     * time at the finest level, clasps included (the polish still ends the
     * coarse levels). Kept only if the oracle finds its result shorter at
     * thickness 1. */
    int newton;
    /* A tight finest level goes to the solver first even without newton
     * (newton then adds the solver in the polish's place for loose ones);
     * 0 keeps the solver out altogether. Default 1. (A tight start goes to
     * the solver before the engine settles it through tr_engine_solve,
     * which the tightening layer calls between tr_engine_open and
     * tr_engine_settle_start.) */
    int newton_tight;
    /* Coarse levels (all but the last of a run with refine_to) with fewer
     * vertices than this run on the serial reference instead of the chosen
     * device: there an OpenCL device's cost per kernel launch outweighs its
     * throughput (bench/notes/2026-11-23-pocl-end-to-end.md: PoCL took 91 s
     * to the N = 1200 level of
     * the N = 2400 trefoil, the reference 28 s). 0: the chosen device at
     * every level. */
    size_t device_min_n;
    /* The hard bound of everything the engine does (tr_engine_solve,
     * the start's settle, tr_engine_run's levels, refinements and settles):
     * past it a settle stops where it is and the engine goes back to its
     * last settled state. tr_engine_run adds its stop flag to it. Zero:
     * none. The soft shares (tr_engine_solve's seconds, tr_engine_run's
     * time_limit, a level's half of the time left) divide the time within
     * it. */
    tr_deadline bound;
    /* written into every checkpoint (tr_engine_checkpoint_goals reads
     * them back) */
    tr_engine_goals goals;
} tr_engine_params;

void tr_engine_params_default(tr_engine_params *p);

/* The contact list's cutoff and tilt for the given longest edge and per-step
 * motion (see skin and tilt_edges above). */
void tr_engine_contact_shape(const tr_engine_params *p, double ebar_max, double minrad, double disp,
                             double *cutoff, double *tilt);

typedef enum tr_stop_reason {
    TR_STOP_NONE = 0,
    TR_STOP_RESIDUAL,  /* residual below the requested value */
    TR_STOP_JAMMED,    /* no step of length >= h_min is accepted: constrained critical */
    TR_STOP_TARGET,    /* ropelength estimate at or below the target */
    TR_STOP_STEPS,     /* step limit */
    TR_STOP_TIME,      /* wall-time limit */
    TR_STOP_SIGNAL,    /* the stop flag was raised (SIGINT/SIGTERM) */
    TR_STOP_SOLVED,    /* the second-order solver converged or settled at the finest level */
    TR_STOP_REFINE     /* a refined level could not be settled: the run stopped at the level before it
                        * (tr_engine_stop_why says why) */
} tr_stop_reason;

const char *tr_stop_reason_name(tr_stop_reason r);

typedef struct tr_engine_progress {
    long steps;        /* accepted steps, all levels */
    long rejected;
    size_t n;          /* vertices */
    double length;
    double ropelength; /* length / min(1, min_strut/2, minrad) - an estimate; the oracle certifies */
    double residual;   /* |resolved force| / |force| of the last accepted step (KKT residual) */
    double min_strut;
    double minrad;
    double edge_dev;
    double h;
    double elapsed;    /* seconds, including earlier runs resumed from checkpoints */
    double steps_per_s;
    int polished;      /* 1: the polish stage ran and was accepted; -1: ran, rejected */
    double polish_before, polish_after; /* oracle ropelength around it */
    double polish_seconds;
    const char *polish_why; /* static text: why polish kept the engine's curve (NULL otherwise) */
    int newton_ran;         /* 1: the second-order solver ran and was accepted; -1: ran, rejected */
    double newton_before, newton_after, newton_seconds;
    int newton_iters;
} tr_engine_progress;

typedef struct tr_engine_limits {
    size_t refine_to;        /* final vertex count per component (0: stay) */
    double residual;         /* stop below (0: off) */
    double target;           /* ropelength estimate target (0: off) */
    long max_steps;          /* total accepted steps (0: off) */
    double time_limit;       /* seconds (0: off) */
    double coarse_residual;  /* a coarse level ends below this residual */
    double checkpoint_every; /* seconds; 0 = only at the end / on signal */
    const char *checkpoint_path;
    volatile sig_atomic_t *stop; /* raised by a signal handler; may be NULL */
    double progress_every;   /* seconds between progress callbacks */
    void (*progress)(const tr_engine_progress *p, void *user);
    void *user;
} tr_engine_limits;

typedef struct tr_engine tr_engine;

/* Opens the backend for the curve, checks it (too coarse, overlapping,
 * too tightly bent), and equalises its edges: tr_engine_open, then
 * tr_engine_settle_start. */
int tr_engine_create(tr_engine **out, const tr_curve *c, const char *device,
                     const tr_engine_params *p, tr_error *err);

/* tr_engine_create in two steps, for a caller that solves the start
 * first (tr_engine_solve): tr_engine_open takes the curve as it is (no
 * backend opened, nothing checked or moved); tr_engine_settle_start opens
 * the backend, checks and settles it. After a failed settle the caller
 * destroys the engine. A settle the bound stops keeps the start as it
 * was (the solver's result, if it took it), a rope already. */
int tr_engine_open(tr_engine **out, const tr_curve *c, const char *device, const tr_engine_params *p,
                   tr_error *err);
int tr_engine_settle_start(tr_engine *e, tr_error *err);

/* The second-order solver (solver/newton.h) on the engine's curve, before
 * tr_engine_settle_start: a start that is tight (a converged knot resampled
 * by --n) is solved at once, where the settle would first remove a
 * spline's MinRad overshoot by lengthening the rope (1.7e-3 at N = 9600,
 * in 48 s); a loose one is left alone (the level loop tries the solver
 * again in the polish's place). For up to seconds (0: none), within the
 * params' bound, stopping when *stop is raised (NULL: the bound's flag);
 * every checkpoint_every seconds its shortest iterate goes to checkpoint
 * in the checkpoint format (NULL: none), since tr_engine_run's limits come
 * after it. *accepted: the result was shorter at thickness 1 and kept. The
 * level loop reaches the solver through the same path (one way in). */
int tr_engine_solve(tr_engine *e, double seconds, volatile sig_atomic_t *stop, const char *checkpoint,
                    double checkpoint_every, int *accepted, tr_error *err);
void tr_engine_destroy(tr_engine *e);

/* Tightens (through the refinement levels) until a stop condition. */
int tr_engine_run(tr_engine *e, const tr_engine_limits *lim, tr_stop_reason *why, tr_error *err);

/* One step; *accepted tells whether it was kept. */
int tr_engine_step(tr_engine *e, int *accepted, tr_error *err);

/* Low-pass resample every component to n vertices and re-equalise. Where
 * the re-equalising (the settle) fails, a clasp's level goes to the
 * second-order solver from the curve as refined (with the solver and the
 * polish on; should the solver not take it, tr_engine_run goes back to the
 * coarse level and stops there, TR_STOP_REFINE, or with the time or
 * signal that stopped the solve); any other level goes back to the coarse level it came from, and the call fails with
 * TR_EGEOMETRY (nothing lost: the coarse level's curve is the engine's
 * again). TR_EINTERRUPTED: the bound stopped the settle, back at the
 * coarse level too. */
int tr_engine_refine(tr_engine *e, size_t n, tr_error *err);

/* Why the run stopped where it did, in words, for TR_STOP_REFINE ("" for
 * the other reasons). */
const char *tr_engine_stop_why(const tr_engine *e);

void tr_engine_get_progress(const tr_engine *e, tr_engine_progress *p);
const char *tr_engine_device(const tr_engine *e);
const char *tr_engine_warning(const tr_engine *e);
/* Checkpoints of the run that could not be written (it went on without
 * them); *why the last failure's message (may be NULL). */
int tr_engine_checkpoint_failures(const tr_engine *e, const char **why);

/* What became of the second-order solver's state beside a checkpoint
 * (solver_state.c), in one line, once: at resume, taken (the solve goes on
 * from it) or ignored and why; during a run, a state not kept. Returns -1
 * when there is nothing new to say (buf untouched), else 1 for a state
 * ignored or not kept, 0 for news, with the line in buf. */
int tr_engine_solver_state_take_note(tr_engine *e, char *buf, size_t cap);

/* Current coordinates (and constraints) as a curve the caller frees. */
int tr_engine_get_curve(tr_engine *e, tr_curve *out, tr_error *err);

/* Checkpoint: every number of the state, exactly (hex floats), written
 * atomically. Resuming continues bit for bit on the reference backend. */
int tr_engine_checkpoint_write(tr_engine *e, const char *path, tr_error *err);
int tr_engine_resume(tr_engine **out, const char *path, const char *device,
                     const tr_engine_params *p, tr_error *err);
/* The goals a checkpoint was written with (its params' goals); *found 0
 * and g zeroed for a checkpoint written before they were kept. *elapsed
 * (may be NULL): the seconds the run had used (0 if not found). */
int tr_engine_checkpoint_goals(const char *path, tr_engine_goals *g, int *found, double *elapsed, tr_error *err);

#endif
