#pragma once

namespace skein::cli {

/// skein's command line: parses `argv` (argv[0] the program's name) and runs its subcommand. Returns the exit
/// status (0 done, 1 not converged or audit found changes, 2 an error, 128 + signal when interrupted). May be
/// called more than once in one process (skein-mpi runs each sweep case through it).
int run_command_line(int argc, char** argv);

}  // namespace skein::cli
