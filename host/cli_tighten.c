/* PLACEHOLDER: replaced by the real 'tighten' command. */
#include <stdio.h>

#include "cli.h"

int tr_cmd_tighten(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "tightrope tighten: not built yet\n");
    return 2;
}
