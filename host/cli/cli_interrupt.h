/* SIGINT, SIGTERM and SIGHUP for a command that must stop cleanly (analyze:
 * its staging folder, a running gnuplot; tighten: its checkpoint and
 * output): from
 * tr_cli_catch_interrupts on they only raise a flag, which the command polls
 * between its steps, and interrupt a blocking system call (EINTR). */
#ifndef TIGHTROPE_CLI_INTERRUPT_H
#define TIGHTROPE_CLI_INTERRUPT_H

#include <signal.h>

void tr_cli_catch_interrupts(void);

/* The signal that arrived since, or 0. */
int tr_cli_interrupted(void);

/* The flag itself, for the library's stop parameters (engine.h, newton.h,
 * clock.h's tr_deadline), which poll it between their steps (tighten). */
volatile sig_atomic_t *tr_cli_interrupt_flag(void);

#endif
