/* OpenCL C sources embedded into the binary at build time. */
#ifndef TR_KERNEL_SOURCE_H
#define TR_KERNEL_SOURCE_H

#include <stddef.h>

#include "util/error.h"

typedef struct tr_kernel_source {
    const char *name; /* file name, e.g. "strut.cl" */
    const char *text; /* NUL-terminated */
    size_t size;      /* bytes, without the NUL */
} tr_kernel_source;

/* Terminated by an entry with name == NULL. */
extern const tr_kernel_source tr_kernel_sources[];

/* Returns the source of a kernel file in a newly malloc'd string.
 * If the environment variable TIGHTROPE_KERNEL_DIR is set, the file is read
 * from that directory instead (fast kernel work without rebuilding). */
int tr_kernel_source_load(const char *name, char **text, tr_error *err);

#endif
