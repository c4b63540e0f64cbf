/* The tightening layer's interface (host/tighten/): tightening as a call.
 *
 * tr_tighten takes a start curve (or a checkpoint to resume) and options,
 * and returns the tight curve with its certificate. It owns the strategy
 * the engine (engine.h, which opens, steps and settles a curve) does not:
 * the route (a loose start tightened from N/4 and refined), the roads of
 * --tries (scouts at other coarse counts, inflated starts, kicks off the
 * shortest result), the shuffled roads, the start's preparation (resample
 * to --n, scale to thickness 1, densify a coarse start, centre a start far
 * from the origin, a resumed run's goals), the second-order solver on a
 * tight start, and the certificate (thickness 1, the KKT residual).
 *
 * It never prints and never installs a signal handler: what the command
 * line says on stderr comes to opt->note, progress to opt->progress, and a
 * caller's interrupt is a flag it raises (opt->cancel), polled where the
 * engine polls its stop flag; the run then ends at its next step with its
 * best state kept. It writes only the checkpoint (opt->checkpoint, part of
 * the run's safety, and during a second-order solve the solver's state
 * beside it, CHECKPOINT.newton: engine/solver_state.c); the caller writes
 * the output. */
#ifndef TR_TIGHTEN_H
#define TR_TIGHTEN_H

#include <signal.h>
#include <stddef.h>

#include "curve/curve.h"
#include "engine/engine.h"
#include "oracle/kkt.h"
#include "oracle/thickness.h"
#include "oracle/vertex_thickness.h"
#include "util/error.h"

/* The certificate costs ~0.05 s at N = 400, ~1.2 s at 1600 and ~12 s at
 * 2400 on a 2-core machine (bench/notes/2026-11-23-kkt-certificate.md),
 * growing faster than N^2:
 * above this it runs only when asked for (kkt = 1). */
#define TR_TIGHTEN_KKT_AUTO_MAX_N 2400

/* What opt->progress is told, every opt->progress_every seconds while the
 * engine steps. */
typedef struct tr_tighten_progress {
    size_t n;          /* vertices, all components */
    long steps;        /* accepted steps of this road, all levels */
    double ropelength; /* the engine's estimate (the oracle certifies the result) */
    double residual;   /* the engine's residual of the last accepted step */
    double elapsed;    /* seconds of the road, including runs before a resumed checkpoint */
    double steps_per_s;
    int road, roads;   /* the road under way (1-based) of how many (tries, plus the scouts' refinement) */
} tr_tighten_progress;

/* The contact model a tightening holds (docs/physics.md): Rawdon's, every
 * two edges that count at least 2 apart (the default: the engine, polish,
 * second-order solver and KKT certificate), or SP-FEM's vertex model,
 * every two vertices that count at least 2 apart, K = ceil(pi / e) along a
 * component (oracle/vertex_thickness.h; vertex_route.c: the second-order
 * solver alone, on closed unconstrained components). */
enum { TR_CONTACTS_RAWDON = 0, TR_CONTACTS_VERTEX = 1 };

/* What a note is: INFO (the route chosen, the roads as they go; a quiet
 * caller drops them) or WARNING (a road skipped and why, a start
 * resampled, a checkpoint's goals that leave nothing to do). */
enum { TR_TIGHTEN_INFO = 0, TR_TIGHTEN_WARNING = 1 };

typedef struct tr_tighten_options {
    /* the start's name in messages, e.g. its file (default "the start") */
    const char *name;
    /* a checkpoint to continue (start NULL), to the goals it was started
     * with unless given here (NULL: a fresh start) */
    const char *resume;
    /* reference | auto | a device spec (NULL, default: $TIGHTROPE_DEVICE or auto) */
    const char *device;
    /* with refine_to, coarse levels of fewer than this many vertices in all
     * run on the serial reference (-1, default: the engine's 2048) */
    long device_from;
    long n;         /* first resample every component to n vertices (0, default: no) */
    long refine_to; /* tighten, then refine and re-tighten up to this N per component (0: no) */
    int refine_given;   /* refine_to is a goal (the result says when it is missed); default 0 */
    double residual;    /* stop below this engine residual (default 1e-4) */
    int residual_given; /* residual is a goal (also met by a KKT residual <= it); default 0 */
    double target;      /* stop at this ropelength estimate (0, default: off) */
    long steps;         /* accepted steps in all (0, default: off) */
    double time_limit;  /* seconds of wall clock for the whole call (0, default: none) */
    double began;       /* 0 (default): the limit counts from the call; else from this clock time
                         * (util/clock.h tr_clock_seconds), a command's start, its reading included */
    const char *checkpoint; /* written at the start, every checkpoint_every s, at the end (NULL: none);
                             * a solve's state beside it (checkpoint.newton), which resume takes up */
    double checkpoint_every; /* default 300 */
    int polish;     /* the polish stage at every level (default 1) */
    int newton;     /* the second-order solver: 1 also in the polish's place at the finest
                       level, 0 (default) only on a tight finest level, -1 never */
    int scale;      /* scale the start to thickness 1 first (default 0) */
    /* roads (0, default: chosen here: for a loose start taking the automatic
     * route with a time limit, and no shuffles given, the automatic roads of
     * start.c, tt_choose_route: scouts, most of them shuffled, the shortest
     * refined to a count from its length; else 1) */
    long tries;
    long shuffles;  /* the last this many roads start shuffled (default 0; < tries) */
    long seed;      /* the roads' seed (default 1) */
    int kkt;        /* certify: 1 always, 0 never, -1 (default) up to TR_TIGHTEN_KKT_AUTO_MAX_N */
    int auto_route; /* a loose start of N >= 200 given without n and refine_to goes from N/4 (default 1) */
    /* TR_CONTACTS_RAWDON (default) or TR_CONTACTS_VERTEX: the start (after
     * n and scale) goes to the second-order solver in the vertex model, and
     * the result is measured by the vertex oracle; the options that belong
     * to Rawdon's route are refused (tr_tighten_vertex_conflict) */
    int contacts;
    int centre;     /* a start whose box misses the origin is tightened about it (default 1) */
    /* a path the caller will write the result to: its format (for this
     * curve) and writability are checked once the start is open, before
     * the run, so that a run of hours does not end in "cannot write"
     * (NULL, default: not checked). Never written here. */
    const char *output_check;
    /* raised (by a signal handler, another thread) to stop the run: it ends
     * at its next step, keeping its best state (NULL: none) */
    volatile sig_atomic_t *cancel;
    void (*progress)(const tr_tighten_progress *p, void *user); /* NULL: none */
    double progress_every; /* seconds (default 0.25) */
    void (*note)(int kind, const char *msg, void *user);        /* NULL: none */
    void *user;
} tr_tighten_options;

/* Every field its documented default. */
void tr_tighten_options_default(tr_tighten_options *opt);

/* Where a failed call failed, for a caller that tells the user's mistakes
 * from the run's (the command line's exit status). */
typedef enum tr_tighten_stage {
    TR_TIGHTEN_AT_NONE = 0,
    TR_TIGHTEN_AT_RESUME,  /* reading the checkpoint's goals */
    TR_TIGHTEN_AT_START,   /* reading, preparing or settling the start */
    TR_TIGHTEN_AT_CHECK,   /* the start against refine_to and output_check */
    TR_TIGHTEN_AT_RUN,     /* the engine's run */
    TR_TIGHTEN_AT_CERTIFY, /* measuring and certifying the result */
    TR_TIGHTEN_AT_TYPE     /* the result is not the start's knot type (knot_type.h): never a result */
} tr_tighten_stage;

typedef struct tr_tighten_result {
    /* the result, scaled to thickness 1 where no vertex is constrained
     * (rescaled), owned: tr_tighten_result_free */
    tr_curve curve;
    size_t n; /* vertices */
    double ropelength, thickness, minrad, dcsd, length;
    double residual;     /* the engine's (NAN: no step taken) */
    double kkt_residual; /* NAN: not certified */
    tr_stop_reason stop;
    int interrupted;     /* opt->cancel stopped it (stop is TR_STOP_SIGNAL) */
    double elapsed;      /* seconds, runs before a resumed checkpoint included */
    long steps, rejected;
    double steps_per_s;
    int tries;           /* roads run (1: one road) */
    long seed;           /* -1: resumed */
    int road;            /* the road kept, 1-based; 0 resumed */
    /* goals: refine_short, refine_to asked and its N not reached (not
     * after an interrupt); goal_missed, target or residual asked and not
     * reached (not after an interrupt); goal_target says which */
    int refine_short, goal_missed, goal_target;
    long refine_to;      /* the effective refine_to (a resumed run's from its checkpoint) */
    int refine_implied;  /* refine_to is the loose start's own N (its route), not given */
    /* the detail the output's comments carry */
    tr_thickness th;
    tr_kkt kkt;
    int certified;       /* kkt holds the certificate of curve */
    int rescaled;
    tr_engine_progress progress; /* the kept road's: polish and solver outcomes */
    char device[128];
    double shift[3];     /* the start was moved by -shift (centred), 0 if not */
    int checkpoint_failures;
    int checkpointed; /* the kept road wrote checkpoints (scouts write none: tighten.c) */
    char checkpoint_why[256];
    tr_tighten_stage failed_at; /* when tr_tighten fails */
    /* the knot type kept (knot_type.h: the result's invariants equal the
     * start's): 1 checked, 0 not (an open rope, or a diagram the exact
     * arithmetic does not take); type_line says which, in one line */
    int type_checked;
    char type_line[320];
    /* contacts vertex: vt is the vertex oracle's measure of curve (curve is
     * at the model's thickness 1, and ropelength, thickness are vt's; th is
     * Rawdon's measure of the same curve); the solver converged or settled
     * (stop TR_STOP_SOLVED), and why it kept the start if it did (static
     * text, NULL when its result was accepted) */
    int vertex;
    tr_vertex_thickness vt;
    int vertex_converged;
    const char *vertex_why;
    /* the start's ropelength as given (before n, scale or a shuffle),
     * measured before the run: a result longer than it is a valid rope but
     * not what a tightening promises (a run stopped early by steps or the
     * time), which the caller may say. NAN: resumed, constrained ends (a
     * clasp), the vertex model, or not measurable (a start through itself) */
    double start_ropelength;
} tr_tighten_result;

/* Tightens start (or opt->resume's checkpoint, start NULL) as opt says
 * into *res. Returns TR_OK with a result, the goals met or not and
 * interrupted or not (res says), else the error, with res->failed_at, and
 * nothing to free. res is always initialised. */
int tr_tighten(const tr_curve *start, const tr_tighten_options *opt, tr_tighten_result *res, tr_error *err);

void tr_tighten_result_free(tr_tighten_result *res);

/* With opt->contacts TR_CONTACTS_VERTEX: the first option that has no
 * meaning in the vertex model (it belongs to Rawdon's route: the engine's
 * levels, roads, goals, checkpoints and devices, the KKT certificate), as
 * one line that names it, or NULL when there is none (or the model is
 * Rawdon's). tr_tighten refuses such options (TR_EINVAL). */
const char *tr_tighten_vertex_conflict(const tr_tighten_options *opt);

#endif
