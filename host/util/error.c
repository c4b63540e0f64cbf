/* This file contains the library's error records: tr_fail and its wrapping form (error.h). */
#include "util/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int tr_fail(tr_error *err, int status, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
    }
    return status;
}

int tr_fail_wrap(tr_error *err, int status, const char *fmt, ...)
{
    if (err) {
        char prefix[512];
        char old[sizeof err->msg];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(prefix, sizeof prefix, fmt, ap);
        va_end(ap);
        memcpy(old, err->msg, sizeof old);
        /* Truncation of an over-long message is acceptable; an error line stays one line. */
        size_t n = strlen(prefix);
        if (n > sizeof err->msg - 3)
            n = sizeof err->msg - 3;
        memcpy(err->msg, prefix, n);
        memcpy(err->msg + n, ": ", 2);
        size_t room = sizeof err->msg - n - 3;
        size_t m = strnlen(old, room);
        memcpy(err->msg + n + 2, old, m);
        err->msg[n + 2 + m] = '\0';
    }
    return status;
}

const char *tr_strerror(int status)
{
    switch (status) {
    case TR_OK: return "ok";
    case TR_EIO: return "input/output error";
    case TR_EPARSE: return "malformed input";
    case TR_EINVAL: return "invalid argument";
    case TR_ENOMEM: return "out of memory";
    case TR_EGEOMETRY: return "unusable geometry";
    case TR_EOPENCL: return "opencl error";
    case TR_ETOPOLOGY: return "knot type would change";
    case TR_EINTERRUPTED: return "interrupted";
    case TR_EUNSUPPORTED: return "unsupported";
    default: return "unknown error";
    }
}
