/* Tests the tightening's knot-type check (tighten/knot_type.h) on curves
 * whose types are known: the (2,3) torus knot is the trefoil (Alexander
 * polynomial t^-1 - 1 + t, determinant 3), the closure of the braid
 * sigma_1 sigma_2^-1 sigma_1 sigma_2^-1 the figure eight (-t^-1 + 3 - t,
 * determinant 5), a curve and its mirror image (z -> -z) differ in the
 * signature's sign, and the Hopf link's mirror image in its linking
 * number's; a rigid motion and a scaling keep everything. A split link of
 * a circle and a trefoil is not one of two circles, though every linking
 * number is 0 in both: the components' own types tell them apart. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curve/braid_closure.h"
#include "curve/generate.h"
#include "tighten/knot_type.h"
#include "testlib.h"

static void mirror(tr_curve *c)
{
    for (size_t i = 0; i < c->nv; i++)
        c->x[3 * i + 2] = -c->x[3 * i + 2];
}

static void move(tr_curve *c)
{
    /* turned about z by 0.7, scaled by 3, shifted */
    double cs = cos(0.7), sn = sin(0.7);
    for (size_t i = 0; i < c->nv; i++) {
        double *p = c->x + 3 * i, x = p[0], y = p[1];
        p[0] = 3.0 * (cs * x - sn * y) + 5.0;
        p[1] = 3.0 * (sn * x + cs * y) - 2.0;
        p[2] = 3.0 * p[2] + 1.0;
    }
}

/* a and b side by side, 60 apart along x: a split link of two components */
static void split_link(const tr_curve *a, const tr_curve *b, tr_curve *out)
{
    tr_error err = {0};
    size_t nv[2] = {a->nv, b->nv};
    unsigned char closed[2] = {1, 1};
    REQUIRE_OK(tr_curve_alloc(out, 2, nv, closed, &err));
    memcpy(out->x, a->x, 3 * a->nv * sizeof *out->x);
    for (size_t i = 0; i < b->nv; i++) {
        out->x[3 * (a->nv + i)] = b->x[3 * i] + 60.0;
        out->x[3 * (a->nv + i) + 1] = b->x[3 * i + 1];
        out->x[3 * (a->nv + i) + 2] = b->x[3 * i + 2];
    }
}

static void test_split_links(void)
{
    tr_error err = {0};
    tr_curve circle = {0}, tref = {0}, two_circles = {0}, circle_tref = {0};
    REQUIRE_OK(tr_make_circle(&circle, 7.0, 60, &err));
    REQUIRE_OK(tr_make_torus(&tref, 2, 3, 120, &err));
    split_link(&circle, &circle, &two_circles);
    split_link(&circle, &tref, &circle_tref);
    tt_knot_type *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    if (!a || !b) {
        CHECK(a && b);
        free(a);
        free(b);
        return;
    }
    tt_knot_type_of(&two_circles, a);
    tt_knot_type_of(&circle_tref, b);
    CHECK(a->known && b->known && a->tc.components == 2 && b->tc.components == 2);
    CHECK(a->tc.linking[0] == 0 && b->tc.linking[0] == 0);
    CHECK(a->tc.comp[1].alexander.determinant == 1 && b->tc.comp[1].alexander.determinant == 3);
    CHECK(tt_knot_type_same(a, a));
    CHECK(!tt_knot_type_same(a, b));
    /* the trefoil component mirrored: the same determinant and
     * polynomial, the opposite signature */
    tt_knot_type_of(&circle_tref, a);
    for (size_t i = circle.nv; i < circle_tref.nv; i++)
        circle_tref.x[3 * i + 2] = -circle_tref.x[3 * i + 2];
    tt_knot_type_of(&circle_tref, b);
    CHECK(a->known && b->known && a->tc.comp_known[1] && b->tc.comp_known[1]);
    CHECK(b->tc.comp[1].alexander.determinant == 3 && b->tc.comp[1].signature == -a->tc.comp[1].signature);
    CHECK(a->tc.comp[1].signature != 0);
    CHECK(!tt_knot_type_same(a, b));
    free(a);
    free(b);
    tr_curve_free(&circle);
    tr_curve_free(&tref);
    tr_curve_free(&two_circles);
    tr_curve_free(&circle_tref);
}

static void test_types(void)
{
    tr_error err = {0};
    tr_curve tref = {0}, tref2 = {0}, eight = {0}, hopf = {0};
    REQUIRE_OK(tr_make_torus(&tref, 2, 3, 300, &err));
    REQUIRE_OK(tr_curve_copy(&tref2, &tref, &err));
    int w8[4] = {1, -2, 1, -2};
    REQUIRE_OK(tr_make_braid_closure(&eight, 3, w8, 4, 40, &err));
    REQUIRE_OK(tr_make_hopf(&hopf, 60, &err));
    tt_knot_type *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    if (!a || !b) {
        CHECK(a && b);
        return;
    }

    tt_knot_type_of(&tref, a);
    CHECK(a->known && a->tc.components == 1);
    CHECK(a->tc.inv.alexander.determinant == 3);
    CHECK(abs(a->tc.inv.signature) == 2);
    move(&tref2);
    tt_knot_type_of(&tref2, b);
    CHECK(tt_knot_type_same(a, b));
    mirror(&tref2);
    tt_knot_type_of(&tref2, b);
    CHECK(b->known && b->tc.components == 1 && b->tc.inv.signature == -a->tc.inv.signature);
    CHECK(!tt_knot_type_same(a, b));
    tt_knot_type_of(&eight, b);
    CHECK(b->known && b->tc.components == 1 && b->tc.inv.alexander.determinant == 5);
    CHECK(!tt_knot_type_same(a, b));

    tt_knot_type_of(&hopf, a);
    CHECK(a->known && a->tc.components == 2 && abs(a->tc.linking[0]) == 1);
    CHECK(tt_knot_type_same(a, a));
    mirror(&hopf);
    tt_knot_type_of(&hopf, b);
    CHECK(b->known && b->tc.linking[0] == -a->tc.linking[0]);
    CHECK(!tt_knot_type_same(a, b));

    /* an open rope has no type to keep */
    tref.closed[0] = 0;
    tt_knot_type_of(&tref, a);
    CHECK(!a->known && strstr(a->why, "open"));

    free(a);
    free(b);
    tr_curve_free(&tref);
    tr_curve_free(&tref2);
    tr_curve_free(&eight);
    tr_curve_free(&hopf);
}

int main(void)
{
    test_types();
    test_split_links();
    return tr_test_finish("test_knot_type");
}
