/* Error reporting for the Tightrope library.
 *
 * Library functions never print and never exit: they return an int status
 * (0 = ok, negative = failure) and, where a caller passes a tr_error, fill it
 * with one lower-case line that says what failed first, e.g.
 *   "trefoil.vect:7: expected 3 numbers, got 2".
 * main.c prints that line and chooses the exit status. */
#ifndef TR_ERROR_H
#define TR_ERROR_H

#include <stddef.h>

enum tr_status {
    TR_OK = 0,
    TR_EIO = -1,          /* a file could not be opened, read, written or renamed */
    TR_EPARSE = -2,       /* malformed input file (message names FILE:LINE) */
    TR_EINVAL = -3,       /* bad argument or option value */
    TR_ENOMEM = -4,       /* allocation failed */
    TR_EGEOMETRY = -5,    /* the curve cannot be handled (overlap, too coarse, ...) */
    TR_EOPENCL = -6,      /* an OpenCL call failed (message names the call) */
    TR_ETOPOLOGY = -7,    /* a step would have let strands pass through each other */
    TR_EINTERRUPTED = -8, /* stopped by a signal; state was saved */
    TR_EUNSUPPORTED = -9  /* the device or build lacks a needed feature */
};

typedef struct tr_error {
    char msg[1024];
} tr_error;

/* Formats the message into err (if non-NULL) and returns status, so that
 * callers can write `return tr_fail(err, TR_EINVAL, "bad N %d", n);`. */
int tr_fail(tr_error *err, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Prefixes an existing message with context ("reading x.vect: ..."). */
int tr_fail_wrap(tr_error *err, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

const char *tr_strerror(int status);

#endif
