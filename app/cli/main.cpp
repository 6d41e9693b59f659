// skein: the command line (command_line.cpp).
#include "command_line.hpp"
#include "common/cpu_threads.hpp"

int main(int argc, char** argv) {
  skein::wait_passively(argv);  // issue 28: steady beside other work
  skein::follow_free_cores(true);
  return skein::cli::run_command_line(argc, argv);
}
