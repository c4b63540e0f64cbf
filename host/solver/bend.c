/* This file contains a Newton step's bound on how far it bends the rope (bend.h). */
#include "solver/bend.h"

#include <math.h>

#include "util/vec3.h"

/* w_i of x into w; 0 where vertex i has no two neighbours */
static int second_difference(const tr_bend_chain *c, const double *x, size_t i, double w[3])
{
    size_t ip = c->prev[i], in = c->next[i];
    if (ip == TR_BEND_NONE || in == TR_BEND_NONE)
        return 0;
    for (int d = 0; d < 3; d++)
        w[d] = (x[3 * in + (size_t)d] - x[3 * i + (size_t)d]) - (x[3 * i + (size_t)d] - x[3 * ip + (size_t)d]);
    return 1;
}

double tr_bend_max_change(const tr_bend_chain *c, const double *dir)
{
    double m = 0.0;
    for (size_t i = 0; i < c->nv; i++) {
        double dw[3], l0 = c->l0[c->comp[i]];
        if (second_difference(c, dir, i, dw))
            m = fmax(m, v3_norm(dw) / (l0 * l0));
    }
    return m;
}

/* A vertex taken back lands between its trial position and the midpoint
 * of its neighbours' (x_i + f w1 with 0 < f < 1/2). Those lie within the
 * step's largest vertex move of where they were, and the old midpoint within
 * |w0| / 2 (a few l0^2) of x_i, so the step's bound on how far a vertex
 * moves, on which the strut list's safety rests (newton.h, "Never a
 * different knot"), still holds to within a few l0^2 a sweep. */
size_t tr_bend_take_back(const tr_bend_chain *c, const double *y, double *yt, double bend)
{
    size_t moved = 0;
    for (int sweep = 0; sweep < 4; sweep++) {
        size_t m = 0;
        for (size_t i = 0; i < c->nv; i++) {
            double w0[3], w1[3], l0 = c->l0[c->comp[i]], l02 = l0 * l0;
            if ((c->held && c->held[i]) || !second_difference(c, y, i, w0))
                continue;
            second_difference(c, yt, i, w1);
            double bound = (fmax(v3_norm(w0) / l02, 1.0) + bend) * l02, n1 = v3_norm(w1);
            if (n1 <= bound)
                continue;
            /* x_i += f w1 takes w_i to (1 - 2 f) w1 */
            double f = 0.5 * (1.0 - bound / n1);
            for (int d = 0; d < 3; d++)
                yt[3 * i + (size_t)d] += f * w1[d];
            m++;
        }
        moved += m;
        if (!m)
            break;
    }
    return moved;
}
