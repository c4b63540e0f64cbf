/* Curve container basics: allocation, component lookup, constraints, length. */
#include <math.h>

#include "curve/curve.h"
#include "testlib.h"

int main(void)
{
    tr_error err;
    tr_curve c;
    size_t nv[2] = {4, 3};
    unsigned char closed[2] = {1, 0};
    CHECK_OK(tr_curve_alloc(&c, 2, nv, closed, &err));
    CHECK(c.nv == 7);
    CHECK(tr_comp_ne(&c, 0) == 4 && tr_comp_ne(&c, 1) == 2);
    CHECK(tr_curve_comp_of(&c, 0) == 0 && tr_curve_comp_of(&c, 3) == 0);
    CHECK(tr_curve_comp_of(&c, 4) == 1 && tr_curve_comp_of(&c, 6) == 1);
    /* unit square (closed, length 4) and an open L of length 1 + 2 */
    const double sq[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const double el[9] = {5, 0, 0, 6, 0, 0, 6, 2, 0};
    for (int i = 0; i < 12; i++)
        c.x[i] = sq[i];
    for (int i = 0; i < 9; i++)
        c.x[12 + i] = el[i];
    CHECK_NEAR(tr_comp_length(&c, 0), 4.0, 1e-15);
    CHECK_NEAR(tr_comp_length(&c, 1), 3.0, 1e-15);
    CHECK_NEAR(tr_curve_length(&c), 7.0, 1e-15);

    tr_constraint plane = {.kind = TR_CST_PLANE, .id = 1, .u = {0, 0, 1}, .d = 2.0};
    int k = tr_curve_add_constraint(&c, &plane, &err);
    CHECK(k == 0);
    c.vcst[4] = k;
    double p[3] = {1, 2, 7};
    CHECK_NEAR(tr_constraint_violation(&c.cst[0], p), 5.0, 1e-15);
    tr_constraint_project(&c.cst[0], p);
    CHECK_NEAR(p[2], 2.0, 1e-15);
    tr_constraint line = {.kind = TR_CST_LINE, .p = {0, 0, 0}, .u = {1, 0, 0}};
    double q[3] = {3, 4, 0};
    CHECK_NEAR(tr_constraint_violation(&line, q), 4.0, 1e-15);

    tr_curve d;
    CHECK_OK(tr_curve_copy(&d, &c, &err));
    CHECK(d.ncst == 1 && d.vcst[4] == 0 && d.vcst[0] == -1);
    CHECK_NEAR(tr_curve_length(&d), 7.0, 1e-15);
    tr_curve_free(&d);
    tr_curve_free(&c);
    return tr_test_finish("test_curve");
}
