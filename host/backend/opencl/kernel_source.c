/* This file contains the loading of the kernel sources: the embedded copies, or
 * TIGHTROPE_KERNEL_DIR's files, each behind a #line directive naming its file
 * (kernel_source.h). */
#include "backend/opencl/kernel_source.h"
#include "util/text_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "#line 1 \"<where>\"\n" + text + a final newline if text lacks one, in a
 * new string: the compiler's diagnostics and the debug information (from
 * which Oclgrind names lines) then count lines of the file itself, not of
 * the program the sources are concatenated into, and the next source's own
 * directive starts a line of its own. A quote, a backslash or a control
 * character in `where` (a kernel directory's path) is escaped or replaced,
 * so the directive stays one well-formed string literal. */
static int with_line_directive(const char *where, const char *text, size_t size, char **out,
                               tr_error *err)
{
    size_t wlen = strlen(where);
    size_t cap = sizeof "#line 1 \"\"\n" + 2 * wlen + size + 1;
    char *s = malloc(cap);
    if (!s)
        return tr_fail(err, TR_ENOMEM, "out of memory preparing kernel %s", where);
    size_t w = 0;
    memcpy(s, "#line 1 \"", 9);
    w = 9;
    for (const char *p = where; *p; p++) {
        if (*p == '"' || *p == '\\')
            s[w++] = '\\';
        s[w++] = (unsigned char)*p < 0x20 ? '?' : *p;
    }
    memcpy(s + w, "\"\n", 2);
    w += 2;
    memcpy(s + w, text, size);
    w += size;
    if (size == 0 || text[size - 1] != '\n')
        s[w++] = '\n';
    s[w] = '\0';
    *out = s;
    return TR_OK;
}

int tr_kernel_source_load(const char *name, char **text, tr_error *err)
{
    const char *dir = getenv("TIGHTROPE_KERNEL_DIR");
    if (dir && *dir) {
        char path[4096];
        if (snprintf(path, sizeof path, "%s/%s", dir, name) >= (int)sizeof path)
            return tr_fail(err, TR_EINVAL, "kernel path %s/%s too long", dir, name);
        char *raw = NULL;
        size_t size = 0;
        int rc = tr_read_file(path, &raw, &size, err);
        if (rc == TR_OK)
            rc = with_line_directive(path, raw, size, text, err);
        free(raw);
        return rc;
    }
    for (const tr_kernel_source *k = tr_kernel_sources; k->name; k++)
        if (strcmp(k->name, name) == 0) {
            char where[256];
            snprintf(where, sizeof where, "kernels/%s", name);
            return with_line_directive(where, k->text, k->size, text, err);
        }
    return tr_fail(err, TR_EINVAL, "no embedded kernel source named %s", name);
}

/* The file name in the "#line 1 \"NAME\"" that starts s, unescaped, into
 * buf ("" when s has none). */
static void directive_name(const char *s, char *buf, size_t n)
{
    size_t w = 0;
    buf[0] = '\0';
    if (strncmp(s, "#line 1 \"", 9))
        return;
    for (const char *p = s + 9; *p && *p != '"' && *p != '\n' && w + 1 < n; p++) {
        if (*p == '\\' && p[1])
            p++;
        buf[w++] = *p;
    }
    buf[w] = '\0';
}

static int ends_with(const char *s, size_t len, const char *tail)
{
    size_t t = strlen(tail);
    return len >= t && !memcmp(s + len - t, tail, t);
}

char *tr_kernel_log_locate(const char *log, const char *const *src, int nsrc)
{
    enum { MAXSRC = 64 };
    char names[MAXSRC][512];
    long first[MAXSRC + 1]; /* the line of the whole program holding src[i]'s directive */
    if (nsrc > MAXSRC)
        nsrc = MAXSRC;
    first[0] = 1;
    for (int i = 0; i < nsrc; i++) {
        directive_name(src[i], names[i], sizeof names[i]);
        long lines = 0;
        for (const char *p = src[i]; *p; p++)
            lines += *p == '\n';
        first[i + 1] = first[i] + lines;
    }
    tr_text out = {0};
    const char *done = log;
    for (const char *p = log; *p; p++) {
        if (*p != ':' || p[1] < '0' || p[1] > '9')
            continue;
        const char *q = p + 1;
        long line = 0;
        while (*q >= '0' && *q <= '9' && line < 100000000)
            line = 10 * line + (*q++ - '0');
        if (*q != ':')
            continue;
        const char *t = p; /* the location's file name: back to a space or a quote */
        while (t > done && !strchr(" \t\n'\"(", t[-1]))
            t--;
        size_t tlen = (size_t)(p - t);
        /* NVIDIA's compiler names the whole program "<kernel>" */
        int program = tlen == 8 && !memcmp(t, "<kernel>", 8);
        if (!tlen || !(program || ends_with(t, tlen, ".cl") || ends_with(t, tlen, ".clh")))
            continue;
        int named = 0, in = -1;
        for (int i = 0; i < nsrc; i++) {
            /* the end of a name (the token stops at a space or a quote in it) */
            size_t nlen = strlen(names[i]);
            named |= !program && nlen >= tlen && !memcmp(names[i] + nlen - tlen, t, tlen);
            if (line > first[i] && line < first[i + 1])
                in = i;
        }
        if (named || in < 0 || !names[in][0])
            continue; /* already a file's own line, or not one of a file */
        tr_text_printf(&out, "%.*s%s:%ld", (int)(t - done), done, names[in], line - first[in]);
        done = q;
        p = q - 1;
    }
    tr_text_printf(&out, "%s", done);
    return tr_text_take(&out, NULL);
}
