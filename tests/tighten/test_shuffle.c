/* The crankshaft shuffle (tighten/shuffle.h), the start of tighten's
 * shuffled roads. Checked against the physics, not against its own output:
 * every kept move, replayed one at a time, moves no vertex by as much as
 * the thickness the oracle measures before it (so no two strands can meet
 * on the way: the knot type is kept) and leaves the thickness at or above
 * the gate; edge lengths are kept (rigid turns of an arc); the walk really
 * changes the shape (vertices move by several rope diameters, far beyond
 * the kicks under the radius of --tries); a shuffled Hopf link keeps its
 * Gauss linking number +-1; the ratchet compacts a thin rope (its
 * ropelength falls); the same seed gives the same curve, another seed
 * another; constrained or open curves and a start thinner than the gate are
 * refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/generate.h"
#include "tighten/shuffle.h"
#include "oracle/thickness.h"
#include "testlib.h"
#include "util/vec3.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double thickness(const tr_curve *c)
{
    tr_thickness t;
    tr_error err;
    CHECK_OK(tr_thickness_measure(c, NULL, &t, NULL, &err));
    return t.thickness;
}

static double ropelength(const tr_curve *c)
{
    tr_thickness t;
    tr_error err;
    CHECK_OK(tr_thickness_measure(c, NULL, &t, NULL, &err));
    return t.ropelength;
}

static void scale(tr_curve *c, double f)
{
    for (size_t i = 0; i < 3 * c->nv; i++)
        c->x[i] *= f;
}

/* the largest relative change of an edge's length from a to b */
static double edge_change(const tr_curve *a, const tr_curve *b)
{
    double worst = 0.0;
    for (int k = 0; k < a->ncomp; k++) {
        size_t s = a->start[k], n = tr_comp_nv(a, k);
        for (size_t i = 0; i < n; i++) {
            size_t j = s + (i + 1) % n;
            double la = sqrt(v3_dist2(a->x + 3 * (s + i), a->x + 3 * j));
            double lb = sqrt(v3_dist2(b->x + 3 * (s + i), b->x + 3 * j));
            worst = fmax(worst, fabs(lb - la) / la);
        }
    }
    return worst;
}

static double largest_move(const tr_curve *a, const tr_curve *b)
{
    double m = 0.0;
    for (size_t i = 0; i < a->nv; i++)
        m = fmax(m, sqrt(v3_dist2(a->x + 3 * i, b->x + 3 * i)));
    return m;
}

/* the two components' linking number (testlib.h) */
static double linking_number(const tr_curve *c)
{
    return tr_test_linking_number(c->x + 3 * c->start[0], tr_comp_nv(c, 0), c->x + 3 * c->start[1], tr_comp_nv(c, 1));
}

/* a trefoil of 96 vertices inflated to thickness 4: a thin rope (gate 1) */
static void thin_trefoil(tr_curve *c)
{
    tr_error err;
    CHECK_OK(tr_make_torus(c, 2, 3, 96, &err));
    scale(c, 4.0 / thickness(c));
}

static void test_moves_are_isotopies(void)
{
    tr_curve c, prev;
    tr_error err;
    thin_trefoil(&c);
    CHECK_OK(tr_curve_copy(&prev, &c, &err));
    tr_curve start;
    CHECK_OK(tr_curve_copy(&start, &c, &err));
    long kept = 0, tried = 3000;
    double worst_ratio = 0.0, worst_gate = INFINITY, worst_edge = 0.0;
    for (long k = 0; k < tried; k++) {
        double t0 = thickness(&c);
        memcpy(prev.x, c.x, 3 * c.nv * sizeof *c.x);
        long kk;
        CHECK_OK(tr_curve_shuffle(&c, 1, 1.0, 0.0, 1000u + (uint64_t)k, NULL, &kk, &err));
        if (!kk) {
            CHECK(memcmp(prev.x, c.x, 3 * c.nv * sizeof *c.x) == 0); /* a refused move changes nothing */
            continue;
        }
        kept++;
        worst_ratio = fmax(worst_ratio, largest_move(&prev, &c) / t0);
        worst_gate = fmin(worst_gate, thickness(&c));
        worst_edge = fmax(worst_edge, edge_change(&prev, &c));
    }
    double walked = largest_move(&start, &c);
    printf("trefoil: %ld of %ld moves kept; largest move / thickness before %.4f; thinnest %.4f; edge change "
           "%.2e; farthest vertex from the start %.2f (the rope's diameter at the gate: 2)\n",
           kept, tried, worst_ratio, worst_gate, worst_edge, walked);
    CHECK(kept > tried / 2);
    CHECK(worst_ratio < 0.9);
    CHECK(worst_gate >= 1.0);
    CHECK(worst_edge < 1e-12);
    CHECK(walked > 10.0);
    tr_curve_free(&start);
    tr_curve_free(&prev);
    tr_curve_free(&c);
}

static void test_hopf_keeps_linking(void)
{
    tr_curve c;
    tr_error err;
    CHECK_OK(tr_make_hopf(&c, 48, &err));
    scale(&c, 4.0 / thickness(&c));
    double lk0 = linking_number(&c);
    long kept;
    CHECK_OK(tr_curve_shuffle(&c, 5000, 1.0, 0.0, 3, NULL, &kept, &err));
    double lk1 = linking_number(&c);
    printf("hopf: %ld of 5000 moves kept, linking number %.9f -> %.9f, thickness %.4f\n", kept, lk0, lk1,
           thickness(&c));
    CHECK(kept > 1000);
    CHECK_NEAR(fabs(lk0), 1.0, 1e-6);
    CHECK_NEAR(lk1, lk0, 1e-6);
    CHECK(thickness(&c) >= 1.0);
    tr_curve_free(&c);
}

static void test_ratchet_and_seed(void)
{
    tr_curve a, b, d;
    tr_error err;
    thin_trefoil(&a);
    CHECK_OK(tr_curve_shuffle(&a, 5000, 1.0, 0.0, 11, NULL, NULL, &err));
    CHECK_OK(tr_curve_copy(&b, &a, &err));
    CHECK_OK(tr_curve_copy(&d, &a, &err));
    double before = ropelength(&a);
    long kept;
    CHECK_OK(tr_curve_shuffle(&a, 20000, 1.0, 0.98, 12, NULL, &kept, &err));
    double after = ropelength(&a);
    printf("ratchet 0.98: %ld of 20000 moves kept, ropelength %.3f -> %.3f\n", kept, before, after);
    CHECK(after < 0.97 * before);
    CHECK(thickness(&a) >= 1.0);
    /* the same seed, the same curve; another seed, another */
    CHECK_OK(tr_curve_shuffle(&b, 20000, 1.0, 0.98, 12, NULL, NULL, &err));
    CHECK(memcmp(a.x, b.x, 3 * a.nv * sizeof *a.x) == 0);
    CHECK_OK(tr_curve_shuffle(&d, 20000, 1.0, 0.98, 13, NULL, NULL, &err));
    CHECK(largest_move(&a, &d) > 1.0);
    tr_curve_free(&a);
    tr_curve_free(&b);
    tr_curve_free(&d);
}

static void test_refused(void)
{
    tr_curve c, k;
    tr_error err;
    thin_trefoil(&c);
    CHECK(tr_curve_shuffle(&c, 10, 5.0, 0.0, 1, NULL, NULL, &err) == TR_EGEOMETRY);
    CHECK_OK(tr_make_clasp(&k, 100, 1.5, &err));
    CHECK(tr_curve_shuffle(&k, 10, 0.5, 0.0, 1, NULL, NULL, &err) == TR_EINVAL);
    tr_curve_free(&k);
    tr_curve_free(&c);
}

/* A bound that has passed (the clock, or a raised stop flag) ends the walk
 * at once with TR_EINTERRUPTED, and what was walked is still a rope. */
static void test_bound(void)
{
    tr_curve c;
    tr_error err;
    thin_trefoil(&c);
    volatile sig_atomic_t stop = 1;
    tr_deadline raised = {.stop = &stop};
    long kept = -1;
    CHECK(tr_curve_shuffle(&c, 100000, 1.0, 0.0, 5, &raised, &kept, &err) == TR_EINTERRUPTED);
    CHECK(kept == 0);
    CHECK(strstr(err.msg, "signal") != NULL);
    tr_deadline past = {.at = tr_clock_seconds() - 1.0};
    CHECK(tr_curve_shuffle(&c, 100000, 1.0, 0.0, 5, &past, NULL, &err) == TR_EINTERRUPTED);
    CHECK(strstr(err.msg, "time limit") != NULL);
    /* 0.2 s of a walk that would take far longer: it stops within the next
     * SHUFFLE_CLOCK_EVERY moves, a valid walk */
    tr_deadline soon = {.at = tr_clock_seconds() + 0.2};
    double t0 = tr_clock_seconds();
    CHECK(tr_curve_shuffle(&c, 100000000, 1.0, 0.0, 6, &soon, &kept, &err) == TR_EINTERRUPTED);
    CHECK(tr_clock_seconds() - t0 < 2.0);
    CHECK(kept > 0);
    tr_thickness th;
    CHECK_OK(tr_thickness_measure(&c, NULL, &th, NULL, &err));
    CHECK(th.thickness >= 1.0);
    tr_curve_free(&c);
}

int main(void)
{
    test_bound();
    test_moves_are_isotopies();
    test_hopf_keeps_linking();
    test_ratchet_and_seed();
    test_refused();
    return tr_test_finish("test_shuffle");
}
