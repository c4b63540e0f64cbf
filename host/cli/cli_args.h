/* Numbers given on the command line. A value is accepted only when the whole
 * token is a decimal number, finite, and inside [lo, hi]: strtod alone takes
 * "", "3x" (as 3), "nan", "1e400" (as inf) and "0x10" without complaint. */
#ifndef TIGHTROPE_CLI_ARGS_H
#define TIGHTROPE_CLI_ARGS_H

#include <stddef.h>

/* 0 and *out set, or -1 and *out untouched. */
int tr_arg_double(const char *s, double lo, double hi, double *out);
int tr_arg_long(const char *s, long lo, long hi, long *out);
int tr_arg_int(const char *s, int lo, int hi, int *out);
int tr_arg_size(const char *s, size_t lo, size_t hi, size_t *out);

#endif
