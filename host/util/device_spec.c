/* This file contains the serial reference's device names (device_spec.h). */
#include "util/device_spec.h"

#include <string.h>

int tr_device_spec_is_reference(const char *spec)
{
    static const char *const names[] = {"reference", "serial", "cpu-reference"};
    if (!spec)
        return 0;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (!strcmp(spec, names[i]))
            return 1;
    return 0;
}
