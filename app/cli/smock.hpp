#pragma once
// skein smock: a smocking pattern gathered by its threads (Zhou 2024 §4.1), written as JSON, OBJ and pictures.
#include <optional>
#include <string>
#include <vector>

#include "smocking/smocking_embed.hpp"

namespace skein::cli {

struct SmockArgs {
  std::string input, output, obj, png, chart_png, report;
  std::optional<double> gamma;     ///< default: the pattern's own
  std::string pull = "1,0";        ///< X,Y or "along"
  smocking::EmbedOptions options;  ///< gamma and pull are set from the two above
};

/// Runs the embedding and writes what was asked; returns the exit status (0, or 1 when the threads stalled
/// before γ or hit the iteration cap). Throws skein::Error on bad input.
int run_smock(SmockArgs args);

}  // namespace skein::cli
