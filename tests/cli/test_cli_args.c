/* Command-line numbers: the whole token, finite, in range; the cases
 * strtod and strtoull take silently are refused. */
#include <math.h>
#include <stdint.h>

#include "cli/cli_args.h"
#include "testlib.h"

int main(void)
{
    double d = 7;
    CHECK(tr_arg_double("2.5", 0, 10, &d) == 0 && d == 2.5);
    CHECK(tr_arg_double("1e-3", 0, 10, &d) == 0 && d == 1e-3);
    d = 7;
    CHECK(tr_arg_double("", 0, 10, &d) == -1);
    CHECK(tr_arg_double("3x", 0, 10, &d) == -1);
    CHECK(tr_arg_double("nan", -HUGE_VAL, HUGE_VAL, &d) == -1);
    CHECK(tr_arg_double("inf", -HUGE_VAL, HUGE_VAL, &d) == -1);
    CHECK(tr_arg_double("1e400", -HUGE_VAL, HUGE_VAL, &d) == -1);
    CHECK(tr_arg_double("-0.1", 0, 10, &d) == -1);
    CHECK(tr_arg_double("10.5", 0, 10, &d) == -1);
    CHECK(d == 7); /* untouched on failure */

    long l = 0;
    CHECK(tr_arg_long("42", 1, 100, &l) == 0 && l == 42);
    CHECK(tr_arg_long("0", 1, 100, &l) == -1);
    CHECK(tr_arg_long("4.2", 1, 100, &l) == -1);
    CHECK(tr_arg_long("99999999999999999999", 1, 100, &l) == -1); /* ERANGE */
    int i = 0;
    CHECK(tr_arg_int("-3", -5, 5, &i) == 0 && i == -3);
    CHECK(tr_arg_int("2147483648", INT32_MIN, INT32_MAX, &i) == -1);

    size_t n = 0;
    CHECK(tr_arg_size("400", 3, 1000, &n) == 0 && n == 400);
    CHECK(tr_arg_size("-1", 0, SIZE_MAX, &n) == -1); /* strtoull would give SIZE_MAX */
    CHECK(tr_arg_size(" 5", 0, 10, &n) == -1);
    CHECK(tr_arg_size(" -1", 0, SIZE_MAX, &n) == -1);
    CHECK(tr_arg_size("2", 3, 10, &n) == -1);
    return tr_test_finish("test_cli_args");
}
