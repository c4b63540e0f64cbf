/* SIGINT, SIGTERM and SIGHUP for a command that must clean up before it
 * stops (analyze: its staging folder, a running gnuplot): from
 * tr_cli_catch_interrupts on they only raise a flag, which the command polls
 * between its steps, and interrupt a blocking system call (EINTR). */
#ifndef TIGHTROPE_CLI_INTERRUPT_H
#define TIGHTROPE_CLI_INTERRUPT_H

void tr_cli_catch_interrupts(void);

/* The signal that arrived since, or 0. */
int tr_cli_interrupted(void);

#endif
