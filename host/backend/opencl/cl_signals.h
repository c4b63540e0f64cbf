/* The caller's signal handlers, kept across OpenCL calls that may load a
 * compiler. PoCL's LLVM (libLLVM-15, loaded when the devices are listed
 * and the kernels built) installs its own handlers on SIGINT, SIGTERM and
 * SIGHUP, process-wide and for good: a host that set its own (the
 * command line's stop flag, Python's KeyboardInterrupt) found LLVM's in
 * their place after the run (seen with dladdr of the installed handler).
 * (The Python package's Ctrl-C test failure, first laid to this, was a
 * suite started in the background, where SIGINT is ignored from the
 * start: python/tests, python_sigint.) A library must not
 * change a process's signal dispositions, so these calls are bracketed:
 * what the caller had before is what it has after. */
#ifndef TR_CL_SIGNALS_H
#define TR_CL_SIGNALS_H

#include <signal.h>

#define TR_CL_KEPT_SIGNALS 3

typedef struct tr_cl_signals {
    struct sigaction old[TR_CL_KEPT_SIGNALS];
    int ok[TR_CL_KEPT_SIGNALS];
} tr_cl_signals;

/* Notes the handlers of SIGINT, SIGTERM and SIGHUP. */
void tr_cl_signals_keep(tr_cl_signals *s);

/* Puts back the handlers noted. */
void tr_cl_signals_restore(const tr_cl_signals *s);

#endif
