/* This file contains the second-order solver's resumable state beside the
 * engine's checkpoint (newton.h tr_newton_state): with a checkpoint path P,
 * the solve's state goes to P.newton every checkpoint period and when the
 * solve stops unfinished (time limit, signal), and a run resumed from P
 * goes on with the solve where it stopped instead of starting it again
 * from P's curve (mu back at mu0, hundreds of steps at large N).
 *
 * Which state goes with which checkpoint: the checkpoint names it. Every
 * checkpoint written to P while the engine's curve is still the solve's
 * (from the state's write until the solve converges or settles, or the
 * engine takes a step or refines) carries a line "newton_state HASH", the
 * FNV-1a hash of P.newton's bytes as written; the state is written first,
 * then a checkpoint naming it (the solver's last checkpoint curve; at a
 * stop, the run's last checkpoint). A resumed run takes P.newton only when
 * its hash is the one P names: a state from another run, one written after
 * P (a kill between the two writes), or a P written after the solve moved
 * on, is ignored with a note and the solve starts from P's curve, as it
 * did before states were kept. A hash, not the state's shape or the
 * curve's positions: the checkpoint holds the rescaled best iterate, the
 * state the unscaled loop iterate, which match no simple test.
 *
 * Files: P.newton is written (atomically) only where nothing is, or where a
 * solver state is (its magic line): anything else there is left alone and
 * no state is kept. It is removed once its solve converged or settled, or
 * the engine moved past it, and only if this engine wrote it or resumed
 * from it (its checkpoint named it). A run that ends with
 * its solve unfinished (stopped, out of time) leaves it beside its
 * checkpoint: it is what --resume needs. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "engine/engine.h"
#include "engine/engine_internal.h"
#include "solver/newton.h"
#include "util/text_file.h"

/* P.newton into out (cap bytes); 0 when it does not fit */
static int beside(const char *ckpt, char *out, size_t cap)
{
    int n = snprintf(out, cap, "%s.newton", ckpt);
    return n > 0 && (size_t)n < cap;
}

static int exists(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f)
        fclose(f);
    return f != NULL;
}

/* FNV-1a, 64 bits: an identity for the file's bytes, not a defence
 * against anyone making a file collide on purpose */
static int file_hash(const char *path, uint64_t *h)
{
    char *data;
    size_t len;
    tr_error err;
    if (tr_read_file(path, &data, &len, &err) != TR_OK)
        return 0;
    uint64_t v = 14695981039346656037ull;
    for (size_t i = 0; i < len; i++) {
        v ^= (unsigned char)data[i];
        v *= 1099511628211ull;
    }
    free(data);
    *h = v;
    return 1;
}

static void note(tr_engine *e, int warning, const char *fmt, const char *a, const char *b)
{
    snprintf(e->ss.note, sizeof e->ss.note, fmt, a, b);
    e->ss.note_warning = warning;
}

static int same_shape(const tr_newton_state *s, const tr_curve *c)
{
    if (s->nv != c->nv || s->ncomp != c->ncomp)
        return 0;
    for (int k = 0; k < c->ncomp; k++)
        if (s->comp_nv[k] != tr_comp_nv(c, k))
            return 0;
    return 1;
}

static void free_resume(tr_engine *e)
{
    if (e->ss.resume) {
        tr_newton_state_free(e->ss.resume);
        free(e->ss.resume);
        e->ss.resume = NULL;
    }
}

/* The solver's state callback (newton.h state): P.newton, then the
 * checkpoint that names it. A failure is counted as a checkpoint's is; the
 * solve goes on. */
static int give_state(void *user, const tr_newton_state *s, tr_error *err)
{
    tr_engine *e = user;
    char path[sizeof e->ss.file];
    if (!e->ckpt_path || e->ss.refused || !beside(e->ckpt_path, path, sizeof path))
        return TR_OK;
    /* a checkpoint to a device or a FIFO (written in place: text_file.h)
     * is not kept to resume from: no state beside it */
    struct stat st;
    if (stat(e->ckpt_path, &st) == 0 && !S_ISREG(st.st_mode))
        return TR_OK;
    int mine = e->ss.live && !strcmp(e->ss.file, path);
    if (!mine && exists(path) && !tr_newton_state_is_file(path)) {
        e->ss.refused = 1;
        note(e, 1, "%.200s is not a solver state: left alone, and the solve's state is not kept beside %.200s", path,
             e->ckpt_path);
        return TR_OK;
    }
    /* no checkpoint names a state while it is being replaced */
    e->ss.live = 0;
    uint64_t h = 0;
    int rc = tr_newton_state_write(path, s, err);
    if (rc == TR_OK && !file_hash(path, &h))
        rc = tr_fail(err, TR_EIO, "cannot read back %s", path);
    if (rc) {
        e->ckpt_failures++;
        snprintf(e->ckpt_failure, sizeof e->ckpt_failure, "%.255s", err->msg);
        return rc;
    }
    e->ss.live = 1;
    e->ss.ours = 1;
    e->ss.resumed = 0;
    e->ss.hash = h;
    snprintf(e->ss.file, sizeof e->ss.file, "%s", path);
    /* the checkpoint that goes with it; before the solver's first
     * checkpoint curve, the run's own checkpoint names it when it stops */
    if (e->ss.best.nv > 0)
        return tr_engine_i_solver_checkpoint(e, &e->ss.best, err);
    return TR_OK;
}

void tr_engine_i_solver_state_before(tr_engine *e, tr_newton_params *np)
{
    tr_curve_free(&e->ss.best);
    e->ss.best = (tr_curve){0};
    if (e->ss.resume && same_shape(e->ss.resume, &e->curve)) {
        np->resume = e->ss.resume;
    } else {
        if (e->ss.resume) {
            note(e, 1, "%.200s ignored: the solve is of another shape than its checkpoint's curve%.200s", e->ss.file, "");
            free_resume(e);
        }
        /* a new solve: an earlier one's state does not go with it */
        tr_engine_i_solver_state_drop(e);
    }
    if (e->ckpt_path && e->ckpt_every > 0) {
        np->state = give_state;
        np->state_every = e->ckpt_every;
        np->user = e;
    }
}

void tr_engine_i_solver_state_after(tr_engine *e, int rc, const tr_newton_stats *ns)
{
    free_resume(e);
    tr_curve_free(&e->ss.best);
    e->ss.best = (tr_curve){0};
    if (rc == TR_OK && (ns->converged || ns->settled))
        tr_engine_i_solver_state_drop(e);
}

void tr_engine_i_solver_state_drop(tr_engine *e)
{
    if (!e->ss.live)
        return;
    e->ss.live = 0;
    /* a state this engine resumed from is a file a run of this tool made
     * (its checkpoint named it by its bytes' hash) and is done with too; the
     * checkpoint that named it, if not rewritten, then names a missing
     * state, which a resume notes and goes on from the curve */
    if ((e->ss.ours || e->ss.resumed) && tr_newton_state_is_file(e->ss.file))
        remove(e->ss.file);
    e->ss.ours = e->ss.resumed = 0;
}

void tr_engine_i_solver_state_keep_best(tr_engine *e, const tr_curve *best)
{
    tr_error err;
    tr_curve_free(&e->ss.best);
    e->ss.best = (tr_curve){0};
    if (tr_curve_copy(&e->ss.best, best, &err) != TR_OK)
        e->ss.best = (tr_curve){0};
}

void tr_engine_i_solver_state_line(const tr_engine *e, const char *path, char *line, size_t cap)
{
    char sp[sizeof e->ss.file];
    line[0] = 0;
    if (e->ss.live && beside(path, sp, sizeof sp) && !strcmp(sp, e->ss.file))
        snprintf(line, cap, "newton_state %016llx\n", (unsigned long long)e->ss.hash);
}

void tr_engine_i_solver_state_open(tr_engine *e, const char *path, int named, uint64_t hash)
{
    char sp[sizeof e->ss.file];
    if (!beside(path, sp, sizeof sp))
        return;
    if (!named) {
        if (exists(sp))
            note(e, 1, "%.200s ignored: the checkpoint %.200s names no solver state (the solve it was taken in had "
                       "ended or moved on)", sp, path);
        return;
    }
    uint64_t h;
    if (!exists(sp) || !file_hash(sp, &h)) {
        note(e, 1, "the checkpoint %.200s names a solver state, but %.200s cannot be read: the solve starts again "
                   "from the checkpoint's curve", path, sp);
        return;
    }
    if (h != hash) {
        note(e, 1, "%.200s ignored: it is not the solver state the checkpoint %.200s names (another run's, or "
                   "written after it)", sp, path);
        return;
    }
    tr_newton_state *s = calloc(1, sizeof *s);
    tr_error err;
    if (!s || tr_newton_state_read(sp, s, &err) != TR_OK) {
        note(e, 1, "%.200s ignored: %.200s", sp, s ? err.msg : "out of memory");
        free(s);
        return;
    }
    if (!same_shape(s, &e->curve)) {
        note(e, 1, "%.200s ignored: not of the vertices per component of the checkpoint %.200s", sp, path);
        tr_newton_state_free(s);
        free(s);
        return;
    }
    free_resume(e);
    e->ss.resume = s;
    e->ss.live = 1;
    e->ss.ours = 0;
    e->ss.resumed = 1;
    e->ss.hash = h;
    snprintf(e->ss.file, sizeof e->ss.file, "%s", sp);
    char at[160];
    snprintf(at, sizeof at, "step %d, %ld Newton steps and %.1f s before", s->iter, s->steps, s->seconds);
    note(e, 0, "the solve goes on from its state %.200s (%.200s)", sp, at);
}

void tr_engine_i_solver_state_free(tr_engine *e)
{
    free_resume(e);
    tr_curve_free(&e->ss.best);
    e->ss.best = (tr_curve){0};
}

int tr_engine_solver_state_take_note(tr_engine *e, char *buf, size_t cap)
{
    if (!e->ss.note[0])
        return -1;
    snprintf(buf, cap, "%s", e->ss.note);
    e->ss.note[0] = 0;
    return e->ss.note_warning;
}
