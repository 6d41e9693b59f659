#pragma once
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace skein::mesh {

/// Where a yarn piece leaves its face (Yuksel 2012 §4.1: one crossing per wale edge, two per course edge).
/// The positions are fixed by convention, the same for every model, so that pieces of neighbouring faces
/// meet: wale crossings at kWaleCrossing of the edge's height, course crossings at kCourseSlots of the
/// edge's length (slot a, slot b, from the edge's left end).
struct Crossing {
  enum class Side : char { Left, Right, Bottom, Top };
  Side side = Side::Left;
  int edge = 0;  ///< bottom or top edge index, left to right
  int slot = 0;  ///< 0 = a, 1 = b (course edges)
  bool operator==(const Crossing&) const = default;
  std::string name() const;  ///< "L", "R", "B0a", "T2b"
};
inline constexpr double kWaleCrossing = 0.35;
inline constexpr double kCourseSlots[2] = {0.3, 0.7};

/// A control point of a yarn piece: in the face's canonical polygon (u across the course 0..1, v along the
/// wale 0..1) plus an offset h along the surface normal in yarn radii; or a crossing.
struct ModelPoint {
  Eigen::Vector3d uvh = Eigen::Vector3d::Zero();
  std::optional<Crossing> crossing;
};

struct YarnPiece {
  std::vector<ModelPoint> points;  ///< first and last may be crossings; crossings nowhere else
};

/// A stitch model (Yuksel 2012 §4): yarn pieces in face-local 2.5D coordinates. The canonical polygon has its
/// `bottom` course edges on v = 0 and `top` course edges on v = 1, splitting [0, 1] evenly, and the wale edges
/// on u = 0 and u = 1 (cable faces and border pieces have no wale edges).
struct StitchModel {
  std::string name;
  std::string note;  ///< the comment lines at the top of the file
  int bottom = 1, top = 1;
  bool wale_edges = true;
  std::vector<YarnPiece> pieces;

  /// Canonical (u, v) of a crossing of this model.
  Eigen::Vector2d crossing_uv(const Crossing& c) const;
};

/// Parses and validates a `.stitch` file (stitches/FORMAT.md): every wale edge crossed exactly once, every
/// course edge exactly twice (slots a and b), crossings only at the ends of pieces, points inside the
/// canonical polygon. Throws skein::Error naming the file, the line and the rule.
StitchModel parse_stitch_model(const std::string& text, const std::string& file);
/// Writes a model in the `.stitch` format (numbers exact, so parse(format(m)) == m).
std::string format_stitch_model(const StitchModel& model);

/// All models of a folder, by name. Stitch types of the registry must fit their shape.
class StitchLibrary {
public:
  /// Reads every `*.stitch` file of `folder`; throws skein::Error for the first bad file.
  static StitchLibrary load(const std::filesystem::path& folder);
  /// The bundled library: $SKEIN_STITCHES if set, else the stitches/ folder of the source tree.
  static const StitchLibrary& bundled();
  static std::filesystem::path bundled_folder();

  const StitchModel* find(const std::string& name) const;
  const StitchModel& at(const std::string& name) const;  ///< throws skein::Error when missing
  const std::map<std::string, StitchModel>& models() const { return m_models; }

private:
  std::map<std::string, StitchModel> m_models;
};

}  // namespace skein::mesh
