/* The thickness against a gate (oracle/thickness.h, tr_thickness_gate)
 * against the measure itself, an independent computation (the measure's
 * tree search against the gate's all-pairs enumeration): on knots, links,
 * open ropes and random polygons, moved about at random, at gates below,
 * at and above the thickness, the gate gives the measure's thickness bit
 * for bit where it is at or above the gate, and a number below the gate
 * and at or above the thickness where it is not; a curve through itself
 * gets 0, a curve far from the origin the measure's own number, a curve
 * the measure refuses is refused alike. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "curve/generate.h"
#include "oracle/thickness.h"
#include "testlib.h"

static uint64_t rng_next(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}
static double rng_unit(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1.0p-53; }

static long agreed, below;

/* c at its coordinates, at gates around its thickness and far from it */
static void compare_at_gates(tr_thickness_gate *g, const tr_curve *c, const char *what)
{
    tr_error err;
    tr_thickness t;
    CHECK_OK(tr_thickness_measure(c, NULL, &t, NULL, &err));
    const double gates[] = {0.0, 0.5 * t.thickness, nextafter(t.thickness, 0.0), t.thickness,
                            nextafter(t.thickness, INFINITY), 1.001 * t.thickness, 2.0 * t.thickness};
    for (size_t q = 0; q < sizeof gates / sizeof *gates; q++) {
        double th = -1.0;
        CHECK_OK(tr_thickness_gate_eval(g, c->x, gates[q], &th, &err));
        if (t.thickness >= gates[q]) {
            if (th != t.thickness)
                fprintf(stderr, "%s, gate %.17g: measure %.17g, gate %.17g\n", what, gates[q], t.thickness, th);
            CHECK(th == t.thickness);
            agreed++;
        } else {
            if (!(th < gates[q] && th >= t.thickness))
                fprintf(stderr, "%s, gate %.17g: measure %.17g, gate gave %.17g\n", what, gates[q], t.thickness,
                        th);
            CHECK(th < gates[q]);
            CHECK(th >= t.thickness);
            below++;
        }
    }
}

/* moves every vertex of c by up to amp at random, `rounds` times, comparing
 * after each */
static void jiggle_and_compare(tr_curve *c, double amp, int rounds, uint64_t seed, const char *what)
{
    tr_thickness_gate *g;
    tr_error err;
    CHECK_OK(tr_thickness_gate_new(c, &g, &err));
    uint64_t s = seed;
    compare_at_gates(g, c, what);
    for (int r = 0; r < rounds; r++) {
        for (size_t i = 0; i < 3 * c->nv; i++)
            c->x[i] += amp * (2.0 * rng_unit(&s) - 1.0);
        compare_at_gates(g, c, what);
    }
    tr_thickness_gate_free(g);
}

static void test_knots_and_links(void)
{
    tr_curve c;
    tr_error err;
    CHECK_OK(tr_make_torus(&c, 2, 3, 96, &err));
    jiggle_and_compare(&c, 0.02, 40, 1, "trefoil 96");
    tr_curve_free(&c);
    CHECK_OK(tr_make_torus(&c, 3, 5, 150, &err));
    jiggle_and_compare(&c, 0.01, 20, 2, "torus 3,5");
    tr_curve_free(&c);
    CHECK_OK(tr_make_hopf(&c, 48, &err));
    jiggle_and_compare(&c, 0.02, 40, 3, "hopf 2 x 48");
    tr_curve_free(&c);
    /* a regular polygon: many struts of equal length, MinRad everywhere the same */
    CHECK_OK(tr_make_circle(&c, 5.0, 40, &err));
    jiggle_and_compare(&c, 0.0, 0, 4, "circle 40");
    jiggle_and_compare(&c, 1e-3, 10, 5, "circle 40 jiggled");
    /* its first vertex pushed out: MinRad is there */
    for (int q = 0; q < 2; q++)
        c.x[q] *= 1.1;
    jiggle_and_compare(&c, 0.0, 0, 6, "circle 40, vertex 0 bent");
    tr_curve_free(&c);
}

/* open ropes (interior vertices' MinRad only, the last edge's rule) and
 * random polygons, whose strut can be anywhere */
static void test_open_and_random(void)
{
    uint64_t s = 99;
    for (int trial = 0; trial < 20; trial++) {
        size_t nv[2] = {20 + (size_t)(rng_unit(&s) * 30), 12 + (size_t)(rng_unit(&s) * 20)};
        unsigned char closed[2] = {(unsigned char)(trial % 2), (unsigned char)(trial % 3 != 0)};
        tr_curve c;
        tr_error err;
        CHECK_OK(tr_curve_alloc(&c, 2, nv, closed, &err));
        double p[3] = {0, 0, 0};
        for (size_t i = 0; i < c.nv; i++) {
            if (i == c.start[1])
                p[0] += 3.0; /* the second component beside the first */
            for (int q = 0; q < 3; q++) {
                p[q] += 2.0 * rng_unit(&s) - 1.0;
                c.x[3 * i + (size_t)q] = p[q];
            }
        }
        tr_thickness t;
        if (tr_thickness_measure(&c, NULL, &t, NULL, &err) != TR_OK) {
            tr_curve_free(&c); /* a walk through itself: the crossing test below */
            continue;
        }
        char what[64];
        snprintf(what, sizeof what, "random polygons, trial %d", trial);
        jiggle_and_compare(&c, 0.05, 5, 100 + (uint64_t)trial, what);
        tr_curve_free(&c);
    }
}

static void test_through_itself_and_far(void)
{
    tr_curve c;
    tr_error err;
    tr_thickness_gate *g;
    tr_thickness t;
    double th;
    /* a square whose vertex 2 is moved onto edge 0: the rope passes through itself */
    const size_t n = 6;
    CHECK_OK(tr_curve_alloc(&c, 1, &n, NULL, &err));
    const double xyz[] = {0, 0, 0, 4, 0, 0, 4, 4, 0, 2, 4, 0, 2, 0, 0, 0, 4, 0};
    memcpy(c.x, xyz, sizeof xyz);
    CHECK(tr_thickness_measure(&c, NULL, &t, NULL, &err) == TR_EGEOMETRY);
    CHECK_OK(tr_thickness_gate_new(&c, &g, &err));
    CHECK_OK(tr_thickness_gate_eval(g, c.x, 0.0, &th, &err));
    CHECK(th == 0.0);
    tr_thickness_gate_free(g);
    tr_curve_free(&c);

    /* far from the origin for its size: measured in the measure's frame */
    CHECK_OK(tr_make_torus(&c, 2, 3, 96, &err));
    for (size_t i = 0; i < c.nv; i++)
        c.x[3 * i] += ldexp(1.0, 30);
    CHECK_OK(tr_thickness_gate_new(&c, &g, &err));
    jiggle_and_compare(&c, 0.01, 3, 7, "trefoil at 2^30");
    /* beyond the doubles' resolution, or not finite: refused as the measure refuses */
    for (size_t i = 0; i < c.nv; i++)
        c.x[3 * i] += 1e300;
    CHECK(tr_thickness_measure(&c, NULL, &t, NULL, &err) == TR_EGEOMETRY);
    CHECK(tr_thickness_gate_eval(g, c.x, 1.0, &th, &err) == TR_EGEOMETRY);
    c.x[4] = NAN;
    CHECK(tr_thickness_gate_eval(g, c.x, 1.0, &th, &err) == TR_EGEOMETRY);
    tr_thickness_gate_free(g);
    tr_curve_free(&c);
}

int main(void)
{
    test_knots_and_links();
    test_open_and_random();
    test_through_itself_and_far();
    printf("gate against the measure: %ld agreed bit for bit, %ld below the gate and proved so\n", agreed, below);
    CHECK(agreed > 500 && below > 300);
    return tr_test_finish("test_thickness_gate");
}
