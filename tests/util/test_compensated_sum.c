/* This file contains the test of the compensated (Neumaier) sum
 * (util/compensated_sum.h): sums a plain double sum gets wrong and the
 * compensated one gets exactly right. */
#include <math.h>

#include "testlib.h"
#include "util/compensated_sum.h"

int main(void)
{
    /* Neumaier's case: a term larger than the running sum (Kahan's sum gives 0) */
    const double big[] = {1.0, 1e100, 1.0, -1e100};
    tr_csum s = {0.0, 0.0};
    double plain = 0.0;
    for (int i = 0; i < 4; i++) {
        tr_csum_add(&s, big[i]);
        plain += big[i];
    }
    CHECK(plain == 0.0);
    CHECK(tr_csum_value(&s) == 2.0);

    /* 10^6 edges of 0.1 (not a binary fraction): the plain sum drifts by
     * ~1e-6; the compensated one is the correctly rounded 1e5 */
    tr_csum e = {0.0, 0.0};
    plain = 0.0;
    for (int i = 0; i < 1000000; i++) {
        tr_csum_add(&e, 0.1);
        plain += 0.1;
    }
    CHECK(fabs(plain - 1e5) > 1e-7);
    CHECK(tr_csum_value(&e) == 1e5);

    /* a start value: {t0, 0} then t0 + the increments */
    tr_csum t = {3.0, 0.0};
    tr_csum_add(&t, 0.25);
    tr_csum_add(&t, -1.0);
    CHECK(tr_csum_value(&t) == 2.25);
    return tr_test_finish("test_compensated_sum");
}
