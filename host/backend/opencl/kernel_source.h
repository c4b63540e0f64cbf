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

/* Returns the source of a kernel file in a newly malloc'd string, after a
 * "#line 1" directive naming it ("kernels/NAME", or DIR/NAME from disk) and
 * ending in a newline: compile errors and Oclgrind's reports then name the
 * file and its line, wherever it lies in the program tr_cl_build
 * concatenates. If the environment variable TIGHTROPE_KERNEL_DIR is set, the
 * file is read from that directory instead (fast kernel work without
 * rebuilding). */
int tr_kernel_source_load(const char *name, char **text, tr_error *err);

/* The build log of a program concatenated from src[0..nsrc) (each as
 * tr_kernel_source_load returns it) with every location "X.cl:LINE:" that
 * counts lines of the whole program turned into the file and line it
 * points to. For compilers whose messages ignore #line: Oclgrind's name
 * "input.cl:908:1", NVIDIA's "<kernel>:1164:1"; PoCL's already name the
 * file. A new string, NULL when
 * out of memory. */
char *tr_kernel_log_locate(const char *log, const char *const *src, int nsrc);

#endif
