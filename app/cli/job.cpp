#include "job.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

#include <unistd.h>

#include <nlohmann/json.hpp>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "json_keys.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "relax/yarn_checkpoint.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/fabric.hpp"
#include "stitchmesh/knit_field.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "workflow/yarn_shape.hpp"

namespace skein::cli {
namespace {

surface::MeshRelaxOptions mesh_options(const Keys& k) {
  k.only({"alpha", "aspect", "k_stretch", "k_shear", "k_wale", "k_fold", "max_steps", "tolerance", "max_move", "cg_iterations"});
  surface::MeshRelaxOptions o;
  o.alpha = k.number("alpha", o.alpha, 1e-3, 1);
  o.aspect = k.number("aspect", o.aspect, 1e-3, 1e3);
  o.k_stretch = k.number("k_stretch", o.k_stretch, 0, 1e6);
  o.k_shear = k.number("k_shear", o.k_shear, 0, 1e6);
  o.k_wale = k.number("k_wale", o.k_wale, 0, 1e6);
  o.k_fold = k.number("k_fold", o.k_fold, 0, 1e6);
  o.max_steps = static_cast<int>(k.integer("max_steps", o.max_steps, 0, 1000000));
  o.tolerance = k.number("tolerance", o.tolerance, 0, 1e3);
  o.max_move = k.number("max_move", o.max_move, 1e-6, 1e3);
  o.cg_iterations = static_cast<int>(k.integer("cg_iterations", o.cg_iterations, 1, 100000));
  return o;
}

relax::YarnRelaxOptions yarn_options(const Keys& k, std::string& backend) {
  k.only({"method", "backend", "max_steps", "max_seconds", "tolerance", "stall", "stop_scale", "stop_rule", "force_tolerance", "stall_window",
          "energy_stall", "jam_steps", "jam_drop", "max_move", "audit", "active_set",
          "contact_spacing", "checkpoint_every", "checkpoint_minutes", "k_bend", "k_stretch", "k_length", "k_contact"});
  relax::YarnRelaxOptions o;
  o.method = relax::parse_yarn_method(k.choice("method", "fire", workflow::yarn_option("method").choices));
  backend = k.choice("backend", "auto", {"auto", "cpu", "cuda"});
  o.max_steps = static_cast<long>(k.option("max_steps", o.max_steps));
  o.max_seconds = k.option("max_seconds", 0);
  o.tolerance = k.option("tolerance", o.tolerance);
  o.stall = k.option("stall", o.stall);
  o.clipped_scale = k.choice("stop_scale", "first", workflow::yarn_option("stop_scale").choices) == "clipped";
  o.stop_rule = relax::parse_stop_rule(k.choice("stop_rule", "leaf", workflow::yarn_option("stop_rule").choices));
  o.force_tolerance = k.option("force_tolerance", o.force_tolerance);
  o.stall_window = static_cast<long>(k.option("stall_window", o.stall_window));
  o.energy_stall = k.option("energy_stall", o.energy_stall);
  o.jam_steps = static_cast<long>(k.option("jam_steps", o.jam_steps));
  o.jam_drop = k.option("jam_drop", o.jam_drop);
  o.guard.max_move = k.option("max_move", o.guard.max_move);
  o.audit = k.flag("audit", true);
  o.active_set.enabled = k.flag("active_set", false);
  o.sampling.spacing = k.option("contact_spacing", 0);
  // Step-based checkpoints by default: a resumed job then ends exactly as an uninterrupted one would.
  o.checkpoint_every = static_cast<long>(k.option("checkpoint_every", 500));
  o.checkpoint_minutes = k.option("checkpoint_minutes", 0);
  o.params.k_bend = k.option("k_bend", o.params.k_bend);
  o.params.k_stretch = k.option("k_stretch", o.params.k_stretch);
  o.params.k_length = k.option("k_length", o.params.k_length);
  o.params.k_contact = k.option("k_contact", o.params.k_contact);
  return o;
}

JobEdit job_edit(const Keys& k) {
  k.only({"fill", "pattern", "near_border", "rows", "face"});
  JobEdit e;
  if (k.has("fill") == k.has("pattern")) k.fail(k.name("fill"), "each edit has either \"fill\" or \"pattern\"");
  if (k.has("fill")) {
    e.fill = k.text("fill", "");
    try {
      mesh::parse_fill(e.fill);
    } catch (const Error& error) {
      k.fail(k.name("fill"), error.rule());
    }
    if (k.has("face")) k.fail(k.name("face"), "only a pattern has a first stitch");
  } else {
    e.pattern = k.file("pattern");
    e.face = static_cast<int>(k.integer("face", -1, -1, 1 << 30));
  }
  if (k.has("near_border") && k.has("rows")) k.fail(k.name("rows"), "give \"near_border\" or \"rows\", not both");
  e.near_border = static_cast<int>(k.integer("near_border", -1, 0, 1 << 20));
  if (k.has("rows")) {
    try {
      e.rows = parse_rows(k.text("rows", ""));
    } catch (const Error& error) {
      k.fail(k.name("rows"), "expected a row or an inclusive range \"A:B\" with 0 <= A <= B, found " + k.at("rows").dump());
    }
  }
  return e;
}

}  // namespace

Job parse_job(const std::string& text, const fs::path& file) {
  const json j = parse_user_json(text, file);
  const Keys k(j, "", file);
  Job job;
  job.file = file;
  job.name = k.text("name", file.stem().string());
  if (k.has("smocking")) {
    // A smocking job (docs/smocking.md): the pattern, how far its threads are pulled, the output folder.
    k.only({"name", "smocking", "output", "pictures"});
    const Keys sm(k.at("smocking"), "smocking", file);
    sm.only({"pattern", "gamma", "pull", "thickness", "snapshots", "max_iterations", "cloth", "cloth_subdivisions", "cloth_frames"});
    SmockingJob s;
    if (!sm.has("pattern")) sm.fail(sm.name("pattern"), "is missing: the smocking pattern (.smock)");
    s.pattern = sm.file("pattern");
    if (sm.has("gamma")) s.args.gamma = sm.number("gamma", 0.3, 1e-6, 1);
    if (sm.has("pull")) {
      const json& pull = sm.at("pull");
      if (pull == "along") s.args.pull = "along";
      else if (pull.is_array() && pull.size() == 2 && pull[0].is_number() && pull[1].is_number())
        s.args.pull = std::to_string(pull[0].get<double>()) + "," + std::to_string(pull[1].get<double>());
      else sm.fail(sm.name("pull"), "expected [X, Y] (the pulling direction) or \"along\", found " + pull.dump());
    }
    s.args.options.thickness = sm.number("thickness", -1, 1e-6, 1e4);
    s.args.options.max_iterations = static_cast<int>(sm.integer("max_iterations", s.args.options.max_iterations, 0, 100'000'000));
    if (sm.has("snapshots")) {
      const json& list = sm.at("snapshots");
      if (!list.is_array()) sm.fail(sm.name("snapshots"), "expected a list of fractions in (0, 1], found " + list.dump());
      for (const auto& f : list) {
        if (!f.is_number() || !(f.get<double>() > 0 && f.get<double>() <= 1)) sm.fail(sm.name("snapshots"), "expected fractions in (0, 1], found " + f.dump());
        s.args.options.snapshots.push_back(f.get<double>());
      }
    }
    s.cloth = sm.flag("cloth", false);
    if (sm.has("cloth_subdivisions")) {
      if (!s.cloth) sm.fail(sm.name("cloth_subdivisions"), "needs \"cloth\": true");
      s.args.cloth_options.subdivisions = static_cast<int>(sm.integer("cloth_subdivisions", 2, -1'000'000, 1'000'000));
      try {
        s.args.cloth_options.validate();
      } catch (const Error& e) {
        sm.fail(sm.name("cloth_subdivisions"), e.rule());
      }
    }
    if (sm.has("cloth_frames")) {
      if (!s.cloth) sm.fail(sm.name("cloth_frames"), "needs \"cloth\": true");
      s.args.cloth_options.frames = static_cast<int>(sm.integer("cloth_frames", s.args.cloth_options.frames, 1, 100'000));
    }
    job.smocking = std::move(s);
    job.output = (file.parent_path() / k.text("output", "out/" + job.name)).lexically_normal();
    job.pictures = k.flag("pictures", true);
    return job;
  }
  if (k.has("weave")) {
    // A weaving job (docs/woven.md): a design, the exemplars, the synthesis and the picture.
    k.only({"name", "weave", "output", "pictures"});
    const Keys w(k.at("weave"), "weave", file);
    w.only({"pattern", "picture", "weaves", "exemplars", "size", "edge_rank", "randomize", "seed", "warp_colors", "weft_colors", "width", "height", "samples",
            "tilt", "field", "compare_truth"});
    WeavingJob s;
    auto& a = s.args;
    if (w.has("pattern") == w.has("picture")) w.fail(w.name("pattern"), "give a woven pattern (.weave or .wif) or a picture, one of the two");
    if (w.has("pattern")) a.pattern = w.file("pattern").string();
    if (w.has("picture")) {
      a.picture = w.file("picture").string();
      const json& list = w.has("weaves") ? w.at("weaves") : json();
      if (!list.is_array() || list.empty()) w.fail(w.name("weaves"), "expected a list of woven patterns, one per colour of the picture");
      for (size_t i = 0; i < list.size(); ++i) {
        const json entry = {{std::to_string(i), list[i]}};  // Keys holds a reference: the object must outlive it
        const Keys item(entry, w.name("weaves"), file);
        a.weaves.push_back(item.file(std::to_string(i)).string());
      }
    } else if (w.has("weaves")) {
      w.fail(w.name("weaves"), "is for a picture's colours; a pattern is one weave");
    }
    if (w.has("exemplars")) a.exemplars = w.file("exemplars").string();
    a.size = w.text("size", "");
    a.edge_rank = static_cast<int>(w.integer("edge_rank", a.edge_rank, 0, 256));
    a.synthesis.randomize = w.flag("randomize", true);
    a.synthesis.seed = static_cast<std::uint64_t>(w.integer("seed", 1, 0, 1L << 62));
    a.warp_colors = w.text("warp_colors", a.warp_colors);
    a.weft_colors = w.text("weft_colors", a.weft_colors);
    a.render.width = static_cast<int>(w.integer("width", a.render.width, 8, 8192));
    a.render.height = static_cast<int>(w.integer("height", a.render.height, 8, 8192));
    a.render.samples = static_cast<int>(w.integer("samples", a.render.samples, 1, 65536));
    a.render.tilt = w.number("tilt", a.render.tilt, 0, 80);
    a.render.field = w.number("field", 0, 0, 1e6);
    a.compare_truth = w.flag("compare_truth", false);
    job.weaving = std::move(s);
    job.output = (file.parent_path() / k.text("output", "out/" + job.name)).lexically_normal();
    job.pictures = k.flag("pictures", true);
    return job;
  }
  k.only({"name", "mesh", "labels", "start", "end", "stitch_size", "gauge", "max_stitches", "edits", "relax_mesh", "yarn", "relax_yarn", "output", "pictures",
          "smocking", "weave"});
  if (!k.has("mesh"))
    k.fail("mesh", "is missing: the garment mesh to knit (OBJ, PLY, glTF, ... or a .skein project), \"smocking\" for a smocking job or \"weave\" for a weaving job");
  job.mesh = k.file("mesh");
  const std::string labels = k.text("labels", "auto");
  if (labels == "field") job.field = true;
  else if (labels != "auto") job.labels = k.file("labels");
  // Where the rows start and end (issue 25): a border edge for "auto" and "field" (an end for "field" only), a
  // surface point for "field".
  const auto knit_place = [&](const std::string& key) {
    const Keys at(k.at(key), key, file);
    at.only({"edge", "point"});
    if (!job.labels.empty()) k.fail(key, "is for \"labels\": \"auto\" or \"field\"; a labels file says where its rows " + key);
    if (key == "end" && !job.field) k.fail(key, "is for \"labels\": \"field\" (rows traced from the start to the end)");
    if (at.has("edge") == at.has("point")) at.fail(key, "give \"edge\" (a border edge) or \"point\" ([x, y, z] on the surface), one of them");
    mesh::KnitStart place;
    place.border_edge = static_cast<int>(at.integer("edge", -1, 0, 1 << 30));
    if (at.has("point")) {
      if (!job.field) at.fail(at.name("point"), "is for \"labels\": \"field\" (knitting in the round from a point)");
      const json& p = at.at("point");
      if (!p.is_array() || p.size() != 3 || !std::all_of(p.begin(), p.end(), [](const json& v) { return v.is_number() && std::isfinite(v.get<double>()); }))
        at.fail(at.name("point"), "expected [x, y, z] in the mesh's units, found " + p.dump());
      place.point = Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    }
    return place;
  };
  if (k.has("start")) job.start = knit_place("start");
  if (k.has("end")) job.end = knit_place("end");
  if (k.has("stitch_size")) {
    const Keys size(k.at("stitch_size"), "stitch_size", file);
    size.only({"width", "height"});
    job.stitch_size.width = size.number("width", job.stitch_size.width, 1e-3, 1e4);
    job.stitch_size.height = size.number("height", job.stitch_size.height, 1e-3, 1e4);
  }
  if (k.has("gauge")) {
    // Stitches and rows in 10 cm of stockinette (issue 24): the stitch size as a yarn label gives it.
    if (k.has("stitch_size")) k.fail("gauge", "sets the stitch size: give stitch_size or gauge, not both");
    const Keys gauge(k.at("gauge"), "gauge", file);
    gauge.only({"stitches", "rows"});
    if (!gauge.has("stitches")) gauge.fail(gauge.name("stitches"), "is missing: stitches in 10 cm of stockinette");
    const double stitches = gauge.number("stitches", 0, 0.1, 1000);
    job.stitch_size = mesh::Gauge{stitches, gauge.number("rows", mesh::kLoopShapeFactor * stitches, 0.1, 1000)}.stitch_size();
  }
  job.max_stitches = k.number("max_stitches", job.max_stitches, 1, 1e9);
  if (k.has("edits")) {
    if (!k.at("edits").is_array()) k.fail("edits", "expected a list [...] of edits, found " + k.at("edits").dump());
    for (size_t i = 0; i < k.at("edits").size(); ++i) job.edits.push_back(job_edit(Keys(k.at("edits")[i], "edits[" + std::to_string(i) + "]", file)));
  }
  const auto stage = [&](const std::string& key) {
    if (k.has(key) && k.at(key).is_boolean()) return k.at(key).get<bool>() ? json::object() : json();
    return k.has(key) ? k.at(key) : json::object();
  };
  if (const json m = stage("relax_mesh"); !m.is_null()) job.relax_mesh = mesh_options(Keys(m, "relax_mesh", file));
  if (k.has("yarn")) {
    const Keys yarn(k.at("yarn"), "yarn", file);
    yarn.only({"weight", "radius", "take_up", "needle"});
    job.yarn_radius = yarn.number("radius", 0, 0, 1e3);
    if (yarn.has("weight")) {
      // A yarn weight class (issue 24): its radius, and its standard gauge where the job gives no stitch size.
      if (yarn.has("radius")) yarn.fail(yarn.name("weight"), "sets the radius: give radius or weight, not both");
      const std::string name = yarn.text("weight", "");
      const mesh::YarnWeight* weight = nullptr;
      try {
        weight = &mesh::find_yarn_weight(name);
      } catch (const Error& e) {
        yarn.fail(yarn.name("weight"), e.rule());
      }
      job.yarn_radius = weight->diameter() / 2;
      job.yarn_weight = weight->name;
      if (yarn.has("needle")) {
        // The gauge of this yarn knitted on that needle (mesh::needle_gauge): the stitch size.
        for (const char* size_key : {"stitch_size", "gauge"})
          if (k.has(size_key)) yarn.fail(yarn.name("needle"), std::string("sets the stitch size: give ") + size_key + " or the needle, not both");
        const double needle = yarn.number("needle", 0, 1e-3, 50);
        job.stitch_size = mesh::needle_gauge(*weight, needle).stitch_size();
        if (!mesh::needle_in_range(*weight, needle)) spdlog::warn("{}: {} {} mm: {}", file.string(), yarn.name("needle"), needle, mesh::needle_range_note(*weight));
      } else if (!k.has("stitch_size") && !k.has("gauge")) {
        job.stitch_size = mesh::standard_gauge(*weight).stitch_size();
      }
    } else if (yarn.has("needle")) {
      yarn.fail(yarn.name("needle"), "needs the yarn knitted on it: give the yarn's weight too (or the gauge itself)");
    }
    if (yarn.has("take_up")) job.take_up = yarn.number("take_up", 1, 0.1, 10);
  }
  if (const json y = stage("relax_yarn"); !y.is_null()) job.relax_yarn = yarn_options(Keys(y, "relax_yarn", file), job.backend);
  job.output = (file.parent_path() / k.text("output", "out/" + job.name)).lexically_normal();
  job.pictures = k.flag("pictures", true);
  return job;
}

Job read_job(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(file.string(), "", "cannot be read (missing or no permission)");
  std::stringstream s;
  s << in.rdbuf();
  return parse_job(s.str(), file);
}

namespace {

/// The job's report and stage clock: every stage is timed and logged, and the report is written (atomically)
/// however the job ends.
class JobRun {
public:
  JobRun(const Job& job, bool resume) : m_job(job) {
    m_report = {{"job", job.name}, {"job_file", job.file.string()}, {"output", job.output.string()}, {"resumed", resume},
                {"status", "running"}, {"stages", json::array()}};
  }
  template <class F>
  void stage(const std::string& name, F&& work) {
    spdlog::info("[{}] {}", m_job.name, name);
    Stopwatch t;
    work();
    m_report["stages"].push_back({{"stage", name}, {"seconds", t.seconds()}});
    spdlog::info("[{}] {} done ({:.2f} s)", m_job.name, name, t.seconds());
  }
  json& report() { return m_report; }
  void finish(const std::string& status) {
    m_report["status"] = status;
    m_report["total_seconds"] = m_total.seconds();
    write_json(m_report, (m_job.output / "report.json").string());
  }
  std::string out(const std::string& name) const { return (m_job.output / name).string(); }

private:
  const Job& m_job;
  json m_report;
  Stopwatch m_total;
};

/// Fails early when the disk cannot hold what the job will write: the yarn files, a checkpoint and pictures.
void check_space(const fs::path& folder, long points) {
  const std::uintmax_t needed = static_cast<std::uintmax_t>(points) * 200 + (64u << 20);
  std::error_code ec;
  const auto space = fs::space(folder, ec);
  if (!ec && space.available < needed)
    throw Error(folder.string(), "", "only " + std::to_string(space.available >> 20) + " MiB free; the job needs about " + std::to_string(needed >> 20) + " MiB");
}

}  // namespace

int run_job(const Job& job, bool resume, bool progress) {
  // The output folder first: an unwritable place fails before any work.
  std::error_code ec;
  fs::create_directories(job.output, ec);
  if (ec || !fs::is_directory(job.output)) throw Error(job.output.string(), "", "the output folder cannot be made: " + (ec ? ec.message() : "it is not a folder"));
  const auto probe = job.output / ".skein-write-test";
  if (!std::ofstream(probe)) throw Error(job.output.string(), "", "cannot write in the output folder");
  fs::remove(probe, ec);
  check_space(job.output, 0);
  const fs::path checkpoint = job.output / "yarn.ckp";
  if (resume && !job.relax_yarn) throw Error(job.file.string(), "key 'relax_yarn'", "is off, so there is nothing to resume");

  auto log_sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>((job.output / "job.log").string(), !resume);
  spdlog::default_logger()->sinks().push_back(log_sink);
  struct DropSink {
    ~DropSink() { spdlog::default_logger()->sinks().pop_back(); }
  } drop_sink;
  const auto* interrupt = install_interrupt_handlers();

  JobRun run(job, resume);
  if (job.smocking) {
    if (resume) throw Error(job.file.string(), "key 'smocking'", "a smocking job has nothing to resume (it takes seconds)");
    int status = 0;
    try {
      run.stage("gather the smocking pattern", [&] {
        SmockArgs args = job.smocking->args;
        args.input = job.smocking->pattern.string();
        args.output = run.out("embedding.json");
        args.obj = run.out("threads.obj");
        if (job.pictures) args.png = run.out("smocking.png"), args.chart_png = run.out("shrinkage.png");
        if (job.smocking->cloth) {
          args.cloth = run.out("cloth.glb");
          if (job.pictures) args.cloth_png = run.out("cloth.png");
        }
        const json report = smock(args);
        run.report()["smocking"] = report;
        status = report["stopped_by"] == "reached" ? 0 : 1;
      });
    } catch (const Error& e) {
      run.report()["error"] = e.what();
      run.finish("failed");
      throw;
    }
    run.finish(status == 0 ? "done" : "stalled");
    return status;
  }
  if (job.weaving) {
    if (resume) throw Error(job.file.string(), "key 'weave'", "a weaving job has nothing to resume");
    try {
      run.stage("synthesize the woven volume", [&] {
        WeaveVolumeArgs args = job.weaving->args;
        args.output = run.out("volume.vdb");
        args.assignment = run.out("assignment.txt");
        if (job.pictures) args.png = run.out("render.png");
        run.report()["weave"] = weave_volume(args);
      });
    } catch (const Error& e) {
      run.report()["error"] = e.what();
      run.finish("failed");
      throw;
    }
    run.finish("done");
    return 0;
  }
  try {
    mesh::Project project;
    project.stitch_size = job.stitch_size;
    run.stage("load and label", [&] {
      project.input = load_input(job.mesh);
      if (job.field) {  // the traced rows become the project's input mesh, one stitch a face
        mesh::check_stitch_count(*project.input, job.stitch_size, job.max_stitches);  // before tracing, which grows with it
        auto traced = mesh::trace_stitch_mesh(*project.input, job.start, job.stitch_size, job.end);  // by default from the lowest border
        project.input = std::move(traced.mesh);
        project.labels = std::move(traced.labels);
        project.values = std::move(traced.values);
      } else if (job.labels.empty()) {
        project.labels = mesh::auto_label(*project.input, job.start.border_edge >= 0 ? job.start.border_edge : mesh::default_start_edge(*project.input));
      } else {
        auto [labels, values] = labels_for(*project.input, job.labels);
        project.labels = std::move(labels);
        project.values = std::move(values);
      }
      run.report()["mesh"] = mesh_json(*project.input);
      run.report()["labels"] = labels_json(*project.input, *project.labels);
    });
    run.stage("tessellate and edit", [&] {
      mesh::check_stitch_count(*project.input, job.stitch_size, job.max_stitches);
      if (!project.values) project.values = mesh::initial_values(*project.input, *project.labels, job.stitch_size);
      auto stitch = mesh::tessellate(*project.input, *project.labels, *project.values);
      for (const auto& edit : job.edits) {
        std::vector<int> faces;
        if (edit.near_border >= 0) faces = mesh::faces_near_border(stitch, edit.near_border);
        else
          for (int f = 0; f < static_cast<int>(stitch.faces.size()); ++f)
            if (stitch.faces[f].row >= edit.rows.first && stitch.faces[f].row <= edit.rows.second) faces.push_back(f);
        if (!edit.fill.empty()) {
          stitch = mesh::fill(stitch, faces, mesh::parse_fill(edit.fill));
          spdlog::info("filled {} over {} stitches", edit.fill, faces.size());
        } else {
          const auto pattern = mesh::read_pattern(edit.pattern);
          stitch = mesh::tile_pattern(stitch, faces, pattern, edit.face >= 0 ? edit.face : mesh::lowest_left(stitch, faces));
          spdlog::info("tiled {} over {} stitches", pattern.name, faces.size());
        }
      }
      project.stitch = std::move(stitch);
      mesh::write_project(project, run.out("stitch.skein"));
      run.report()["stitch_mesh"] = stats_json(*project.stitch);
      if (job.pictures) render_stitch_mesh(*project.stitch, run.out("stitch-types.png"), render::ColorBy::StitchType);
    });
    if (job.relax_mesh) {
      bool stopped = false;
      run.stage("relax the stitch mesh", [&] {
        auto options = *job.relax_mesh;
        options.interrupt = interrupt;
        surface::MeshRelaxer relaxer(project.input->points(), project.input->faces(), *project.stitch, options);
        if (job.pictures) render_stretch(relaxer.relaxed(), relaxer.r_course(), relaxer.r_wale(), run.out("stretch-before.png"));
        ProgressBar bar(progress);
        double first_move = 0;
        const auto report = relaxer.run([&](const surface::MeshRelaxStep& s) {
          if (first_move == 0) first_move = s.max_displacement;
          const double goal = options.tolerance * relaxer.r_course();
          const double by_move = s.max_displacement > 0 && first_move > goal ? std::log(first_move / s.max_displacement) / std::log(first_move / goal) : 0;
          char text[120];
          std::snprintf(text, sizeof text, "mesh step %d largest move %.3g mm", s.step, s.max_displacement);
          bar.show(std::max(static_cast<double>(s.step) / options.max_steps, by_move), text);
        });
        stopped = interrupt->load();
        json history = json::array();
        for (const auto& s : report.steps) history.push_back({{"step", s.step}, {"energy", s.energy}, {"max_displacement", s.max_displacement}});
        run.report()["relax_mesh"] = {{"converged", report.converged}, {"steps", report.steps.size()}, {"r_course", report.r_course},
                                      {"r_wale", report.r_wale}, {"turned_over_before", report.turned_over_before},
                                      {"turned_over_after", report.turned_over_after}, {"history", history}};
        if (stopped) return;
        project.stitch = relaxer.relaxed();
        mesh::write_project(project, run.out("relaxed.skein"));
        if (job.pictures) render_stretch(*project.stitch, relaxer.r_course(), relaxer.r_wale(), run.out("stretch-after.png"));
      });
      if (stopped) {
        spdlog::warn("interrupted during mesh relaxation; run the job again (with --resume or without) to start over");
        run.finish("interrupted");
        return 128 + interrupt_signal();
      }
    }
    relax::YarnCurves yarn;
    run.stage("emit yarn", [&] {
      mesh::EmitOptions options;
      options.yarn_radius = job.yarn_radius > 0 ? job.yarn_radius : 0.1 * job.stitch_size.width;
      // A yarn weight's yarn is relaxed at its compressed contact radius and written at its full one (docs/yarn.md).
      if (!job.yarn_weight.empty()) options.yarn_radius *= mesh::kYarnCompression;
      mesh::EmitReport emitted;
      yarn = mesh::emit_yarn(*project.stitch, mesh::StitchLibrary::bundled(), options, &emitted);
      check_space(job.output, static_cast<long>(yarn.points.size()));
      auto written = yarn;
      if (!job.yarn_weight.empty()) written.radius = job.yarn_radius;
      write_yarn(written, run.out("yarn.bcc"));
      run.report()["yarn"] = yarn_json(written);
      if (job.pictures) render_yarn_tubes(written, run.out("yarn.png"), own_colours(written));
    });
    if (!job.relax_yarn) {
      run.finish("done");
      return 0;
    }
    int status = 0;
    relax::StopReason stopped_by = relax::StopReason::Converged;
    run.stage("relax the yarn", [&] {
      auto options = *job.relax_yarn;
      options.interrupt = interrupt;
      options.checkpoint = checkpoint;
      auto system = relax::make_yarn_system(yarn, job.take_up.value_or(1), {}, options.sampling);
      if (!job.yarn_weight.empty()) {
        // As `skein relax-yarn --yarn`: unless the job gives a take-up, each stitch's yarn cut (or let out) to
        // Munden's loop length for the project's stitch width.
        const double munden = mesh::gauge_of(project.stitch_size).loop_length();
        const int stitches = static_cast<int>(project.stitch->faces.size());
        json fabric = {{"yarn", job.yarn_weight}, {"radius_mm", job.yarn_radius}, {"contact_radius_mm", yarn.radius}, {"munden_loop_length_mm", munden}};
        if (!job.take_up) {
          const double take_up = workflow::take_up_to_munden(workflow::garment_loop_length(system, stitches), munden, job.file.string(), "key 'yarn.weight'");
          system = relax::make_yarn_system(yarn, take_up, {}, options.sampling);
          fabric["take_up_to_munden"] = take_up;
        }
        fabric["yarn_per_stitch_mm"] = workflow::garment_loop_length(system, stitches);
        run.report()["fabric"] = fabric;
      }
      const auto targets = workflow::shape_targets(*project.stitch, yarn, options.shape);
      auto state = relax::initial_state(system, options);
      if (std::error_code ec; resume && fs::exists(checkpoint, ec)) {
        state = relax::read_checkpoint(checkpoint, relax::checkpoint_fingerprint(system, options.method), system.num_points());
        spdlog::info("resuming the yarn from {} at step {}", checkpoint.string(), state.step);
      } else if (resume) {
        spdlog::warn("no checkpoint {} yet: the yarn starts from the beginning", checkpoint.string());
      }
      YarnRunOutputs outputs;
      outputs.input = job.file.string();
      outputs.output = run.out("yarn-relaxed.bcc");
      outputs.backend = job.backend;
      outputs.log = run.out("yarn-relax-log.csv");
      outputs.png = job.pictures ? run.out("yarn-relaxed.png") : "";
      outputs.views = "garment";
      outputs.progress = progress;
      if (!job.yarn_weight.empty()) outputs.radius_out = job.yarn_radius;
      auto relaxed = relax_and_write(yarn, system, targets, options, state, outputs);
      run.report()["relax_yarn"] = std::move(relaxed.report);
      stopped_by = relaxed.stopped_by;
      status = exit_status(stopped_by);
    });
    if (stopped_by == relax::StopReason::Interrupted) {
      const std::string command = "skein run " + job.file.string() + " -o " + job.output.string() + " --resume";
      spdlog::warn("go on with: {}", command);
      run.report()["resume"] = command;
    }
    run.finish(stopped_by == relax::StopReason::Interrupted ? "interrupted" : stopped_by == relax::StopReason::Diverged ? "diverged" : "done");
    return status;
  } catch (const std::exception& e) {
    run.report()["error"] = e.what();
    run.finish("failed");
    throw;
  }
}

}  // namespace skein::cli
