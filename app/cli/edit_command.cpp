// skein edit: change stitch types of a stitch mesh: fills over rows, single faces
#include "subcommand.hpp"

#include <memory>

#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "render/stitch_view.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/project.hpp"

namespace skein::cli {
namespace {

struct EditCommand final : Subcommand {
  CLI::App* edit = nullptr;
  std::string edit_in, edit_out, edit_fill, edit_rows, edit_type, edit_png;
  std::vector<int> edit_faces;
  int near_border = -1;

  void declare(CLI::App& app) override {
    edit = app.add_subcommand("edit", "change stitch types of a stitch mesh: fills over rows, single faces");
    edit->add_option("PROJECT", edit_in, ".skein project with a stitch mesh")->required();
    edit->add_option("--fill", edit_fill, "stockinette, reverse, garter, seed, moss, rib or ribKxP");
    auto* rows_opt = edit->add_option("--rows", edit_rows, "rows A:B the fill covers (default: all)");
    edit->add_option("--near-border", near_border, "the fill covers the N stitch rows next to each border (hems, cuffs, necklines)")
        ->excludes(rows_opt);
    edit->add_option("--set-type", edit_type, "stitch type for --faces");
    edit->add_option("--faces", edit_faces, "face ids for --set-type");
    edit->add_option("--png-types", edit_png, "picture coloured by stitch type");
    edit->add_option("-o,--output", edit_out, "project to write")->required();
  }

  bool chosen() const override { return edit->parsed(); }

  int run(const Context&) override {
    check_writable(edit_out);
    auto project = mesh::read_project(edit_in);
    if (!project.stitch) throw Error(edit_in, "", "holds no stitch mesh; run 'skein stitch' first");
    auto& sm = *project.stitch;
    if (!edit_fill.empty()) {
      const auto pattern = mesh::parse_fill(edit_fill);
      std::vector<int> faces;
      if (near_border >= 0) {
        faces = mesh::faces_near_border(sm, near_border);
      } else {
        const auto [a, b] = edit_rows.empty() ? std::pair{0, INT32_MAX} : parse_rows(edit_rows);
        for (int f = 0; f < static_cast<int>(sm.faces.size()); ++f)
          if (sm.faces[f].row >= a && sm.faces[f].row <= b) faces.push_back(f);
      }
      sm = mesh::fill(sm, faces, pattern);
      spdlog::info("filled {} faces with {}", faces.size(), edit_fill);
    }
    if (!edit_type.empty()) sm = mesh::set_stitch_type(sm, edit_faces, edit_type);
    mesh::write_project(project, edit_out);
    if (!edit_png.empty()) render_stitch_mesh(sm, edit_png, render::ColorBy::StitchType);
    return 0;
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_edit_command() { return std::make_unique<EditCommand>(); }

}  // namespace skein::cli
