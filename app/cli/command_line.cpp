// skein's command line, callable in-process (skein's main, and skein-mpi's sweep cases). Each subcommand lives in
// a file of its own (subcommand.hpp); this parses, sets up the log and runs the one chosen.
#include "command_line.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "common/error.hpp"
#include "skein/config.hpp"
#include "subcommand.hpp"

namespace skein::cli {

int run_command_line(int argc, char** argv) {
  CLI::App app{"skein: polygon mesh → knitted garment with yarn-level detail (Yuksel et al. 2012 stitch meshes)"};
  app.set_version_flag("--version", SKEIN_VERSION);
  app.require_subcommand(1);
  Context context;
  app.add_flag("-q,--quiet", context.quiet, "print warnings and errors only");
  const auto subcommands = make_subcommands();
  for (const auto& s : subcommands) s->declare(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a bad option or value is a user's error like any other: exit 2 (README).
    return app.exit(e) == 0 ? 0 : 2;
  }
  // The log goes to stderr, so that what a command prints as data (--stats -, a script's CSV) stays clean.
  if (!spdlog::get("skein")) spdlog::set_default_logger(spdlog::stderr_color_mt("skein"));  // once a process
  spdlog::set_pattern("[%H:%M:%S.%e] %^%l%$ %v");
  spdlog::set_level(context.quiet ? spdlog::level::warn : spdlog::level::info);
  try {
    check_companions(app);
    for (const auto& s : subcommands)
      if (s->chosen()) return s->run(context);
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  return 0;
}

}  // namespace skein::cli
