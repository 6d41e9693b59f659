// skein label: label a mesh's knitting rows and save the labels (.skein)
#include "subcommand.hpp"

#include <memory>

#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/project.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::cli {
namespace {

struct LabelCommand final : Subcommand {
  CLI::App* label = nullptr;
  std::string label_in, label_out;
  int label_start = -1;
  std::vector<int> flips;
  bool label_repair = false;
  std::vector<int> first_rows, next_rows;
  mesh::StitchSize label_size;
  std::vector<std::string> course_values, row_values;
  std::vector<int> marked_wales;
  FabricChoice label_fabric;
  bool label_partial = false;

  void declare(CLI::App& app) override {
    label = app.add_subcommand("label", "label a mesh's knitting rows and save the labels (.skein)");
    label->add_option("MESH", label_in, "mesh or .skein project")->required();
    label->add_flag("--repair", label_repair, "mend the mesh first where CGAL can (duplicate points and faces, degenerate faces, orientation, bow ties) and say what changed");
    auto* start_opt = label->add_option("--start-edge", label_start, "auto-label from this border edge (default: the lowest)");
    auto* first_opt = label->add_option("--first-row", first_rows, "label by hand: first rows from these border edges (instead of auto-label)");
    label->add_option("--next-row", next_rows, "then the next row across each of these course edges, in order")->needs(first_opt);
    first_opt->excludes(start_opt);
    label->add_option("--flip-row", flips, "flip these rows' wale direction after labeling");
    label->add_option("--stitch-size", label_size.width, "stitch width for the tessellation values [mm]")->capture_default_str();
    label->add_option("--stitch-height", label_size.height, "stitch height [mm] (default: the width × 5/6)");
    label->add_option("--course-value", course_values, "set a course edge's stitch count: EDGE=N (repeatable)");
    label->add_option("--row-value", row_values, "set a row's stitch-row count: ROW=N (repeatable)");
    label->add_option("--mark-wale", marked_wales, "wale edges next to which increases and decreases go");
    label->add_option("-o,--output", label_out, "labels and tessellation values to write (.skein)")->required();
    label->add_flag("--partial", label_partial, "write the labels even when some faces are not labeled yet (to go on later, by hand or in the app); exit 1");
    add_fabric(label, label_fabric, "without --gauge, sets the stitch size of its standard gauge", true);
  }

  bool chosen() const override { return label->parsed(); }

  int run(const Context&) override {
    check_writable(label_out);
    const auto label_fabric_size = resolve_fabric(label_fabric, size_given(label), false).size;
    mesh::Project project;
    project.input = load_input(label_in, label_repair);
    const auto& m = *project.input;
    if (first_rows.empty()) {
      project.labels = mesh::auto_label(m, label_start >= 0 ? label_start : mesh::default_start_edge(m));
    } else {
      project.labels = mesh::Labeling(m);
      for (int e : first_rows) mesh::label_first_row(m, *project.labels, e);
      for (int e : next_rows) mesh::label_next_row(m, *project.labels, e);
    }
    for (int r : flips) {
      if (r < 0 || r >= project.labels->rows) throw Error("", "--flip-row " + std::to_string(r), "no such row (there are " + std::to_string(project.labels->rows) + ")");
      mesh::flip_row(*project.labels, r);
    }
    const auto report = mesh::validate_labels(m, *project.labels);
    log_face_problems(label_in, m, report, label_partial ? spdlog::level::warn : spdlog::level::err);
    for (const auto& [e, why] : report.mismatches) spdlog::warn("{}: edge {}: {}", label_in, e, why);
    if (!report.valid() && !label_partial)
      throw Error(label_in, "face " + std::to_string(report.face_problems.front().first),
                  std::to_string(report.face_problems.size()) + " of " + std::to_string(m.num_faces()) +
                      " faces are not labeled (listed above); nothing written. --partial writes the labels made so far");
    if (label->count("--stitch-height") == 0) label_size.height = label_size.width * 5.0 / 6.0;
    if (label_fabric_size) label_size = *label_fabric_size;
    project.stitch_size = label_size;
    if (report.valid()) {
      project.values = mesh::initial_values(m, *project.labels, label_size);
      for (const auto& a : course_values) {
        const auto [e, n] = parse_assignment("--course-value", a);
        mesh::set_course_value(m, *project.labels, *project.values, e, n);
      }
      for (const auto& a : row_values) {
        const auto [r, n] = parse_assignment("--row-value", a);
        mesh::set_row_value(m, *project.labels, *project.values, r, n);
      }
      for (int e : marked_wales) mesh::mark_wale_edge(m, *project.labels, *project.values, e, true);
    }
    mesh::write_project(project, label_out);
    spdlog::info("{} rows; wrote {}", project.labels->rows, label_out);
    return report.valid() ? 0 : 1;
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_label_command() { return std::make_unique<LabelCommand>(); }

}  // namespace skein::cli
