#pragma once
// skein smock: a smocking pattern gathered by its threads (Zhou 2024 §4.1), written as JSON, OBJ and pictures.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "smocking/smocking_cloth.hpp"
#include "smocking/smocking_embed.hpp"
#include "smocking/smocking_svg.hpp"

namespace skein::cli {

struct SmockArgs {
  std::string input, output, obj, png, chart_png, report;  ///< empty: not written
  std::string write_smock;         ///< the pattern as .smock text (what an SVG drawing was read as)
  smocking::SvgImport svg;         ///< how an .svg input is read
  std::string style;               ///< an .svg input's style: italian (default), canadian or english
  std::optional<double> gamma;     ///< default: the pattern's own
  std::string pull = "1,0";        ///< X,Y or "along"
  smocking::EmbedOptions options;  ///< gamma and pull are set from the two above
  std::string cloth, cloth_png;    ///< the 3-D fabric (§4.2) as OBJ, and its picture; either asks for it
  smocking::ClothOptions cloth_options;
};

/// Gathers the pattern and writes what was asked; returns the report (also written to `report`).
/// Throws skein::Error on bad input.
nlohmann::json smock(SmockArgs args);

/// `skein smock`: the exit status (0, or 1 when the threads stalled before γ or hit the iteration cap).
int run_smock(const SmockArgs& args);

}  // namespace skein::cli
