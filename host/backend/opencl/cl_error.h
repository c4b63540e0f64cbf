/* Naming OpenCL errors and the one checking macro every OpenCL call goes
 * through. A failed call records
 *   "clEnqueueNDRangeKernel: CL_INVALID_WORK_GROUP_SIZE (-54) [backend_opencl.c:212]"
 * into the caller's tr_error and jumps to the function's cleanup ladder;
 * nothing here prints or aborts. */
#ifndef TR_CL_ERROR_H
#define TR_CL_ERROR_H

#include <CL/cl.h>
#include <stdarg.h>

#include "util/error.h"

/* "CL_INVALID_WORK_GROUP_SIZE" for -54; "CL_UNKNOWN_ERROR" for codes no
 * specification or common extension defines. */
const char *tr_cl_strerror(cl_int code);

/* Fills err with "NAME: CL_X (code) [file:line]" where NAME is the first
 * OpenCL entry point (cl[A-Z]...) named in call_text, and returns TR_EOPENCL. */
int tr_cl_fail(tr_error *err, cl_int code, const char *call_text, const char *file, int line);

/* TR_CL_CHECK(clFinish(queue)) or, for calls that report through an
 * errcode_ret argument, TR_CL_CHECK((buf = clCreateBuffer(..., &e), e)).
 * Needs `int rc`, `tr_error *err` and a `cleanup:` label in the caller. */
#define TR_CL_CHECK(call)                                                             \
    do {                                                                              \
        cl_int tr_cl_code_ = (call);                                                  \
        if (tr_cl_code_ != CL_SUCCESS) {                                              \
            rc = tr_cl_fail(err, tr_cl_code_, #call, __FILE__, __LINE__);             \
            goto cleanup;                                                             \
        }                                                                             \
    } while (0)

/* k's function name into name (n bytes), "?" when OpenCL cannot say or the
 * name does not fit: for messages and the kernel profile. */
void tr_cl_kernel_name(cl_kernel k, char *name, size_t n);

/* Kernel arguments, one way everywhere: arguments first, first + 1, ... of
 * kernel k from TR_CL_A(v) pairs (v a cl_mem, int or double variable),
 *   TR_CL_ARGS(k, 0, TR_CL_A(x), TR_CL_A(n), TR_CL_A(out));
 * A failure reads "kernel j_rows, argument 3: clSetKernelArg:
 * CL_INVALID_ARG_SIZE (-51) [file:line]" (the name asked of the kernel).
 * TR_CL_ARGS needs what TR_CL_CHECK needs; the functions return a tr status
 * for callers with their own argument lists (the va_list form, terminated
 * by TR_CL_END). */
#define TR_CL_A(v) sizeof(v), (const void *)&(v)
#define TR_CL_END ((size_t)0)
#define TR_CL_ARGS(k, first, ...)                                                     \
    TR_TRY(tr_cl_args_at(err, __FILE__, __LINE__, (k), (first), __VA_ARGS__, TR_CL_END))
int tr_cl_args_at(tr_error *err, const char *file, int line, cl_kernel k, cl_uint first, ...);
int tr_cl_vargs(tr_error *err, const char *file, int line, cl_kernel k, cl_uint first, va_list ap);

/* Same for library calls returning a tr status: keep their message. */
#define TR_TRY(expr)                                                                  \
    do {                                                                              \
        rc = (expr);                                                                  \
        if (rc != TR_OK)                                                              \
            goto cleanup;                                                             \
    } while (0)

#endif
