/* Test helpers over the thickness oracle, for the tests of the layers at
 * or above it (testlib.h is below every layer). */
#ifndef TR_TESTLIB_ORACLE_H
#define TR_TESTLIB_ORACLE_H

#include <math.h>

#include "oracle/thickness.h"

/* The curve's ropelength as the oracle measures it (NaN where it fails). */
static inline double tr_test_ropelength(const tr_curve *c)
{
    tr_thickness th;
    tr_error err = {0};
    if (tr_thickness_measure(c, NULL, &th, NULL, &err))
        return NAN;
    return th.ropelength;
}

/* The curve's thickness as the oracle measures it (NaN where it fails). */
static inline double tr_test_thickness(const tr_curve *c)
{
    tr_thickness th;
    tr_error err = {0};
    if (tr_thickness_measure(c, NULL, &th, NULL, &err))
        return NAN;
    return th.thickness;
}

#endif
