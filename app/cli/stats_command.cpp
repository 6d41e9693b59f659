// skein stats: counts and validity of a mesh, labeling, stitch mesh or yarn (.bcc)
#include "subcommand.hpp"

#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "stitchmesh/project.hpp"
#include "workflow/yarn_io.hpp"

using nlohmann::json;

namespace skein::cli {
namespace {

struct StatsCommand final : Subcommand {
  CLI::App* stats = nullptr;
  std::string stats_in;
  bool stats_json_flag = false;
  std::string stats_out;

  void declare(CLI::App& app) override {
    stats = app.add_subcommand("stats", "counts and validity of a mesh, labeling, stitch mesh or yarn (.bcc)");
    stats->add_option("FILE", stats_in, "mesh or .skein project")->required();
    stats->add_flag("--json", stats_json_flag, "print JSON (default: text)");
    stats->add_option("-o,--output", stats_out, "write the JSON here instead of printing it");
  }

  bool chosen() const override { return stats->parsed(); }

  int run(const Context&) override {
    json j;
    if (is_bcc(stats_in)) {
      j = yarn_json(workflow::read_bcc(stats_in));
    } else if (is_project(stats_in)) {
      const auto project = mesh::read_project(stats_in);
      if (project.stitch) j = stats_json(*project.stitch);
      else if (project.labels) j = {{"kind", "labeled-mesh"}, {"mesh", mesh_json(*project.input)}, {"labels", labels_json(*project.input, *project.labels)}};
      else if (project.input) j = mesh_json(*project.input);
    } else {
      j = mesh_json(mesh::load_mesh(stats_in));
    }
    if (!stats_out.empty()) {
      write_json(j, stats_out);
    } else if (stats_json_flag) {
      std::cout << j.dump(2) << "\n";
    } else {
      print_text(j, "");
    }
    return 0;
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_stats_command() { return std::make_unique<StatsCommand>(); }

}  // namespace skein::cli
