// libFuzzer harness: .skein projects (docs/FORMATS.md), their yarn settings included.
#include <optional>

#include "fuzz_support.hpp"
#include "stitchmesh/project.hpp"
#include "workflow/yarn_settings.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::optional<skein::mesh::Project> project;
  skein::fuzz::expect_clean([&] { project = skein::mesh::parse_project(skein::fuzz::text(data, size), "fuzz.skein"); });
  if (!project) return 0;
  skein::fuzz::expect_clean([&] { skein::workflow::read_yarn_settings(project->settings, "fuzz.skein"); });
  // What reads writes back to text that reads again (an error here escapes: a bug), and to the same text.
  const std::string text = skein::mesh::project_text(*project);
  if (skein::mesh::project_text(skein::mesh::parse_project(text, "again.skein")) != text) __builtin_trap();
  return 0;
}
