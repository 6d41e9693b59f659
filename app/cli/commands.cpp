#include "commands.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include <omp.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include "common/atomic_file.hpp"
#include "common/cpu_threads.hpp"
#include "common/error.hpp"
#include "cuda/yarn_relaxer.hpp"
#include "render/stitch_view.hpp"
#include "render/yarn_view.hpp"
#include "stitchmesh/mesh_repair.hpp"
#include "workflow/yarn_io.hpp"
#include "workflow/yarn_options.hpp"

namespace skein::cli {


bool is_project(const fs::path& path) { return path.extension() == ".skein"; }

mesh::InputMesh load_input(const fs::path& path, bool repair) {
  if (!is_project(path)) {
    auto soup = mesh::read_mesh_soup(path);
    if (repair) {  // issue 25: mend what CGAL can, and say what changed
      mesh::RepairReport report;
      soup = mesh::repair_mesh_soup(std::move(soup), report);
      spdlog::info("repaired {}: {}", path.string(), report.summary());
    }
    try {
      return mesh::InputMesh(std::move(soup.points), std::move(soup.faces), path.string());
    } catch (const Error& e) {  // a rule of the mesh broken: say what can mend it, unless it has been tried
      if (repair) throw;
      throw Error(e.file(), e.place(), e.rule() + "; --repair mends duplicate points and faces, degenerate faces, orientation and bow ties");
    }
  }
  if (repair) throw Error(path.string(), "", "--repair mends a mesh file, not a project");
  auto project = mesh::read_project(path);
  if (!project.input) throw Error(path.string(), "", "the project holds no input mesh");
  return std::move(*project.input);
}

std::pair<mesh::Labeling, std::optional<mesh::TessellationValues>> labels_for(const mesh::InputMesh& mesh, const fs::path& path) {
  auto project = mesh::read_project(path);
  if (!project.input || !project.labels) throw Error(path.string(), "", "holds no labels (it needs 'input-mesh' and 'labels' sections)");
  const auto& stored = *project.input;
  const auto differ = [&](const std::string& what) {
    throw Error(path.string(), "", "its labels were made for a different mesh than " + mesh.source() + " (" + what + ")");
  };
  if (stored.num_faces() != mesh.num_faces()) differ(std::to_string(stored.num_faces()) + " faces, not " + std::to_string(mesh.num_faces()));
  const double tolerance = 1e-6 * mesh.bounding_diagonal();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (stored.face(f).size() != mesh.face(f).size()) differ("face " + std::to_string(f) + " has another number of corners");
    for (size_t k = 0; k < mesh.face(f).size(); ++k)
      if ((stored.point(stored.face(f)[k]) - mesh.point(mesh.face(f)[k])).norm() > tolerance)
        differ("face " + std::to_string(f) + " corner " + std::to_string(k) + " is elsewhere");
  }
  return {std::move(*project.labels), std::move(project.values)};
}

json stats_json(const mesh::StitchMesh& sm) {
  const auto s = mesh::stitch_stats(sm);
  return {{"kind", "stitch-mesh"}, {"faces", s.faces},         {"vertices", s.vertices},
          {"rows", s.rows},         {"increases", s.increases}, {"decreases", s.decreases},
          {"cable_edges", s.cable_edges}, {"stitch_types", s.stitch_types}, {"invalid_faces", s.invalid_faces},
          {"valid", s.valid}};
}

json labels_json(const mesh::InputMesh& m, const mesh::Labeling& labels) {
  const auto report = mesh::validate_labels(m, labels);
  json problems = json::array(), mismatches = json::array();
  for (const auto& [f, why] : report.face_problems) problems.push_back({{"face", f}, {"reason", why}});
  for (const auto& [e, why] : report.mismatches) mismatches.push_back({{"edge", e}, {"reason", why}});
  return {{"rows", labels.rows}, {"invalid_faces", report.face_problems.size()}, {"face_problems", problems},
          {"mismatched_edges", report.mismatches.size()}, {"mismatches", mismatches}, {"valid", report.valid()}};
}

json mesh_json(const mesh::InputMesh& m) {
  int border = 0;
  std::map<std::string, int> sizes;
  for (int e = 0; e < m.num_edges(); ++e) border += m.is_border(e);
  for (const auto& f : m.faces()) ++sizes[std::to_string(f.size()) + "-gons"];
  return {{"kind", "mesh"}, {"vertices", m.num_vertices()}, {"faces", m.num_faces()}, {"edges", m.num_edges()},
          {"border_edges", border}, {"face_sizes", sizes}};
}

void write_json(const json& j, const std::string& path) {
  if (path == "-") {
    std::cout << j.dump(2) << "\n";
    return;
  }
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
}

render::View view_named(const std::string& name) {
  render::View view;
  if (name == "flat") view.directions = {{0, 0, -1}, {0, 0, 1}};
  if (name == "front") view.directions = {{0, 0, -1}};
  if (name == "three") view.directions = {{0, 0, -1}, {0, 0, 1}, {0.4, -0.35, -1.0}};  // front, back, three-quarter from above
  return view;
}

void render_yarn_tubes(const relax::YarnCurves& yarn, const std::string& path, render::YarnColor color, const std::string& views,
                       int panel) {
  Stopwatch t;
  render::View view = view_named(views);
  view.panel = panel;
  view.outlines = false;
  render::write_png(render::draw(render::yarn_polygons(yarn, color), view), path);
  spdlog::info("wrote {} ({:.2f} s)", path, t.seconds());
}

void render_stitch_mesh(const mesh::StitchMesh& sm, const std::string& path, render::ColorBy color, const std::string& views) {
  Stopwatch t;
  render::write_png(render::draw(render::stitch_polygons(sm, color), view_named(views)), path);
  spdlog::info("wrote {} ({:.2f} s)", path, t.seconds());
}

std::vector<Eigen::Vector3f> stretch_colors(const surface::FaceStretch& strain) {
  std::vector<Eigen::Vector3f> colors;
  colors.reserve(strain.area_strain.size());
  for (double a : strain.area_strain) colors.push_back(render::strain_color(a));
  return colors;
}

void render_stretch(const mesh::StitchMesh& sm, double r_course, double r_wale, const std::string& path) {
  Stopwatch t;
  const auto colors = stretch_colors(surface::face_stretch(sm, r_course, r_wale));
  render::write_png(render::draw(render::stitch_polygons(sm, colors), render::View{}), path);
  spdlog::info("wrote {} ({:.2f} s)", path, t.seconds());
}

bool is_bcc(const fs::path& path) { return path.extension() == ".bcc"; }

relax::YarnCurves yarn_of(const fs::path& path, double radius, const std::string& stitches, mesh::EmitReport* report) {
  if (is_bcc(path)) return workflow::read_bcc(path);
  const auto project = mesh::read_project(path);
  if (!project.stitch) throw Error(path.string(), "", "holds no stitch mesh; run 'skein stitch' first");
  mesh::EmitOptions options;
  options.yarn_radius = radius > 0 ? radius : 0.1 * project.stitch_size.width;
  const auto& library = stitches.empty() ? mesh::StitchLibrary::bundled() : mesh::StitchLibrary::load(stitches);
  return mesh::emit_yarn(*project.stitch, library, options, report);
}

json yarn_json(const relax::YarnCurves& yarn) {
  const auto s = workflow::yarn_stats(yarn);
  return {{"kind", "yarn"},
          {"curves", s.curves},
          {"closed_curves", s.closed_curves},
          {"control_points", s.control_points},
          {"total_length", s.total_length},
          {"min_segment_distance", std::isfinite(s.min_segment_distance) ? json(s.min_segment_distance) : json(nullptr)},
          {"closest_points", {s.closest.first, s.closest.second}},
          {"radius", s.radius}};
}

void check_yarn_output(const std::string& path) {
  const auto ext = fs::path(path).extension();
  if (ext != ".bcc" && ext != ".obj") throw Error(path, "", "yarn is written as .bcc or .obj (polylines)");
  check_writable(path);
}

void write_yarn(const relax::YarnCurves& yarn, const std::string& path, bool preview, const std::string& unit) {
  check_yarn_output(path);
  if (fs::path(path).extension() == ".bcc") workflow::write_bcc(yarn, path, preview);
  else workflow::write_obj_polylines(yarn, path, preview, unit);
}

render::YarnColor own_colours(const relax::YarnCurves& yarn) {
  return yarn.point_colour.empty() ? render::YarnColor::StitchType : render::YarnColor::Colour;
}

void write_tubes(const relax::YarnCurves& yarn, const std::string& path, double scale, const std::string& unit) {
  const auto ext = fs::path(path).extension();
  if (ext == ".glb" || ext == ".gltf") return workflow::write_tube_gltf(yarn, path);  // metres, whatever the scale
  auto scaled = yarn;
  for (auto& p : scaled.points) p *= scale;
  scaled.radius *= scale;
  workflow::write_tube_obj(scaled, path, {.unit = unit});
}

std::pair<int, int> parse_rows(const std::string& s) {
  int a = 0, b = 0;
  char colon = 0, tail = 0;
  const int n = std::sscanf(s.c_str(), "%d%c%d%c", &a, &colon, &b, &tail);
  if (n == 1) return {a, a};
  if (n == 3 && colon == ':' && a >= 0 && b >= a) return {a, b};
  throw Error("", "--rows '" + s + "'", "expected a row or an inclusive range A:B with 0 <= A <= B");
}

void print_text(const json& j, const std::string& prefix) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) print_text(v, prefix.empty() ? k : prefix + "." + k);
  } else if (j.is_array() && !j.empty() && j.front().is_object()) {
    constexpr size_t shown = 5;
    for (size_t i = 0; i < std::min(shown, j.size()); ++i) print_text(j[i], prefix + "[" + std::to_string(i) + "]");
    if (j.size() > shown) std::cout << prefix << ": ... " << j.size() - shown << " more (see --json)\n";
  } else {
    std::cout << prefix << ": " << (j.is_string() ? j.get<std::string>() : j.dump()) << "\n";
  }
}

std::pair<int, int> parse_assignment(const std::string& option, const std::string& s) {
  int k = 0, v = 0;
  char eq = 0, tail = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &k, &eq, &v, &tail) != 3 || eq != '=')
    throw Error("", option + " '" + s + "'", "expected ID=VALUE, e.g. 12=7");
  return {k, v};
}


std::map<std::string, double> parse_take_up(const std::string& option, const std::vector<std::string>& pairs) {
  std::map<std::string, double> out;
  for (const auto& text : pairs) {
    const auto [name, value] = std::pair{text.substr(0, text.find('=')), text.find('=') == std::string::npos ? "" : text.substr(text.find('=') + 1)};
    char* end = nullptr;
    const double f = std::strtod(value.c_str(), &end);
    if (name.empty() || value.empty() || *end != 0 || !std::isfinite(f))
      throw Error("", option, "expected TYPE=FACTOR or TYPE:vertical=FACTOR (e.g. s=0.8, s:vertical=0.3), found '" + text + "'");
    const auto& take_up = workflow::yarn_option("take_up");  // a factor of the same kind as --take-up, in its range
    if (!take_up.allows(f)) throw Error("", option + " '" + text + "'", "the factor must be in " + take_up.range() + ", as --take-up's");
    out[name] = f;
  }
  return out;
}

Fabric resolve_fabric(const FabricChoice& choice, bool size_given, bool radius_given) {
  Fabric out;
  if (choice.yarn.empty() && choice.gauge.empty() && choice.needle.empty()) return out;
  if (!choice.gauge.empty() && size_given) throw Error("", "--gauge", "sets the stitch size: leave out --stitch-size and --stitch-height");
  if (!choice.needle.empty() && size_given) throw Error("", "--needle", "sets the stitch size: leave out --stitch-size and --stitch-height");
  if (!choice.needle.empty() && !choice.gauge.empty()) throw Error("", "--needle", "sets the gauge: give --needle or --gauge, not both");
  if (!choice.needle.empty() && choice.yarn.empty())
    throw Error("", "--needle", "needs the yarn knitted on it: give --yarn WEIGHT too (or the gauge itself with --gauge)");
  if (!choice.yarn.empty() && radius_given) throw Error("", "--yarn", "sets the yarn radius: leave out --yarn-radius");
  out.report = json::object();
  std::optional<mesh::Gauge> gauge;
  if (!choice.gauge.empty()) gauge = mesh::parse_gauge(choice.gauge);
  if (!choice.yarn.empty()) {
    const auto& weight = mesh::find_yarn_weight(choice.yarn);
    out.radius = weight.diameter() / 2;
    out.report["yarn"] = {{"weight", weight.name}, {"category", weight.category}, {"wraps_per_inch", weight.wraps_per_inch},
                          {"diameter_mm", weight.diameter()}, {"needle_mm", weight.needle_mm}};
    if (!choice.needle.empty()) {
      char* end = nullptr;
      const double needle = std::strtod(choice.needle.c_str(), &end);
      if (end == choice.needle.c_str() || *end != 0)
        throw Error("", "--needle '" + choice.needle + "'", "expected the needle's diameter in millimetres (e.g. 4.5)");
      gauge = mesh::needle_gauge(weight, needle);
      out.report["needle_mm"] = needle;
      out.report["needle_in_cyc_range"] = mesh::needle_in_range(weight, needle);
      if (!mesh::needle_in_range(weight, needle)) spdlog::warn("--needle {} mm: {}", needle, mesh::needle_range_note(weight));
    }
    if (!gauge && !size_given) gauge = mesh::standard_gauge(weight);
  }
  if (gauge) {
    out.size = gauge->stitch_size();
    out.report["gauge_per_10cm"] = {{"stitches", gauge->stitches}, {"rows", gauge->rows}};
    out.report["stitch_mm"] = {out.size->width, out.size->height};
    out.report["munden_loop_length_mm"] = gauge->loop_length();
  }
  return out;
}

void log_face_problems(const std::string& file, const mesh::InputMesh& mesh, const mesh::LabelReport& report, spdlog::level::level_enum level) {
  constexpr size_t kShown = 10;
  std::map<size_t, long> not_quads;  // corners -> faces among the problems
  for (size_t i = 0; i < report.face_problems.size(); ++i) {
    const auto& [f, why] = report.face_problems[i];
    if (i < kShown) spdlog::log(level, "{}: face {}: {}", file, f, why);
    if (mesh.face(f).size() != 4) ++not_quads[mesh.face(f).size()];
  }
  if (report.face_problems.size() > kShown) spdlog::log(level, "{}: ... and {} more faces like these", file, report.face_problems.size() - kShown);
  if (not_quads.empty()) return;
  std::string kinds;
  long total = 0;
  for (const auto& [corners, n] : not_quads) {
    kinds += (kinds.empty() ? "" : ", ") + std::to_string(n) + (corners == 3 ? " triangles" : " " + std::to_string(corners) + "-gons");
    total += n;
  }
  spdlog::log(level, "{}: {} of these {} faces are not quads ({}): rows are labeled across quads (Yuksel 2012 §5), so a mesh of triangles "
              "or other polygons is traced with `skein stitch MESH --field` instead (rows from the knitting distance)", file, total, report.face_problems.size(), kinds);
}

json guard_json(const relax::GuardCounters& g) {
  return {{"steps", g.steps},           {"rate_limited", g.rate_limited}, {"pairs_tested", g.pairs_tested},
          {"pairs_skipped", g.pairs_skipped}, {"sphere_tests", g.sphere_tests}, {"finest_hits", g.finest_hits},
          {"halvings", g.halvings},     {"held_points", g.held_points}};
}

namespace {
std::atomic<int> g_signal{0};
std::atomic<bool> g_interrupt{false};
extern "C" void on_signal(int signal) {
  g_signal = signal;
  g_interrupt = true;
}
}  // namespace

const std::atomic<bool>* install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGINT, SIGTERM}) sigaction(signal, &action, nullptr);
  return &g_interrupt;
}

int interrupt_signal() { return g_signal; }

namespace {
/// A free period still moving: over the run's last tenth it changed by more than 0.1 %.
bool period_creeping(const std::vector<double>& periods) {
  if (periods.size() < 10) return false;
  const double late = periods[periods.size() - periods.size() / 10 - 1], last = periods.back();
  return std::abs(last - late) > 1e-3 * std::abs(last);
}
}  // namespace

RelaxOutcome relax_and_write(const relax::YarnCurves& yarn, const relax::YarnSystem& system, const relax::ShapeTargets& targets,
                             const relax::YarnRelaxOptions& options, relax::YarnState& state, const YarnRunOutputs& run) {
  std::unique_ptr<std::ofstream> log;
  if (!run.log.empty()) {
    // Going on from a checkpoint, the log keeps its rows up to the checkpoint's step (a killed run may have
    // logged further) and goes on from there.
    std::string kept = "step,energy,residual,time_step,moved_mm,contacts,guard_hits,held_points,crossings,seconds,awake,force,period_x,period_y\n";
    if (state.step > 0) {
      std::ifstream old(run.log);
      std::string line;
      for (bool header = true; std::getline(old, line); header = false)
        if (!header && std::atol(line.c_str()) <= state.step) kept += line + "\n";
    }
    log = std::make_unique<std::ofstream>(run.log, std::ios::trunc);
    *log << kept;
  }
  ProgressBar bar(run.progress);
  auto relaxer = cuda::make_yarn_relaxer(relax::parse_backend(run.backend), system, targets, options);
  spdlog::info("relaxing with {} ({} CPU threads for the host side{}, wait policy {})", relax::to_string(options.method), omp_get_max_threads(),
               following_free_cores() ? ", following the free cores" : "", wait_policy());
  const double log_tol = std::log(std::max(options.tolerance, 1e-12));
  std::vector<std::array<double, 3>> history;  // step, residual, energy
  std::vector<double> periods;                 // with a free period: L_x + L_y, step by step
  const Stopwatch clock;
  const auto report = relaxer->run(state, [&](const relax::YarnStepLog& s) {
    if (log)
      *log << s.step << ',' << s.energy << ',' << s.residual << ',' << s.time_step << ',' << s.moved << ',' << s.contacts << ','
           << s.guard_hits << ',' << s.held_points << ',' << s.crossings << ',' << clock.seconds() << ',' << s.awake << ','
           << s.force << ',' << s.period_x << ',' << s.period_y << std::endl;  // flushed: a long job's log can be followed
    history.push_back({static_cast<double>(s.step), s.residual, s.energy});
    if (options.period.free) periods.push_back(s.period_x + s.period_y);
    const double by_steps = static_cast<double>(s.step) / std::max<long>(options.max_steps, 1);
    const double by_residual = s.residual > 0 && s.residual < 1 ? std::log(s.residual) / log_tol : 0;
    char text[160];
    std::snprintf(text, sizeof text, "step %ld residual %.3g move %.3g mm contacts %ld", s.step, s.residual, s.moved, s.contacts);
    bar.show(std::max(by_steps, by_residual), text);
    if (!isatty(fileno(stderr)) && s.step % 500 == 0) spdlog::info("{}", text);
  });
  auto yarn_out_curves = relax::with_points(yarn, state.points * run.scale);
  yarn_out_curves.radius = run.radius_out > 0 ? run.radius_out : yarn_out_curves.radius * run.scale;
  const bool final = report.stopped_by != relax::StopReason::Interrupted;
  if (final) write_yarn(yarn_out_curves, run.output);
  if (final && !run.tubes.empty()) write_tubes(yarn_out_curves, run.tubes);
  spdlog::info("{} after {} steps ({:.2f} s): residual {:.3g}, {} guard hits, {} held points, {} pull-through events{}",
               relax::to_string(report.stopped_by), report.steps, report.wall_seconds, report.residual, report.guard.finest_hits, report.guard.held_points,
               report.pull_through_events < 0 ? std::string("unaudited") : std::to_string(report.pull_through_events),
               final ? "; wrote " + run.output : std::string());
  if (report.stopped_by == relax::StopReason::StepCap && options.period.free && options.period.method == relax::PeriodOptions::Method::Frame &&
      options.period.free_x != options.period.free_y && !options.period.shear && period_creeping(periods))
    spdlog::info("the free period was still moving at the step cap (under tension a width is a soft mode the frame creeps along): "
                 "--period-method bracket relaxes fixed widths until the stress-free one is bracketed (docs/patterns.md)");
  if (!final)
    spdlog::warn("interrupted at step {}: {}", report.steps,
                 options.checkpoint.empty() ? std::string("without a checkpoint file the state is lost")
                                            : "the checkpoint " + options.checkpoint.string() + " holds the state; --resume it to go on");
  // The residual history, thinned to at most 1000 entries.
  json steps = json::array(), residuals = json::array(), energies = json::array();
  const size_t stride = history.size() / 1000 + 1;
  for (size_t i = 0; i < history.size(); ++i)
    if (i % stride == 0 || i + 1 == history.size()) {
      steps.push_back(static_cast<long>(history[i][0]));
      residuals.push_back(history[i][1]);
      energies.push_back(history[i][2]);
    }
  json j = {{"input", run.input}, {"method", relax::to_string(options.method)}, {"backend", report.backend}, {"threads", omp_get_max_threads()},
            {"control_points", system.num_points()}, {"segments", system.num_segments()},
            {"contact_samples", system.sample_start.back() + system.contact_samples.back()}, {"contact_spacing_r", options.sampling.spacing},
            {"converged", report.converged}, {"stopped_by", relax::to_string(report.stopped_by)}, {"steps", report.steps},
            {"wall_seconds", report.wall_seconds}, {"us_per_point_step", report.steps > 0 ? 1e6 * report.wall_seconds / report.steps / system.num_points() : 0.0},
            {"residual", report.residual}, {"energy", report.energy}, {"contacts", report.contacts},
            {"first_residual_peak", report.first_residual_peak < 0 ? json(nullptr) : json(report.first_residual_peak)},
            {"guard_events", guard_json(report.guard)},
            {"pull_through_events", report.pull_through_events < 0 ? json(nullptr) : json(report.pull_through_events)},
            {"rollbacks", report.rollbacks}, {"contact_rebuilds", report.contact_rebuilds},
            {"yarn", yarn_json(yarn_out_curves)},
            {"history", {{"step", steps}, {"residual", residuals}, {"energy", energies}}}};
  j["threads_follow_free_cores"] = following_free_cores();
  j["wait_policy"] = wait_policy();
  j["stop_scale"] = options.clipped_scale ? "clipped" : "first";
  j["stop_rule"] = relax::to_string(options.stop_rule);
  j["force_residual"] = report.force_residual;
  if (!report.period.isZero()) {
    // The relaxed repeat as a knitter reads it: its size and the gauge, per 10 cm (Leaf §7 set the period by hand);
    // a fixed period's stress says which way its stress-free one lies.
    const Eigen::Matrix<double, 3, 2> period = report.period * run.scale;
    const double lx = period(0, 0), ly = period(1, 1);
    json free = {{"period_x_mm", {period(0, 0), period(1, 0), period(2, 0)}}, {"period_y_mm", {period(0, 1), period(1, 1), period(2, 1)}},
                 {"repeat_mm", {lx, ly}}, {"shear", period(0, 1) / ly},
                 {"stress_over_bending", {report.period_stress.x(), report.period_stress.y(), report.period_stress.z()}},
                 {"repeat_energy", report.repeat_energy},
                 {"repeat_energy_terms", {{"bending", report.repeat_terms.bending}, {"stretch", report.repeat_terms.stretch},
                                          {"length", report.repeat_terms.length}, {"contact", report.repeat_terms.contact}}}};
    if (run.repeat[0] > 0 && run.repeat[1] > 0) {
      free["gauge_per_10cm"] = {{"stitches", 100.0 * run.repeat[0] / lx}, {"rows", 100.0 * run.repeat[1] / ly}};
      // Munden's dimensional constants Kc = courses per length × l and Kw = wales per length × l.
      const double loop = relax::patch_loop_length(system, targets.periodic, run.repeat) * run.scale;
      free["loop_length_mm"] = loop;
      free["Kc"] = run.repeat[1] / ly * loop;
      free["Kw"] = run.repeat[0] / lx * loop;
      // A loop of yarn length l stands at most l / 2 tall: rows further apart than that no longer interlock. With
      // a free row height frictionless yarn can get there, its loops sliding out of each other (docs/patterns.md).
      const double row = ly / run.repeat[1];
      free["rows_apart"] = report.free_period && row > 0.5 * loop;
      if (free["rows_apart"].get<bool>())
        spdlog::warn("the rows relaxed {:.1f} mm apart, more than half the loop length ({:.1f} mm): their loops have slid out of each other; "
                     "free only the width (--free-period x) to hold the rows at the height of the gauge",
                     row, loop);
      if (run.extra.contains("fabric") && run.extra["fabric"].contains("gauge_per_10cm")) {
        // The relaxed repeat against the gauge and Munden's loop length that were asked for (--gauge, --yarn).
        const json& fabric = run.extra["fabric"];
        free["against_asked"] = {{"stitches", 100.0 * run.repeat[0] / lx / fabric["gauge_per_10cm"]["stitches"].get<double>()},
                                 {"rows", 100.0 * run.repeat[1] / ly / fabric["gauge_per_10cm"]["rows"].get<double>()},
                                 {"loop_length", loop / fabric["munden_loop_length_mm"].get<double>()}};
      }
    }
    if (report.free_period) {
      const bool bracket = options.period.method == relax::PeriodOptions::Method::Bracket;
      free["method"] = bracket ? "bracket" : "frame";
      if (bracket) free["widths_relaxed"] = report.period_trials;
    }
    j[report.free_period ? "free_period" : "fixed_period"] = free;
    if (report.free_period)
      spdlog::info("free period: the repeat {} {:.2f} x {:.2f} mm (shear {:.3f}){}", report.converged ? "relaxed to" : "not converged, at", lx, ly,
                   period(0, 1) / ly,
                   run.repeat[0] > 0 ? fmt::format(": {:.1f} stitches and {:.1f} rows per 10 cm", 100.0 * run.repeat[0] / lx, 100.0 * run.repeat[1] / ly)
                                     : std::string());
    else
      spdlog::info("fixed period {:.2f} x {:.2f} mm: its stress {:.2g} across the courses, {:.2g} along the wales x B/r^3 "
                   "(positive: the repeat would shrink that way; --free-period finds where it is zero)",
                   lx, ly, report.period_stress.x(), report.period_stress.y());
  }
  if (options.active_set.enabled) {
    const auto& a = report.active;
    const double all = static_cast<double>(report.steps) * system.num_points();
    j["active_set"] = {{"point_steps", a.point_steps}, {"integrated_share", all > 0 ? a.point_steps / all : 1.0}, {"sleeps", a.sleeps},
                       {"wakes_by_force", a.wakes_by_force}, {"wakes_by_move", a.wakes_by_move}};
  }
  j.update(run.extra);
  if (!run.report.empty()) write_json(j, run.report);
  if (final && !run.png.empty()) render_yarn_tubes(yarn_out_curves, run.png, run.color, run.views, run.panel);
  return {std::move(j), report.stopped_by};
}

int exit_status(relax::StopReason stopped_by) {
  if (stopped_by == relax::StopReason::Diverged) return 1;
  if (stopped_by == relax::StopReason::Interrupted) return 128 + interrupt_signal();
  return 0;
}

}  // namespace skein::cli
