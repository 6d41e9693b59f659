// skein: the command line (command_line.cpp).
#include "command_line.hpp"

int main(int argc, char** argv) { return skein::cli::run_command_line(argc, argv); }
