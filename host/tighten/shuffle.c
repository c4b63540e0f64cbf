/* This file contains the crankshaft shuffle of a start curve, the shuffled
 * roads of tighten --shuffles (shuffle.h). */
#include "tighten/shuffle.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oracle/thickness.h"
#include "util/splitmix64.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* uniform in [0, 1) */
#define SHUFFLE_CLOCK_EVERY 64

static double shuffle_uniform(uint64_t *state) { return (double)(tr_splitmix64(state) >> 11) * 0x1.0p-53; }

/* turns the m - 1 vertices after vertex a (cyclically, on a component of
 * n vertices from vertex s0) about the axis through p with unit direction
 * u by angle th, into y (which holds a copy of x) */
static void turn_arc(const double *x, double *y, size_t s0, size_t n, size_t a, size_t m, const double *p,
                     const double *u, double th)
{
    double cs = cos(th), sn = sin(th);
    for (size_t q = 1; q < m; q++) {
        size_t i = s0 + (a + q) % n;
        double v[3] = {x[3 * i] - p[0], x[3 * i + 1] - p[1], x[3 * i + 2] - p[2]};
        double d = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        double w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        for (int r = 0; r < 3; r++) /* Rodrigues */
            y[3 * i + (size_t)r] = p[r] + v[r] * cs + w[r] * sn + u[r] * d * (1.0 - cs);
    }
}

int tr_curve_shuffle(tr_curve *c, long moves, double gate, double ratchet, uint64_t seed, const tr_deadline *bound,
                     long *kept, tr_error *err)
{
    if (kept)
        *kept = 0;
    if (c->ncst > 0)
        return tr_fail(err, TR_EINVAL, "shuffle: the curve has constraints");
    for (int k = 0; k < c->ncomp; k++)
        if (!c->closed[k] || tr_comp_nv(c, k) < 4)
            return tr_fail(err, TR_EINVAL, "shuffle: component %d is open or has fewer than 4 vertices", k);
    tr_curve_drop_lo(c); /* the moves are in doubles */
    tr_thickness t0;
    int rc = tr_thickness_measure(c, NULL, &t0, NULL, err);
    if (rc)
        return rc;
    double t = t0.thickness;
    if (!(t >= gate && isfinite(t)))
        return tr_fail(err, TR_EGEOMETRY, "shuffle: thickness %g below the gate %g", t, gate);
    /* Each move asks whether the thickness stays at or above the gate, and
     * what it is then: the oracle's gate gives the measure's number where
     * it is, and stops at the first vertex or strut below the gate where
     * not (most of a ratchet's moves). The same walk bit for bit, 6.2
     * times faster for 9_3 at 96 vertices (the first recipe of roads.c: 20 s
     * -> 3.2 s), 3.1 times for a link of 3 x 96 (bench/notes/2026-11-30-shuffle-gate.md). */
    tr_thickness_gate *tg;
    if ((rc = tr_thickness_gate_new(c, &tg, err)))
        return rc;
    double *y = malloc(3 * c->nv * sizeof *y);
    if (!y) {
        tr_thickness_gate_free(tg);
        return tr_fail(err, TR_ENOMEM, "out of memory (shuffle)");
    }
    memcpy(y, c->x, 3 * c->nv * sizeof *y);
    uint64_t state = seed;
    long nk = 0;
    for (long mv = 0; mv < moves; mv++) {
        /* a move costs a thickness measure: 10^5 of them are seconds to
         * tens of seconds (more under load), so the bound is looked at
         * every SHUFFLE_CLOCK_EVERY moves */
        int past = mv % SHUFFLE_CLOCK_EVERY == 0 ? tr_deadline_passed(bound) : 0;
        if (past) {
            rc = tr_fail(err, TR_EINTERRUPTED, "shuffle: %s after %ld of %ld moves",
                         past == 2 ? "stopped by a signal" : "the time limit came", mv, moves);
            break;
        }
        /* a component by its share of the vertices, an arc of 2 to n/2 edges */
        size_t i0 = (size_t)(shuffle_uniform(&state) * (double)c->nv);
        int k = tr_curve_comp_of(c, i0 < c->nv ? i0 : c->nv - 1);
        size_t s0 = c->start[k], n = tr_comp_nv(c, k);
        size_t a = (size_t)(shuffle_uniform(&state) * (double)n) % n;
        size_t m = 2 + (size_t)(shuffle_uniform(&state) * (double)(n / 2 - 1));
        double sgn = shuffle_uniform(&state) < 0.5 ? -1.0 : 1.0, frac = shuffle_uniform(&state);
        if (m > n / 2)
            m = n / 2;
        const double *p = c->x + 3 * (s0 + a), *q = c->x + 3 * (s0 + (a + m) % n);
        double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        if (!(ul > 0.0))
            continue;
        for (int r = 0; r < 3; r++)
            u[r] /= ul;
        /* the farthest turned vertex from the axis bounds every move */
        double rho = 0.0;
        for (size_t j = 1; j < m; j++) {
            const double *v = c->x + 3 * (s0 + (a + j) % n);
            double w[3] = {v[0] - p[0], v[1] - p[1], v[2] - p[2]};
            double d = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
            rho = fmax(rho, sqrt(fmax(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - d * d, 0.0)));
        }
        if (!(rho > 0.0))
            continue;
        double th = sgn * frac * fmin(0.9 * t / rho, M_PI);
        turn_arc(c->x, y, s0, n, a, m, p, u, th);
        double ty;
        if ((rc = tr_thickness_gate_eval(tg, y, gate, &ty, err)))
            break;
        if (ty >= gate && isfinite(ty)) {
            for (size_t j = 1; j < m; j++) {
                size_t i = s0 + (a + j) % n;
                memcpy(c->x + 3 * i, y + 3 * i, 3 * sizeof *y);
            }
            t = ty;
            gate = fmax(gate, ratchet * t);
            nk++;
        } else {
            for (size_t j = 1; j < m; j++) {
                size_t i = s0 + (a + j) % n;
                memcpy(y + 3 * i, c->x + 3 * i, 3 * sizeof *y);
            }
        }
    }
    free(y);
    tr_thickness_gate_free(tg);
    if (kept)
        *kept = nk;
    return rc;
}
