#include "backend/opencl/kernel_source.h"
#include "util/text_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int tr_kernel_source_load(const char *name, char **text, tr_error *err)
{
    const char *dir = getenv("TIGHTROPE_KERNEL_DIR");
    if (dir && *dir) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        return tr_read_file(path, text, NULL, err);
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
