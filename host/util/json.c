/* This file contains the JSON writers of strings and numbers (json.h). */
#include "util/json.h"

#include <math.h>
#include <stdlib.h>

void tr_json_string(tr_text *t, const char *s)
{
    tr_text_printf(t, "\"");
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            tr_text_printf(t, "\\%c", c);
        else if (c < 0x20)
            tr_text_printf(t, "\\u%04x", c);
        else
            tr_text_printf(t, "%c", c);
    }
    tr_text_printf(t, "\"");
}

void tr_json_number(tr_text *t, const char *fmt, double v)
{
    if (!isfinite(v)) {
        tr_text_printf(t, "null");
        return;
    }
    tr_text_printf(t, fmt, v);
}

void tr_json_fputs(FILE *f, const char *s)
{
    tr_text t = {0};
    tr_json_string(&t, s);
    char *out = tr_text_take(&t, NULL);
    /* out of memory: an empty string keeps the document well formed */
    fputs(out ? out : "\"\"", f);
    free(out);
}
