/* Tests the Newton step's bend bounds (solver/bend.h) on a regular polygon,
 * whose second differences have the closed form |w| = 2 l sin(pi / n) *
 * ... = 4 r sin^2(pi / n): the largest change of a step that moves one
 * vertex, and the bends of a kinked trial point taken back to
 * max(kappa, 1) + bend with nothing else moved, a held vertex left where it
 * is, and the ends of an open rope untouched. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "solver/bend.h"
#include "testlib.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define NV 64

typedef struct polygon {
    double x[3 * NV];
    size_t prev[NV], next[NV];
    int comp[NV];
    double l0;
} polygon;

/* the regular NV-gon of circumradius r in the xy plane, closed or open */
static void make_polygon(polygon *p, double r, int closed)
{
    for (size_t i = 0; i < NV; i++) {
        double a = 2.0 * M_PI * (double)i / NV;
        p->x[3 * i] = r * cos(a);
        p->x[3 * i + 1] = r * sin(a);
        p->x[3 * i + 2] = 0.0;
        p->prev[i] = i == 0 ? (closed ? NV - 1 : TR_BEND_NONE) : i - 1;
        p->next[i] = i == NV - 1 ? (closed ? 0 : TR_BEND_NONE) : i + 1;
        p->comp[i] = 0;
    }
    p->l0 = 2.0 * r * sin(M_PI / NV);
}

/* |w_i| / l0^2 of x */
static double bend_at(const polygon *p, const double *x, size_t i)
{
    size_t a = p->prev[i], b = p->next[i];
    double s = 0.0;
    for (int d = 0; d < 3; d++) {
        double w = x[3 * b + d] - 2.0 * x[3 * i + d] + x[3 * a + d];
        s += w * w;
    }
    return sqrt(s) / (p->l0 * p->l0);
}

int main(void)
{
    polygon p;
    /* radius 2: curvature about 1/2, the bound 1 + bend is what counts */
    make_polygon(&p, 2.0, 1);
    tr_bend_chain c = {.nv = NV, .prev = p.prev, .next = p.next, .comp = p.comp, .l0 = &p.l0, .held = NULL};
    /* the polygon's own bend: 4 r sin^2(pi / n) / l0^2 = 1 / r for any n */
    double k0 = bend_at(&p, p.x, 5);
    CHECK_NEAR(k0, 4.0 * 2.0 * sin(M_PI / NV) * sin(M_PI / NV) / (p.l0 * p.l0), 1e-12);
    CHECK_NEAR(k0, 0.5, 1e-12);

    /* one vertex moved by e: its own w changes by -2 e, its neighbours' by e */
    double dir[3 * NV];
    memset(dir, 0, sizeof dir);
    dir[3 * 17 + 2] = 0.3 * p.l0 * p.l0;
    CHECK_NEAR(tr_bend_max_change(&c, dir), 0.6, 1e-12);

    /* a trial point within every bound: nothing moves */
    double yt[3 * NV];
    memcpy(yt, p.x, sizeof yt);
    for (size_t i = 0; i < NV; i++)
        yt[3 * i + 2] += 0.01 * p.l0 * p.l0 * sin((double)i);
    double keep[3 * NV];
    memcpy(keep, yt, sizeof keep);
    CHECK(tr_bend_take_back(&c, p.x, yt, 0.05) == 0);
    CHECK(memcmp(yt, keep, sizeof yt) == 0);

    /* a kink at vertex 17: pushed inward so its bend is 3 (and its
     * neighbours' past 1 too) */
    memcpy(yt, p.x, sizeof yt);
    for (int d = 0; d < 2; d++)
        yt[3 * 17 + d] *= 1.0 - 2.5 * p.l0 * p.l0 / 2.0;
    CHECK(bend_at(&p, yt, 17) > 2.9);
    CHECK(tr_bend_take_back(&c, p.x, yt, 0.05) > 0);
    double worst = 0.0;
    for (size_t i = 0; i < NV; i++)
        worst = fmax(worst, bend_at(&p, yt, i) - (fmax(bend_at(&p, p.x, i), 1.0) + 0.05));
    CHECK(worst <= 1e-12);
    /* only the kink and its neighbours moved */
    for (size_t i = 0; i < NV; i++)
        if (i < 15 || i > 19)
            for (int d = 0; d < 3; d++)
                CHECK(yt[3 * i + d] == p.x[3 * i + d]);

    /* the kinked vertex held: it stays, and its bend is left as it is */
    unsigned char held[NV] = {0};
    held[17] = 1;
    c.held = held;
    memcpy(yt, p.x, sizeof yt);
    for (int d = 0; d < 2; d++)
        yt[3 * 17 + d] *= 1.0 - 2.5 * p.l0 * p.l0 / 2.0;
    memcpy(keep, yt, sizeof keep);
    tr_bend_take_back(&c, p.x, yt, 0.05);
    for (int d = 0; d < 3; d++)
        CHECK(yt[3 * 17 + d] == keep[3 * 17 + d]);
    c.held = NULL;

    /* an open rope: its end vertices have no bend and are not moved, even
     * where the step kinks the rope next to them */
    make_polygon(&p, 2.0, 0);
    memcpy(yt, p.x, sizeof yt);
    for (int d = 0; d < 2; d++)
        yt[3 * 1 + d] *= 1.0 - 2.5 * p.l0 * p.l0 / 2.0;
    CHECK(tr_bend_take_back(&c, p.x, yt, 0.05) > 0);
    for (int d = 0; d < 3; d++) {
        CHECK(yt[d] == p.x[d]);
        CHECK(yt[3 * (NV - 1) + d] == p.x[3 * (NV - 1) + d]);
    }
    CHECK(bend_at(&p, yt, 1) <= 1.05 + 1e-12);

    return tr_test_finish("test_bend");
}
