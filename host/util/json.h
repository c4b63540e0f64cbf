/* The two JSON values every --json writer needs and C's printf gets wrong:
 * strings (device names, file names and error messages can hold quotes,
 * backslashes or control characters) and numbers (JSON has no NaN or
 * infinity, which printf writes as "nan" and "inf"). */
#ifndef TIGHTROPE_JSON_H
#define TIGHTROPE_JSON_H

#include <stdio.h>

#include "util/text_file.h"

/* Appends s as a quoted JSON string, escaping '"', '\\' and control characters. */
void tr_json_string(tr_text *t, const char *s);

/* Appends v with the printf format fmt (one double conversion), or null
 * where v is not finite. */
void tr_json_number(tr_text *t, const char *fmt, double v);

/* tr_json_string to a stream (the commands that print JSON as they go). */
void tr_json_fputs(FILE *f, const char *s);

#endif
