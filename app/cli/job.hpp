#pragma once
// `skein run JOB.json`: the whole pipeline from a job file, unattended (docs/jobs.md).

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "relax/yarn_relax.hpp"
#include "surface/mesh_relax.hpp"
#include "smock.hpp"
#include "weave.hpp"
#include "stitchmesh/knit_field.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::cli {

/// One stitch edit of a job: a fill or a pattern over some stitches.
struct JobEdit {
  std::string fill;                       ///< a parse_fill name, or empty
  std::filesystem::path pattern;          ///< a .knit file, or empty
  int near_border = -1;                   ///< stitches within this many rows of a cast-on or bind-off edge; -1: by rows
  std::pair<int, int> rows{0, 1 << 30};   ///< stitch rows A..B (inclusive)
  int face = -1;                          ///< pattern: the stitch that takes its first stitch; -1: the lowest-left chosen one
};

/// A smocking job (issue 30): a pattern gathered by its threads instead of a garment knitted.
struct SmockingJob {
  std::filesystem::path pattern;
  SmockArgs args;  ///< gamma, pull and options; the output paths are set in the job's folder
  bool cloth = false;  ///< the 3-D fabric too (cloth.glb, cloth.png)
};

/// A weaving job (issue 29): a woven design's appearance volume synthesized from exemplars and rendered.
struct WeavingJob {
  WeaveVolumeArgs args;  ///< the design, exemplars and settings; the output paths are set in the job's folder
};

struct Job {
  std::filesystem::path file;    ///< the job file; relative paths in it are relative to its folder
  std::string name;
  std::filesystem::path mesh;    ///< the garment; empty for a smocking job
  std::optional<SmockingJob> smocking;
  std::optional<WeavingJob> weaving;
  std::filesystem::path labels;  ///< a .skein with labels for the mesh; empty: auto-label (or the field)
  bool field = false;            ///< "labels": "field": rows traced from the knitting field (issue 25)
  mesh::KnitStart start;         ///< "start": the border edge (auto and field) or surface point (field) the rows start from
  std::optional<mesh::KnitStart> end;  ///< "end": the border edge or surface point the rows end at (field)
  mesh::StitchSize stitch_size;
  double max_stitches = mesh::kDefaultMaxStitches;  ///< refused past this estimate (check_stitch_count)
  std::vector<JobEdit> edits;
  std::optional<surface::MeshRelaxOptions> relax_mesh;  ///< none: skipped
  double yarn_radius = 0;        ///< [mm]; 0: a tenth of the stitch width
  std::string yarn_weight;       ///< a weight class: relaxed at its compressed contact radius (docs/yarn.md); empty: none
  std::optional<double> take_up;  ///< none: 1, or with a yarn weight Munden's loop length
  std::optional<relax::YarnRelaxOptions> relax_yarn;  ///< none: skipped
  std::string backend = "auto";
  std::filesystem::path output;  ///< the folder every output goes to
  bool pictures = true;
};

/// Parses a job; throws skein::Error naming `file`, the key and what was expected (unknown keys included, so
/// that a misspelt key is not silently ignored).
Job parse_job(const std::string& text, const std::filesystem::path& file);
Job read_job(const std::filesystem::path& file);

/// Runs a job: checks the output folder first, then every stage with its time, progress and log (on the
/// terminal and in OUTPUT/job.log), writing each output atomically and OUTPUT/report.json at the end, also
/// when interrupted or failed. SIGINT and SIGTERM stop the yarn relaxation after its step with a checkpoint;
/// `resume` goes on from OUTPUT/yarn.ckp. Returns the exit status (0, 1 diverged, 128 + signal interrupted).
int run_job(const Job& job, bool resume, bool progress);

}  // namespace skein::cli
