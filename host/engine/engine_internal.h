/* This file contains the engine's state (struct tr_engine) and the helpers
 * its files share, internal to host/engine/: engine.c (create, step, refine),
 * checkpoint.c (the checkpoint format) and level_loop.c (tr_engine_run: the
 * levels, the polish stage, the stop rules). */
#ifndef TR_ENGINE_INTERNAL_H
#define TR_ENGINE_INTERNAL_H

#include <stdint.h>

#include "backend/backend.h"
#include "engine/engine.h"

struct tr_engine {
    char device[128];
    int coarse_ref; /* this level runs on the reference, not device (device_min_n) */
    tr_engine_params prm;
    tr_backend be;
    tr_curve curve; /* topology, constraints; coordinates as of the last download */
    int *gap;       /* exclusion gap per component, fixed between rebuilds */
    double *ebar;   /* scratch, ncomp */
    int contacts_valid;
    double disp_acc; /* max vertex motion summed since the contact list was built */
    double disp_est; /* the per-step motion the contact list's tilt allows for */
    tr_contact_stats contacts; /* of the last rebuild */
    double h;
    long steps, rejected;
    double length, residual, min_strut, minrad, edge_dev;
    int jammed;
    double elapsed_base; /* seconds before this process (from a checkpoint) */
    double t0;           /* monotonic start of this process's run */
    long steps_at_t0;
    int polished; /* 0: not yet; 1: accepted; -1: ran and kept the engine's curve */
    double polish_before, polish_after, polish_seconds;
    const char *polish_why;
    int newton_ran; /* as polished, for the second-order solver */
    double newton_before, newton_after, newton_seconds;
    int newton_iters;
    /* why the solver's last call kept nothing (tr_newton_stats.why_rejected,
     * or its own error's text), for the message when a refinement needs it */
    char newton_why[160];
    /* The polished curve itself, kept when settling it onto the engine's
     * constraint set cost ropelength (the oracle's, which is scale free):
     * until the engine takes another step it is the curve handed out. */
    double *polish_x;
    /* The second-order solver's last accepted result and its low parts
     * (curve.h; the solver's end game holds the iterate in extended
     * precision): the engine's steps move vertices in doubles, so the low
     * parts go out with the curve only while the curve handed out is that
     * result to the bit (tr_engine_get_curve). NULL when it had none. */
    double *newton_x, *newton_lo;
    size_t newton_nv; /* their vertices */
    /* the level's curve as it came, before the settle put it on the
     * engine's constraint set: the second-order solver starts from it at
     * the finest level (a spline through a tight knot overshoots MinRad
     * where the curvature jumps; the settle removes that by lengthening the
     * rope, 1.7e-3 at N = 9600, the solver by bending it back in place) */
    /* the solver's last run was accepted and converged or settled: the
     * finest level is done (TR_STOP_SOLVED) */
    int newton_solved;
    /* the solver has had its look at a tight finest level (run, or found
     * the start loose) */
    int newton_tried;
    /* a refined clasp handed to the solver unsettled (engine.c,
     * tr_engine_refine): the level is the solver's; if it does not take
     * it, the engine goes back to the coarse level held here (nothing of
     * the run lost) and the run stops there (TR_STOP_REFINE) */
    int refine_unsettled;
    size_t refine_unsettled_n;
    struct tr_engine_coarse_level {
        int held;
        tr_curve curve;    /* the coarse level, settled, as it was refined */
        double *ebar;      /* its edge targets */
        int polished;      /* its polish and solver flags */
        double *polish_x;  /* its polished curve, if it kept one */
        int newton_tried, newton_solved;
        double h, residual, disp_est; /* its step figures, for the stop's checkpoint */
        int jammed;
    } coarse;
    /* A clasp's solved level carried to the next (newton.h coarse,
     * prolong.c): the state its solve converged or settled with, the
     * multipliers a refined level starts from instead of the warm start's.
     * lvl_ok: it is the state of the engine's curve (set by a solve that
     * was accepted and converged or settled, cleared by any other step or
     * a roll-back);
     * lvl_refined: the curve is the refinement of that level's. */
    struct tr_newton_state *lvl;
    int lvl_ok, lvl_refined;
    /* the solver's last call stopped unfinished (its time, a stop, its
     * step limit), neither converged nor settled nor refused */
    int newton_unfinished;
    /* a stop decided inside a pass (a refined clasp's solve stopped by the
     * run's time or a signal): the next pass stops with it */
    tr_stop_reason stop_pending;
    /* the stop writes no checkpoint: the solver's own of a refined clasp,
     * with its state, is the one a resume goes on from */
    int ckpt_hold;
    /* a refinement that could not be settled and went back (TR_STOP_REFINE) */
    char stop_why[512];
    /* where the second-order solver writes its checkpoints (tr_engine_solve:
     * its arguments; the level loop: its limits) */
    const char *ckpt_path;
    double ckpt_every;
    /* checkpoints that could not be written (the run went on) and why the
     * last one failed */
    int ckpt_failures;
    char ckpt_failure[256];
    double *presettle_x;
    long polish_steps;
    /* The second-order solver's resumable state beside the checkpoint
     * (solver_state.c): with a checkpoint path P, the solve's state goes to
     * P.newton and every checkpoint written to P while that state is the
     * engine's (live) names it by the FNV-1a hash of its bytes; a resumed
     * run takes P.newton only when its checkpoint names it. */
    struct {
        int live;            /* file holds the state of the engine's last solve (unfinished) */
        int ours;            /* file was written by this engine */
        int resumed;         /* file is the state this engine resumed from (its checkpoint named it) */
        char file[4200];     /* where that state is */
        uint64_t hash;       /* of its bytes */
        struct tr_newton_state *resume; /* read at resume: the first solve goes on from it */
        tr_curve best;       /* the solver's last checkpoint curve in this solve (nv 0: none) */
        int refused;         /* a file at P.newton that is no solver state: never written over */
        char note[640];      /* what a caller says once (tr_engine_solver_state_note) */
        int note_warning;    /* the note is a warning (a state ignored), not news */
    } ss;
    /* the hard bound in force (engine.h, bound): the params' at create,
     * narrowed by tr_engine_run's limits while it runs */
    tr_deadline bound;
};

/* The backend's measure, with e->ebar set from it. */
int tr_engine_i_measure(tr_engine *e, tr_measure *m, tr_error *err);
/* Rebuilds the contact list (and, with recompute_gap, the exclusion gaps).
 * now: a measurement of the current state (e->ebar set by it) when the
 * caller has one, else NULL. The list does not change what the tilt reads
 * (the longest edge and MinRad), so it is not measured twice. */
int tr_engine_i_rebuild_contacts(tr_engine *e, int recompute_gap, const tr_measure *now, tr_error *err);
/* Copies a measurement into the engine's figures (length, MinRad, ...). */
void tr_engine_i_fill_state(tr_engine *e, const tr_measure *m);
/* Brings a fresh backend state onto the constraint set (equal edges,
 * struts, chords) in damped Newton steps, guarding every one. Past
 * e->bound it stops with TR_EINTERRUPTED, the backend half-settled: the
 * caller goes back to a settled state. */
int tr_engine_i_settle(tr_engine *e, const char *what, double overlap_ok, tr_error *err);
/* The second-order solver on e->curve (replaced only if accepted), its
 * figures kept in the engine; tight_only: give up on a loose start (not
 * reported as a run). A failure on the geometry is not an error. */
int tr_engine_i_newton(tr_engine *e, double seconds, int tight_only, volatile sig_atomic_t *stop, int *accepted,
                       tr_error *err);
/* Goes back from a refined level the solver did not take to the coarse
 * level e->coarse holds (tr_engine_refine kept it), measured afresh.
 * keep_state: the solver's state of the refined level stays (a solve the
 * run's time or a signal stopped, for a resume to go on with). */
int tr_engine_i_refine_back(tr_engine *e, int keep_state, tr_error *err);
/* The solver took the refined level: the coarse one is let go. */
void tr_engine_i_refine_taken(tr_engine *e);
/* Writes a checkpoint of e's state with curve c (its edge targets ebar,
 * exclusion gaps gap) in place of e's own (tr_engine_checkpoint_write
 * downloads e's). */
int tr_engine_i_checkpoint_curve(tr_engine *e, const tr_curve *c, const double *ebar, const int *gap,
                                 const char *path, tr_error *err);
/* solver_state.c: the solver's state beside the checkpoint. Sets np's
 * state callback (with a checkpoint path) and its resume (the state a
 * resumed run read, once); before a solve that does not resume, the state
 * of an earlier one is dropped. */
struct tr_newton_params;
struct tr_newton_stats;
void tr_engine_i_solver_state_before(tr_engine *e, struct tr_newton_params *np);
/* After the solve: a converged or settled one's state is dropped; the
 * state it resumed from is freed either way. */
void tr_engine_i_solver_state_after(tr_engine *e, int rc, const struct tr_newton_stats *ns);
/* The engine moves past the solve (a step, a refinement): its state no
 * longer goes with the engine's curve; the file is removed if this engine
 * made it (or resumed from it and rewrites its checkpoint). */
void tr_engine_i_solver_state_drop(tr_engine *e);
/* The solver's checkpoint curve, kept for the checkpoint written with each
 * state. */
void tr_engine_i_solver_state_keep_best(tr_engine *e, const tr_curve *best);
/* The checkpoint line naming the live state beside path ("" when none):
 * "newton_state HASH\n". */
void tr_engine_i_solver_state_line(const tr_engine *e, const char *path, char *line, size_t cap);
/* At resume from the checkpoint at path, whose line named hash (named 0:
 * no line): reads path.newton when it matches, else a note. */
void tr_engine_i_solver_state_open(tr_engine *e, const char *path, int named, uint64_t hash);
void tr_engine_i_solver_state_free(tr_engine *e);
/* engine.c: the solver's curve (at thickness 1) as a checkpoint at
 * e->ckpt_path, its edge targets and gaps its own; a failure is counted
 * (tr_engine_checkpoint_failures). */
int tr_engine_i_solver_checkpoint(tr_engine *e, const tr_curve *best, tr_error *err);

/* Keeps e->curve.x as the level's presettle_x. */
int tr_engine_i_keep_presettle(tr_engine *e, tr_error *err);
/* Opens e->be on c: the device, or the reference for a coarse level. */
int tr_engine_i_open_backend(tr_engine *e, const tr_curve *c, tr_error *err);
/* (Re)allocates the per-component arrays gap and ebar. */
int tr_engine_i_alloc_comp_arrays(tr_engine *e, tr_error *err);
/* A zeroed engine with its device spec and parameters (NULL: out of memory). */
tr_engine *tr_engine_i_new(const char *device, const tr_engine_params *p);

#endif
