/* This file contains the serial reference's tension_step (backend.h): the
 * force, its low-pass passes, its projection on the tangent cone of the
 * active rows, and the capped move. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/reference/reference_state.h"
#include "segment_distance.h"
#include "util/vec3.h"

static void edge_unit(const ref_state *s, size_t a, double *u)
{
    v3_sub(u, s->x + 3 * (size_t)s->next[a], s->x + 3 * a);
    double l = v3_norm(u);
    v3_scale(u, 1.0 / l, u);
}

/* Tangent projection of the (smoothed) force G: rows in the active band
 * (edges always) evaluated at x; solve A y = J (P G); v = P G - M^-1 J^T y;
 * inequality rows whose multiplier pulls (y_r > 0: the force would separate
 * them) are released and the solve repeated, passes times in all. G <- v,
 * s->debar <- the ebar velocity. */
static void project_tangent(ref_state *s, const tr_correct_params *prm, double *G)
{
    size_t nv = s->nv, nr = 2 * nv + s->np;
    rb_eval_rows(s, prm);
    for (size_t i = 0; i < nv; i++) {
        rb_project_motion(s, i, G + 3 * i);
    }
    for (int pass = 0; pass < prm->max_newton; pass++) {
        memcpy(s->dx, G, 3 * nv * sizeof *G);
        for (int k = 0; k < s->ncomp; k++)
            s->debar[k] = 0.0;
        for (size_t r = 0; r < nr; r++)
            s->y[r] = 0.0;
        rb_apply_J(s, prm, s->y, s->b);
        rb_cg_solve(s, prm);
        if (pass + 1 < prm->max_newton) {
            int changed = 0;
            for (size_t r = nv; r < nr; r++)
                if (s->ract[r] && s->y[r] > 0.0) {
                    s->ract[r] = 0;
                    changed = 1;
                }
            if (changed)
                continue;
        }
        break;
    }
    rb_apply_JT(s, prm, s->y);
    for (size_t i = 0; i < 3 * nv; i++)
        G[i] -= s->dx[i];
    for (int k = 0; k < s->ncomp; k++)
        s->debar[k] = -s->debar[k];
}

int rb_tension_step(void *sp, const tr_tension_params *prm, tr_tension_stats *out,
                            tr_error *err)
{
    ref_state *s = sp;
    size_t nv = s->nv;
    double *F = s->F, *G = s->G, *H = s->H;
    for (size_t i = 0; i < nv; i++) {
        double f[3] = {0, 0, 0}, u[3];
        if (s->next[i] >= 0) {
            edge_unit(s, i, u);
            v3_add(f, f, u);
        }
        if (s->prev[i] >= 0) {
            edge_unit(s, (size_t)s->prev[i], u);
            v3_sub(f, f, u);
        }
        memcpy(F + 3 * i, f, sizeof f);
    }
    memcpy(G, F, 3 * nv * sizeof *F);
    for (int pass = 0; pass < prm->smooth_passes; pass++) {
        for (size_t i = 0; i < nv; i++) {
            const double *g = G + 3 * i;
            double *h = H + 3 * i;
            ptrdiff_t pv = s->prev[i], nx = s->next[i];
            if (pv >= 0 && nx >= 0) {
                const double *gp = G + 3 * (size_t)pv, *gn = G + 3 * (size_t)nx;
                for (int k = 0; k < 3; k++)
                    h[k] = (gp[k] + 2.0 * g[k] + gn[k]) / 4.0;
            } else if (pv >= 0 || nx >= 0) {
                const double *gb = G + 3 * (size_t)(pv >= 0 ? pv : nx);
                for (int k = 0; k < 3; k++)
                    h[k] = (3.0 * g[k] + gb[k]) / 4.0;
            } else {
                memcpy(h, g, 3 * sizeof *h);
            }
        }
        double *t = G;
        G = H;
        H = t;
    }
    double smooth2 = 0.0, free2 = 0.0;
    for (size_t i = 0; i < nv; i++) {
        double g[3] = {G[3 * i], G[3 * i + 1], G[3 * i + 2]};
        rb_project_motion(s, i, g);
        smooth2 += v3_dot(g, g);
    }
    if (prm->project) {
        int rc = rb_ensure_rows(s, err);
        if (rc)
            return rc;
        project_tangent(s, prm->project, G);
        for (size_t i = 0; i < 3 * nv; i++)
            free2 += G[i] * G[i];
    } else {
        free2 = smooth2;
    }
    double force2 = 0.0, pred = 0.0, maxm = 0.0;
    for (size_t i = 0; i < nv; i++) {
        double f[3], d[3];
        memcpy(f, F + 3 * i, sizeof f);
        rb_project_motion(s, i, f);
        force2 += v3_dot(f, f);
        v3_scale(d, prm->h, G + 3 * i);
        rb_project_motion(s, i, d);
        double m = v3_norm(d);
        if (m > prm->max_move) {
            v3_scale(d, prm->max_move / m, d);
            m = prm->max_move;
        }
        if (m > maxm)
            maxm = m;
        pred += v3_dot(F + 3 * i, d);
        v3_add(s->x + 3 * i, s->x + 3 * i, d);
        rb_snap(s, i);
    }
    if (prm->project)
        for (int k = 0; k < s->ncomp; k++)
            s->ebar[k] += prm->h * s->debar[k];
    if (out) {
        out->force2 = force2;
        out->predicted = pred;
        out->max_move = maxm;
        out->smooth2 = smooth2;
        out->free2 = free2;
    }
    return TR_OK;
}

