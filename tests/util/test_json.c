/* The JSON writers' strings and numbers, against RFC 8259: '"' and '\\' are
 * escaped with a backslash, control characters (< 0x20) as \u00XX, other
 * bytes (UTF-8 included) pass through; JSON has no NaN or infinity. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/json.h"
#include "testlib.h"

static int string_is(const char *in, const char *want)
{
    tr_text t = {0};
    tr_json_string(&t, in);
    char *got = tr_text_take(&t, NULL);
    int ok = got && !strcmp(got, want);
    if (!ok)
        tr_test_report(__FILE__, __LINE__, "tr_json_string(\"%s\") = %s, want %s", in,
                       got ? got : "(null)", want);
    free(got);
    return ok;
}

static int number_is(const char *fmt, double v, const char *want)
{
    tr_text t = {0};
    tr_json_number(&t, fmt, v);
    char *got = tr_text_take(&t, NULL);
    int ok = got && !strcmp(got, want);
    if (!ok)
        tr_test_report(__FILE__, __LINE__, "tr_json_number(%s, %g) = %s, want %s", fmt, v,
                       got ? got : "(null)", want);
    free(got);
    return ok;
}

int main(void)
{
    CHECK(string_is("", "\"\""));
    CHECK(string_is("trefoil_2400.vect", "\"trefoil_2400.vect\""));
    CHECK(string_is("a\"b", "\"a\\\"b\""));
    CHECK(string_is("C:\\knots", "\"C:\\\\knots\""));
    CHECK(string_is("line\nnext\ttab\r", "\"line\\u000anext\\u0009tab\\u000d\""));
    CHECK(string_is("\x01\x1f ", "\"\\u0001\\u001f \""));
    CHECK(string_is("Przyby\xc5\x82", "\"Przyby\xc5\x82\"")); /* UTF-8 as is */

    CHECK(number_is("%.17g", 0.5, "0.5"));
    CHECK(number_is("%.3g", 32.7429, "32.7"));
    CHECK(number_is("%.17g", -0.0, "-0"));
    CHECK(number_is("%.17g", NAN, "null"));
    CHECK(number_is("%.6g", HUGE_VAL, "null"));
    CHECK(number_is("%.6g", -HUGE_VAL, "null"));
    return tr_test_finish("test_json");
}
