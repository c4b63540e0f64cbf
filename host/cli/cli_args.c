/* This file contains the whole-token number parsing of command-line values (cli_args.h). */
#include "cli/cli_args.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int tr_arg_double(const char *s, double lo, double hi, double *out)
{
    if (strpbrk(s, "xX")) /* strtod's hexadecimal ("0x10") */
        return -1;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno || !isfinite(v) || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int tr_arg_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int tr_arg_int(const char *s, int lo, int hi, int *out)
{
    long v;
    if (tr_arg_long(s, lo, hi, &v))
        return -1;
    *out = (int)v;
    return 0;
}

int tr_arg_size(const char *s, size_t lo, size_t hi, size_t *out)
{
    /* strtoull skips blanks and wraps "-1" (also " -1") to the largest value */
    if (!isdigit((unsigned char)s[0]))
        return -1;
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi)
        return -1;
    *out = (size_t)v;
    return 0;
}
