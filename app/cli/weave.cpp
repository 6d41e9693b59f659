#include "weave.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "render/raster.hpp"
#include "render/sketch.hpp"
#include "skein/config.hpp"
#include "woven/volume.hpp"

namespace skein::cli {
namespace {

/// "#rrggbb,#rrggbb,...": linear albedos.
std::vector<Eigen::Vector3f> parse_colors(const std::string& text, const std::string& option) {
  std::vector<Eigen::Vector3f> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    unsigned r = 0, g = 0, b = 0;
    char tail = 0;
    if (item.size() != 7 || std::sscanf(item.c_str(), "#%2x%2x%2x%c", &r, &g, &b, &tail) != 3)
      throw Error("", option, "expected colours as #rrggbb separated by commas, found \"" + item + "\"");
    out.emplace_back(render::linear_of_byte(r), render::linear_of_byte(g), render::linear_of_byte(b));
  }
  if (out.empty()) throw Error("", option, "needs at least one colour");
  return out;
}

std::pair<int, int> parse_size(const std::string& text, const std::string& option) {
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 100000 || h > 100000)
    throw Error("", option, "expected WxH crossings (1 to 100000 each), found \"" + text + "\"");
  return {w, h};
}

woven::Weave read_weave(const std::string& path) { return woven::from_pattern(mesh::read_pattern(path)); }

json score_json(const woven::SynthesisScore& s) {
  return {{"crossings", s.crossings}, {"correct", s.correct}, {"neighbour_matches", s.matches}, {"best_possible_matches", s.best_matches},
          {"consistent", s.consistent}, {"continuity", s.continuity}};
}

json difference_json(const woven::VolumeDifference& d) {
  return {{"density_error", d.density_error}, {"occupancy", d.occupancy}, {"orientation_deg", d.orientation_deg}, {"surface_error_mm", d.surface_error},
          {"top_agreement", d.top_agreement}};
}

/// Zhao could not do this: the design relaxed directly as one patch and voxelized alike, against the synthesized
/// volume; beside it the floor (the same patch relaxed with other random perturbations) and a ceiling (another
/// weave synthesized from the same exemplars).
json compare_with_truth(const WeaveVolumeArgs& args, const std::vector<woven::Exemplar>& exemplars, const std::vector<woven::Weave>& weaves,
                        const woven::WovenVolume& volume) {
  if (args.pattern.empty()) throw Error("", "--compare-truth", "needs a woven PATTERN (not --picture): the truth is its repeat relaxed directly");
  const int n = volume.weave.warps;
  if (volume.weave.wefts != n || n > 32) throw Error("", "--compare-truth", "needs a square design of at most 32 x 32 crossings (--size NxN)");
  const auto& first = exemplars[0];
  woven::ExemplarOptions o;
  o.crossings = n;
  o.radius = first.radius;
  o.spacing = first.spacing;
  o.voxels_per_crossing = first.block_x;
  const Stopwatch start;
  const auto pattern = mesh::read_pattern(args.pattern);
  o.seed = 101;
  const auto truth = woven::make_exemplar(pattern, o);
  o.seed = 102;
  const auto other = woven::make_exemplar(pattern, o);
  const auto synthesized = woven::volume_region(volume, 0, 0, n, n);
  // The ceiling: an exemplar's weave other than the design's, synthesized from the same exemplars.
  const auto design = woven::from_pattern(pattern);
  const auto another = std::find_if(weaves.begin(), weaves.end(), [&](const woven::Weave& w) { return !(w == woven::tiled(design, w.warps, w.wefts)); });
  if (another == weaves.end()) throw Error("", "--compare-truth", "needs an exemplar of another weave than the design's (the ceiling it measures against)");
  const auto wrong_weave = woven::tiled(*another, n, n);
  const auto wrong_volume = woven::make_volume(exemplars, wrong_weave, woven::synthesize(wrong_weave, weaves, args.synthesis), args.edge_rank);
  const auto wrong = woven::volume_region(wrong_volume, 0, 0, n, n);
  json j = {{"crossings", n},
            {"synthesized", difference_json(woven::compare_grids(synthesized.grid, truth.grid, n))},
            {"relaxed_again", difference_json(woven::compare_grids(other.grid, truth.grid, n))},
            {"other_weave", difference_json(woven::compare_grids(wrong.grid, truth.grid, n))},
            {"seconds", start.seconds()}};
  spdlog::info("against the design relaxed directly ({} x {} crossings): top yarn agrees over {:.0f} % of the cloth (relaxed again {:.0f} %, another weave {:.0f} %), "
               "density error {:.3f} ({:.3f}, {:.3f}), fibre angle {:.1f} deg ({:.1f}, {:.1f}), occupancy {:.2f} ({:.2f}, {:.2f})",
               n, n, 100 * j["synthesized"]["top_agreement"].get<double>(), 100 * j["relaxed_again"]["top_agreement"].get<double>(),
               100 * j["other_weave"]["top_agreement"].get<double>(), j["synthesized"]["density_error"].get<double>(), j["relaxed_again"]["density_error"].get<double>(),
               j["other_weave"]["density_error"].get<double>(), j["synthesized"]["orientation_deg"].get<double>(),
               j["relaxed_again"]["orientation_deg"].get<double>(), j["other_weave"]["orientation_deg"].get<double>(),
               j["synthesized"]["occupancy"].get<double>(), j["relaxed_again"]["occupancy"].get<double>(), j["other_weave"]["occupancy"].get<double>());
  if (!args.png.empty()) {
    // The truth rendered as the synthesized volume is, and the two pictures' mean difference.
    woven::Assignment identity{n, n, {}};
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k) identity.blocks.push_back({0, k, i});
    const std::vector<woven::Exemplar> own{truth};
    const auto truth_volume = woven::make_volume(own, truth.weave, identity, 0, volume.warp_color, volume.weft_color);
    auto options = args.render;
    options.colors = parse_colors(args.warp_colors, "--warp-colors");
    const auto wefts = parse_colors(args.weft_colors, "--weft-colors");
    options.colors.insert(options.colors.end(), wefts.begin(), wefts.end());
    const auto a = woven::render_woven(volume, options), b = woven::render_woven(truth_volume, options);
    double sum = 0;
    for (size_t k = 0; k < a.rgb.size(); ++k) sum += std::abs(static_cast<int>(a.rgb[k]) - static_cast<int>(b.rgb[k]));
    const auto path = std::filesystem::path(args.png).replace_extension("").string() + "-truth.png";
    render::write_png(render::side_by_side({a, b}), path);
    j["picture"] = {{"png", path}, {"mean_difference", sum / a.rgb.size()}};
    spdlog::info("synthesized (left) and relaxed directly (right), mean difference {:.1f} of 255: wrote {}", sum / a.rgb.size(), path);
  }
  return j;
}

}  // namespace

std::vector<woven::Exemplar> bundled_exemplars(const woven::ExemplarOptions& options) {
  std::vector<woven::Exemplar> out;
  for (const char* name : {"plain-weave", "twill-3-2", "twill-4-1", "satin-5-2", "basket-2x2"}) {
    const auto path = std::filesystem::path(SKEIN_SOURCE_DIR) / "patterns" / (std::string(name) + ".weave");
    woven::ExemplarReport report;
    out.push_back(woven::make_exemplar(mesh::read_pattern(path), options, &report));
    spdlog::info("exemplar {}: relaxed in {} steps ({}), {:.2f} s; voxelized {} x {} x {} in {:.2f} s", name, report.steps, report.stopped_by,
                 report.relax_seconds, out.back().grid.nx, out.back().grid.ny, out.back().grid.nz, report.voxel_seconds);
  }
  return out;
}

json weave_exemplar(const WeaveExemplarArgs& args) {
  std::error_code error;
  if (!std::filesystem::is_directory(args.output, error)) throw Error(args.output, "", "is not a folder (make it first)");
  if (!args.report.empty() && args.report != "-") check_writable(args.report);
  json report = {{"exemplars", json::array()}};
  std::set<std::string> stems;
  for (const auto& file : args.patterns)
    if (!stems.insert(std::filesystem::path(file).stem().string()).second)
      throw Error(file, "", "has the same name as another pattern given: both would be written to " + std::filesystem::path(file).stem().string() + ".vdb");
  for (const auto& file : args.patterns) {
    const auto pattern = mesh::read_pattern(file);
    if (pattern.format != mesh::PatternFormat::Woven) throw Error(file, "", "is a knitting pattern; exemplars are woven (.weave or .wif)");
    woven::ExemplarReport r;
    const auto ex = woven::make_exemplar(pattern, args.options, &r);
    const auto out = std::filesystem::path(args.output) / (std::filesystem::path(file).stem().string() + ".vdb");
    woven::write_exemplar(ex, out);
    spdlog::info("{}: {} x {} crossings relaxed in {} steps ({}, {:.2f} s, {} pull-through events), voxelized {} x {} x {} ({:.0f} % filled) in {:.2f} s; wrote {}",
                 file, ex.weave.warps, ex.weave.wefts, r.steps, r.stopped_by, r.relax_seconds, r.pull_through_events, ex.grid.nx, ex.grid.ny, ex.grid.nz,
                 100 * r.filled, r.voxel_seconds, out.string());
    report["exemplars"].push_back({{"pattern", file}, {"output", out.string()}, {"crossings", {ex.weave.warps, ex.weave.wefts}},
                                   {"voxels", {ex.grid.nx, ex.grid.ny, ex.grid.nz}}, {"voxel_mm", ex.grid.voxel}, {"steps", r.steps},
                                   {"stopped_by", r.stopped_by}, {"pull_through_events", r.pull_through_events}, {"relax_seconds", r.relax_seconds},
                                   {"voxel_seconds", r.voxel_seconds}, {"filled", r.filled}, {"weave", woven::to_text(ex.weave)}});
  }
  if (!args.report.empty()) write_json(report, args.report);
  return report;
}

json weave_volume(const WeaveVolumeArgs& args) {
  if (args.pattern.empty() == args.picture.empty()) throw Error("", "weave-volume", "give a woven PATTERN or --picture (one of the two)");
  if (!args.picture.empty() && args.weaves.empty()) throw Error("", "--picture", "needs --weaves: one elementary weave per colour of the picture");
  for (const auto& path : {args.output, args.png, args.report, args.assignment})
    if (!path.empty() && path != "-") check_writable(path);
  // The design (§5.1, §5.2).
  woven::Weave weave;
  if (!args.picture.empty()) {
    const auto image = render::read_png(args.picture);
    int colours = 0;
    const auto labels = woven::picture_labels(image, colours);
    if (colours != static_cast<int>(args.weaves.size()))
      throw Error(args.picture, "", "has " + std::to_string(colours) + " colours and --weaves names " + std::to_string(args.weaves.size()) +
                                        " weaves: name one weave per colour (posterize the picture first)");
    std::vector<woven::Weave> elementary;
    std::vector<int> map;
    for (int c = 0; c < colours; ++c) elementary.push_back(read_weave(args.weaves[c])), map.push_back(c);
    weave = woven::weave_from_labels(labels, image.width, image.height, elementary, map);
    if (!args.size.empty()) throw Error("", "--size", "is the picture's size (one crossing per pixel); scale the picture instead");
  } else {
    const auto repeat = read_weave(args.pattern);
    const auto [w, h] = args.size.empty() ? std::pair{repeat.warps * std::max(1, 48 / repeat.warps), repeat.wefts * std::max(1, 48 / repeat.wefts)}
                                          : parse_size(args.size, "--size");
    weave = woven::tiled(repeat, w, h);
  }
  const auto warp_palette = parse_colors(args.warp_colors, "--warp-colors"), weft_palette = parse_colors(args.weft_colors, "--weft-colors");
  // The exemplars (§4): a folder, or the bundled set.
  const Stopwatch exemplar_start;
  const auto exemplars = args.exemplars.empty() ? bundled_exemplars({}) : woven::read_exemplars(args.exemplars);
  const double exemplar_seconds = exemplar_start.seconds();
  std::vector<woven::Weave> weaves;
  json exemplar_names = json::array();
  for (const auto& e : exemplars) weaves.push_back(e.weave), exemplar_names.push_back(e.name);
  spdlog::info("{} x {} crossings; {} exemplars ({:.1f} s)", weave.warps, weave.wefts, exemplars.size(), exemplar_seconds);
  // Synthesis (§5.3, §5.4) and edge fixing (§5.5).
  const Stopwatch synthesis_start;
  const auto assignment = woven::synthesize(weave, weaves, args.synthesis);
  const double synthesis_seconds = synthesis_start.seconds();
  const auto score = woven::score(weave, weaves, assignment);
  std::vector<int> warp_color(weave.warps * static_cast<size_t>(weave.wefts)), weft_color(warp_color.size());
  const int warps_n = static_cast<int>(warp_palette.size());
  for (int i = 0; i < weave.wefts; ++i)
    for (int j = 0; j < weave.warps; ++j) {
      warp_color[static_cast<size_t>(i) * weave.warps + j] = j % warps_n;
      weft_color[static_cast<size_t>(i) * weave.warps + j] = warps_n + i % static_cast<int>(weft_palette.size());
    }
  const Stopwatch fix_start;
  const auto volume = woven::make_volume(exemplars, weave, assignment, args.edge_rank, warp_color, weft_color);
  const double fix_seconds = fix_start.seconds();
  const long crossings = static_cast<long>(weave.warps) * weave.wefts;
  json report = {{"design", args.picture.empty() ? args.pattern : args.picture},
                 {"crossings", {weave.warps, weave.wefts}},
                 {"size_mm", {volume.size().x(), volume.size().y(), volume.size().z()}},
                 {"exemplars", exemplar_names},
                 {"exemplar_seconds", exemplar_seconds},
                 {"synthesis_seconds", synthesis_seconds},
                 {"synthesis", score_json(score)},
                 {"randomized", args.synthesis.randomize},
                 {"effective_voxels", static_cast<double>(crossings) * volume.block_x * volume.block_y * std::round((volume.z_high - volume.z_low) / volume.voxel)},
                 {"memory_bytes", crossings * (sizeof(woven::Block) + 2 * sizeof(int)) + 2 * crossings * volume.fix.rank() * sizeof(float)}};
  if (args.edge_rank != 0) {
    const double before = woven::seam_step(exemplars, assignment), after = woven::seam_step(exemplars, assignment, &volume.fix);
    report["edge_fixing"] = {{"rank", volume.fix.rank()}, {"kept", volume.fix.kept()}, {"seconds", fix_seconds}, {"seam_step_mm", before},
                             {"seam_step_fixed_mm", after}};
    spdlog::info("synthesis {:.2f} s: {} of {} neighbours match (best possible {}), continuity {}; edge fixing (rank {}, {:.1f} % kept) {:.2f} s: seams {:.4f} -> {:.4f} mm",
                 synthesis_seconds, score.matches, 4 * crossings, score.best_matches, score.continuity, volume.fix.rank(), 100 * volume.fix.kept(),
                 fix_seconds, before, after);
  } else {
    report["edge_fixing"] = nullptr;
    spdlog::info("synthesis {:.2f} s: {} neighbours match (best possible {}), continuity {}; no edge fixing", synthesis_seconds, score.matches,
                 score.best_matches, score.continuity);
  }
  if (!args.assignment.empty()) {
    write_file_atomically(args.assignment, [&](std::ostream& out) {
      out << "# skein weave-volume: per crossing (weft row, warp column) the exemplar block it copies: exemplar x y\n";
      for (size_t u = 0; u < exemplars.size(); ++u) out << "# exemplar " << u << " " << exemplars[u].name << "\n";
      for (int i = 0; i < weave.wefts; ++i)
        for (int j = 0; j < weave.warps; ++j) {
          const auto& b = assignment.at(i, j);
          out << i << " " << j << " " << b.exemplar << " " << b.x << " " << b.y << "\n";
        }
    });
    spdlog::info("wrote {}", args.assignment);
  }
  if (!args.output.empty()) {
    int x = 0, y = 0, w = weave.warps, h = weave.wefts;
    if (!args.region.empty()) {
      char tail = 0;
      if (std::sscanf(args.region.c_str(), "%d,%d,%d,%d%c", &x, &y, &w, &h, &tail) != 4) throw Error("", "--region", "expected X,Y,W,H crossings, found \"" + args.region + "\"");
    } else if (w > 16 || h > 16) {
      x = std::max(0, w / 2 - 8), y = std::max(0, h / 2 - 8), w = std::min(w, 16), h = std::min(h, 16);
    }
    // What skein reads back (read_exemplar's limit), and what is made densely here.
    const double voxels = static_cast<double>(w) * h * volume.block_x * volume.block_y * std::ceil((volume.z_high - volume.z_low) / volume.voxel);
    if (voxels > 64.0 * 1024 * 1024)
      throw Error("", "--region", "of " + std::to_string(w) + " x " + std::to_string(h) + " crossings is " + std::to_string(std::lround(voxels / 1e6)) +
                                      " M voxels; at most 64 M (about 28 x 28 crossings of 24 x 24 voxels)");
    const auto region = woven::volume_region(volume, x, y, w, h);
    woven::write_exemplar(region, args.output);
    report["output"] = {{"path", args.output}, {"region", {x, y, w, h}}, {"voxels", {region.grid.nx, region.grid.ny, region.grid.nz}}};
    spdlog::info("wrote crossings {},{} to {},{} as {} x {} x {} voxels: {}", x, y, x + w, y + h, region.grid.nx, region.grid.ny, region.grid.nz, args.output);
  }
  if (args.compare_truth) report["truth"] = compare_with_truth(args, exemplars, weaves, volume);
  if (!args.png.empty()) {
    auto options = args.render;
    options.colors = warp_palette;
    options.colors.insert(options.colors.end(), weft_palette.begin(), weft_palette.end());
    woven::WovenRenderReport r;
    const auto image = woven::render_woven(volume, options, &r);
    render::write_png(image, args.png);
    report["render"] = {{"png", args.png}, {"pixels", {options.width, options.height}}, {"samples", options.samples}, {"seconds", r.seconds},
                        {"seconds_per_megapixel", r.seconds / (1e-6 * options.width * options.height)}, {"lookups", r.lookups}};
    spdlog::info("rendered {} x {} pixels, {} paths each, in {:.1f} s; wrote {}", options.width, options.height, options.samples, r.seconds, args.png);
  }
  if (!args.report.empty()) write_json(report, args.report);
  return report;
}

}  // namespace skein::cli
