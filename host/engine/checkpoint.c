/* This file contains the engine's checkpoint: the exact text format (hex
 * floats) tr_engine_checkpoint_write writes and tr_engine_resume reads back
 * (engine.h). */
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/engine.h"
#include "engine/engine_internal.h"
#include "util/text_file.h"

int tr_engine_checkpoint_write(tr_engine *e, const char *path, tr_error *err)
{
    int rc = e->be.ops->download(e->be.state, e->curve.x, e->ebar, err);
    if (rc)
        return rc;
    return tr_engine_i_checkpoint_curve(e, &e->curve, e->ebar, e->gap, path, err);
}

int tr_engine_i_checkpoint_curve(tr_engine *e, const tr_curve *c, const double *ebar, const int *gap,
                                 const char *path, tr_error *err)
{
    int rc;
    tr_engine_progress p;
    tr_engine_get_progress(e, &p);
    tr_text b = {0};
    tr_text_printf(&b, "tightrope-checkpoint 1\n");
    tr_text_printf(&b, "ncomp %d\n", c->ncomp);
    for (int k = 0; k < c->ncomp; k++)
        tr_text_printf(&b, "comp %zu %d %a %d\n", tr_comp_nv(c, k), c->closed[k], ebar[k], gap[k]);
    /* before the engine's first step (the solver's checkpoints at the
     * start) h is not set yet: the step it would begin with */
    tr_text_printf(&b, "state %ld %ld %a %a %a %a %a %d\n", e->steps, e->rejected, e->h > 0 ? e->h : ebar[0], e->disp_est,
              p.elapsed, e->residual, e->length, e->jammed);
    const tr_engine_goals *g = &e->prm.goals;
    tr_text_printf(&b, "goals %ld %d %a %a %d %ld %a\n", g->refine_to, g->refine_given, g->target, g->residual,
                   g->residual_given, g->steps, g->time_limit);
    /* the solver's state that goes with this checkpoint (solver_state.c) */
    char line[64];
    tr_engine_i_solver_state_line(e, path, line, sizeof line);
    tr_text_printf(&b, "%s", line);
    tr_text_printf(&b, "ncst %d\n", c->ncst);
    for (int q = 0; q < c->ncst; q++) {
        const tr_constraint *k = &c->cst[q];
        tr_text_printf(&b, "cst %d %d %a %a %a %a %a %a %a\n", (int)k->kind, k->id, k->p[0], k->p[1], k->p[2],
                  k->u[0], k->u[1], k->u[2], k->d);
    }
    for (size_t i = 0; i < c->nv; i++)
        if (c->vcst && c->vcst[i] >= 0)
            tr_text_printf(&b, "vcst %zu %d\n", i, c->vcst[i]);
    tr_text_printf(&b, "x\n");
    for (size_t i = 0; i < c->nv; i++)
        tr_text_printf(&b, "%a %a %a\n", c->x[3 * i], c->x[3 * i + 1], c->x[3 * i + 2]);
    tr_text_printf(&b, "end\n");
    size_t len;
    char *text = tr_text_take(&b, &len);
    if (!text)
        return tr_fail(err, TR_ENOMEM, "out of memory writing a checkpoint");
    rc = tr_write_file_atomic(path, text, len, err);
    free(text);
    return rc;
}

/* A whole token that is a finite number (strtod alone accepts "zzz" as 0). */
static int parse_finite(const char *tok, double *v)
{
    char *endp;
    *v = strtod(tok, &endp);
    return endp != tok && *endp == '\0' && isfinite(*v);
}

/* The 'goals' line (tr_engine_checkpoint_write): 1 when it parses into a
 * sane set of goals, else 0. */
static int parse_goals(const char *ln, tr_engine_goals *g)
{
    char t[64], r[64], l[64], extra;
    memset(g, 0, sizeof *g);
    if (sscanf(ln, "goals %ld %d %63s %63s %d %ld %63s %c", &g->refine_to, &g->refine_given, t, r, &g->residual_given,
               &g->steps, l, &extra) != 7)
        return 0;
    return parse_finite(t, &g->target) && parse_finite(r, &g->residual) && parse_finite(l, &g->time_limit) &&
           g->refine_to >= 0 && g->steps >= 0 && g->target >= 0 && g->residual >= 0 && g->time_limit >= 0 &&
           (g->refine_given == 0 || g->refine_given == 1) && (g->residual_given == 0 || g->residual_given == 1);
}

int tr_engine_checkpoint_goals(const char *path, tr_engine_goals *g, int *found, double *elapsed, tr_error *err)
{
    memset(g, 0, sizeof *g);
    *found = 0;
    if (elapsed)
        *elapsed = 0.0;
    char *text;
    int rc = tr_read_file(path, &text, NULL, err);
    if (rc)
        return rc;
    /* the line follows the header, the components and the state: it is
     * found where it starts a line before the coordinates ('x') */
    int line = 1;
    for (char *ln = text; ln && *ln; line++) {
        char *nl = strchr(ln, '\n');
        if (nl)
            *nl = '\0';
        if (!strcmp(ln, "x"))
            break;
        long st, rj;
        char h[64], da[64], el[64];
        double v;
        if (elapsed && sscanf(ln, "state %ld %ld %63s %63s %63s", &st, &rj, h, da, el) == 5 && parse_finite(el, &v) &&
            v >= 0)
            *elapsed = v;
        if (!strncmp(ln, "goals ", 6)) {
            if (!parse_goals(ln, g))
                rc = tr_fail(err, TR_EPARSE, "%s:%d: bad 'goals' line", path, line);
            else
                *found = 1;
            break;
        }
        ln = nl ? nl + 1 : NULL;
    }
    free(text);
    return rc;
}

int tr_engine_resume(tr_engine **out, const char *path, const char *device,
                     const tr_engine_params *p, tr_error *err)
{
    *out = NULL;
    char *text;
    int rrc = tr_read_file(path, &text, NULL, err);
    if (rrc)
        return rrc;
    /* every vertex needs a line of at least "0 0 0\n": bounds the counts
     * before anything is allocated from them (taken before strtok cuts the text) */
    const size_t max_vertices = strlen(text) / 6;
    tr_engine *e = tr_engine_i_new(device, p);
    size_t *nv = NULL;
    unsigned char *closed = NULL;
    double *ebar = NULL;
    int *gap = NULL;
    int rc = TR_OK, line = 1, ncomp = 0;
    char *save = NULL;
    char *ln = strtok_r(text, "\n", &save);
#define BAD(what)                                                                                  \
    do {                                                                                           \
        rc = tr_fail(err, TR_EPARSE, "%s:%d: %s", path, line, what);                               \
        goto fail;                                                                                 \
    } while (0)
#define NEXT()                                                                                     \
    do {                                                                                           \
        ln = strtok_r(NULL, "\n", &save);                                                          \
        line++;                                                                                    \
        if (!ln)                                                                                   \
            BAD("checkpoint ends early");                                                          \
    } while (0)
    if (!e) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory");
        goto fail;
    }
    if (!ln || strcmp(ln, "tightrope-checkpoint 1") != 0)
        BAD("not a tightrope checkpoint (expected 'tightrope-checkpoint 1')");
    NEXT();
    if (sscanf(ln, "ncomp %d", &ncomp) != 1 || ncomp <= 0 || ncomp > 1000000)
        BAD("expected 'ncomp K'");
    nv = calloc((size_t)ncomp, sizeof *nv);
    closed = calloc((size_t)ncomp, 1);
    ebar = calloc((size_t)ncomp, sizeof *ebar);
    gap = calloc((size_t)ncomp, sizeof *gap);
    if (!nv || !closed || !ebar || !gap) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory");
        goto fail;
    }
    size_t total = 0;
    for (int k = 0; k < ncomp; k++) {
        NEXT();
        int cl;
        char eb[64];
        if (sscanf(ln, "comp %zu %d %63s %d", &nv[k], &cl, eb, &gap[k]) != 4 || nv[k] < 2)
            BAD("expected 'comp NV CLOSED EBAR GAP'");
        if (nv[k] > max_vertices - total)
            BAD("more vertices than the checkpoint holds");
        total += nv[k];
        if (gap[k] < 2 || (cl != 0 && cl != 1) || (cl && nv[k] < 3))
            BAD("bad component closure or exclusion gap");
        closed[k] = (unsigned char)(cl != 0);
        if (!parse_finite(eb, &ebar[k]) || !(ebar[k] > 0))
            BAD("edge length must be a positive finite number");
    }
    NEXT();
    {
        char h[64], da[64], el[64], rs[64], le[64];
        if (sscanf(ln, "state %ld %ld %63s %63s %63s %63s %63s %d", &e->steps, &e->rejected, h, da, el, rs,
                   le, &e->jammed) != 8)
            BAD("expected the 'state' line");
        if (!parse_finite(h, &e->h) || !parse_finite(da, &e->disp_est) || !(e->disp_est >= 0) ||
            !parse_finite(el, &e->elapsed_base) || !parse_finite(rs, &e->residual) ||
            !parse_finite(le, &e->length) || !(e->h > 0) || e->steps < 0 || e->rejected < 0)
            BAD("bad number in the 'state' line");
    }
    if ((rc = tr_curve_alloc(&e->curve, ncomp, nv, closed, err)))
        goto fail;
    NEXT();
    /* the run's goals (older checkpoints have none): the caller reads them
     * with tr_engine_checkpoint_goals and passes them in p */
    if (!strncmp(ln, "goals ", 6)) {
        tr_engine_goals g;
        if (!parse_goals(ln, &g))
            BAD("bad 'goals' line");
        NEXT();
    }
    /* the solver's state that goes with it (solver_state.c; older
     * checkpoints and those taken outside a solve have none) */
    int state_named = 0;
    uint64_t state_hash = 0;
    if (!strncmp(ln, "newton_state ", 13)) {
        unsigned long long h;
        char tail;
        if (sscanf(ln, "newton_state %16llx %c", &h, &tail) != 1 || strlen(ln) != 13 + 16)
            BAD("bad 'newton_state' line (expected 'newton_state' and 16 hexadecimal digits)");
        state_named = 1;
        state_hash = (uint64_t)h;
        NEXT();
    }
    int ncst;
    if (sscanf(ln, "ncst %d", &ncst) != 1 || ncst < 0)
        BAD("expected 'ncst C'");
    for (int q = 0; q < ncst; q++) {
        NEXT();
        tr_constraint k;
        int kind;
        char f[7][64];
        if (sscanf(ln, "cst %d %d %63s %63s %63s %63s %63s %63s %63s", &kind, &k.id, f[0], f[1], f[2], f[3],
                   f[4], f[5], f[6]) != 9)
            BAD("expected a 'cst' line");
        if (kind < TR_CST_FIXED || kind > TR_CST_PLANE)
            BAD("unknown constraint kind");
        k.kind = (tr_cst_kind)kind;
        int ok = 1;
        for (int a = 0; a < 3; a++)
            ok = ok && parse_finite(f[a], &k.p[a]) && parse_finite(f[3 + a], &k.u[a]);
        if (!ok || !parse_finite(f[6], &k.d))
            BAD("bad number in a 'cst' line");
        if ((rc = tr_curve_add_constraint(&e->curve, &k, err)) < 0)
            goto fail;
        rc = TR_OK;
    }
    NEXT();
    while (!strncmp(ln, "vcst ", 5)) {
        size_t i;
        int q;
        if (sscanf(ln, "vcst %zu %d", &i, &q) != 2 || i >= e->curve.nv || q < 0 || q >= ncst)
            BAD("bad 'vcst' line");
        e->curve.vcst[i] = q;
        NEXT();
    }
    if (strcmp(ln, "x") != 0)
        BAD("expected 'x'");
    for (size_t i = 0; i < e->curve.nv; i++) {
        NEXT();
        char *q = ln;
        for (int a = 0; a < 3; a++) {
            char *endp;
            e->curve.x[3 * i + a] = strtod(q, &endp);
            if (endp == q || !isfinite(e->curve.x[3 * i + a]))
                BAD("expected three finite coordinates");
            q = endp;
        }
        while (*q == ' ' || *q == '\t' || *q == '\r')
            q++;
        if (*q)
            BAD("unexpected text after the coordinates");
    }
    NEXT();
    if (strcmp(ln, "end") != 0)
        BAD("expected 'end' (truncated checkpoint?)");
#undef BAD
#undef NEXT
    if ((rc = tr_engine_i_alloc_comp_arrays(e, err)) || (rc = tr_engine_i_open_backend(e, &e->curve, err)))
        goto fail;
    memcpy(e->gap, gap, (size_t)ncomp * sizeof *gap);
    if ((rc = e->be.ops->upload(e->be.state, e->curve.x, ebar, err)))
        goto fail;
    /* the list is rebuilt with the saved exclusion gaps: pairs it adds beyond
     * the uninterrupted run's list are inactive and contribute exact zeros */
    {
        memcpy(e->ebar, ebar, (size_t)ncomp * sizeof *ebar);
        if ((rc = tr_engine_i_rebuild_contacts(e, 0, NULL, err)))
            goto fail;
        tr_measure m;
        if ((rc = tr_engine_i_measure(e, &m, err)))
            goto fail;
        /* a checkpoint is input like any other: never continue from a state
         * that is not a valid rope (overlap, a kink, a wrong edge length) */
        if (!(m.min_strut >= e->prm.correct.strut_dist - 100.0 * e->prm.accept_viol) ||
            !(m.min_minrad >= e->prm.correct.minrad * (1.0 - 2.0 * e->prm.minrad_tol)) ||
            !(m.edge_dev <= 1e-6)) {
            rc = tr_fail(err, TR_EGEOMETRY,
                         "%s: checkpoint is not a valid rope state (closest non-local distance %.6g, "
                         "MinRad %.6g, edge deviation %.3g)",
                         path, m.min_strut, m.min_minrad, m.edge_dev);
            goto fail;
        }
        double len = e->length;
        tr_engine_i_fill_state(e, &m);
        e->length = len;
    }
    e->steps_at_t0 = e->steps;
    /* the solver's state beside it, when it is the one named (else a note) */
    tr_engine_i_solver_state_open(e, path, state_named, state_hash);
    free(text);
    free(nv);
    free(closed);
    free(ebar);
    free(gap);
    *out = e;
    return TR_OK;
fail:
    free(text);
    free(nv);
    free(closed);
    free(ebar);
    free(gap);
    tr_engine_destroy(e);
    return rc;
}

