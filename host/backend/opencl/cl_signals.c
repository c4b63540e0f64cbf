/* cl_signals.h: the caller's signal handlers kept across OpenCL calls. */
#include "backend/opencl/cl_signals.h"
#include <stddef.h>

static const int kept[TR_CL_KEPT_SIGNALS] = {SIGINT, SIGTERM, SIGHUP};

void tr_cl_signals_keep(tr_cl_signals *s)
{
    for (int i = 0; i < TR_CL_KEPT_SIGNALS; i++)
        s->ok[i] = sigaction(kept[i], NULL, &s->old[i]) == 0;
}

void tr_cl_signals_restore(const tr_cl_signals *s)
{
    for (int i = 0; i < TR_CL_KEPT_SIGNALS; i++)
        if (s->ok[i])
            sigaction(kept[i], &s->old[i], NULL);
}
