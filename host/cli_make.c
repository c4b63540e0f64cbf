/* PLACEHOLDER: replaced by the real 'make' command. */
#include <stdio.h>

#include "cli.h"

int tr_cmd_make(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "tightrope make: not built yet\n");
    return 2;
}
