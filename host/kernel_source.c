#include "kernel_source.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int read_whole_file(const char *path, char **text, tr_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return tr_fail(err, TR_EIO, "%s: cannot open kernel source", path);
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 4096 + 1 > cap) {
            cap = 2 * cap + 8192;
            char *grown = realloc(buf, cap);
            if (!grown) {
                free(buf);
                fclose(f);
                return tr_fail(err, TR_ENOMEM, "out of memory reading %s", path);
            }
            buf = grown;
        }
        size_t got = fread(buf + len, 1, 4096, f);
        len += got;
        if (got < 4096)
            break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return tr_fail(err, TR_EIO, "%s: read error", path);
    }
    buf[len] = '\0';
    *text = buf;
    return TR_OK;
}

int tr_kernel_source_load(const char *name, char **text, tr_error *err)
{
    const char *dir = getenv("TIGHTROPE_KERNEL_DIR");
    if (dir && *dir) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        return read_whole_file(path, text, err);
    }
    for (const tr_kernel_source *k = tr_kernel_sources; k->name; k++) {
        if (strcmp(k->name, name) == 0) {
            *text = malloc(k->size + 1);
            if (!*text)
                return tr_fail(err, TR_ENOMEM, "out of memory copying kernel %s", name);
            memcpy(*text, k->text, k->size + 1);
            return TR_OK;
        }
    }
    return tr_fail(err, TR_EINVAL, "no embedded kernel source named %s", name);
}
