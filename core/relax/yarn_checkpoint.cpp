#include "relax/yarn_checkpoint.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace skein::relax {
namespace {

constexpr char kMagic[8] = {'S', 'K', 'E', 'I', 'N', 'C', 'K', 'P'};
constexpr std::uint32_t kVersion = 1;

/// FNV-1a, 64 bits.
class Hash {
public:
  void add(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) m_value = (m_value ^ bytes[i]) * 0x100000001b3ull;
  }
  template <class T> void add(const T& value) { add(&value, sizeof(T)); }
  std::uint64_t value() const { return m_value; }

private:
  std::uint64_t m_value = 0xcbf29ce484222325ull;
};

/// The state's fields in file order, shared by the writer and the reader so the two cannot drift apart.
template <class State, class F>
void for_each_scalar(State& s, F&& field) {
  field(s.step);
  field(s.time_step);
  field(s.fire_alpha);
  field(s.fire_positive);
  field(s.residual0);
  field(s.residual_prev);
  field(s.guard.steps);
  field(s.guard.rate_limited);
  field(s.guard.pairs_tested);
  field(s.guard.pairs_skipped);
  field(s.guard.sphere_tests);
  field(s.guard.finest_hits);
  field(s.guard.halvings);
  field(s.guard.held_points);
  field(s.rollbacks);
  field(s.contact_rebuilds);
  field(s.pull_through_events);
}

}  // namespace

std::uint64_t checkpoint_fingerprint(const YarnSystem& system, YarnMethod method) {
  Hash h;
  h.add(static_cast<int>(method));
  h.add(system.radius);
  h.add(system.curve_start.data(), system.curve_start.size() * sizeof(int));
  h.add(system.closed.data(), system.closed.size());
  h.add(system.rest_length.data(), system.rest_length.size() * sizeof(double));
  h.add(system.contact_samples.data(), system.contact_samples.size() * sizeof(int));
  return h.value();
}

void write_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint, const YarnState& state) {
  std::string bytes;
  const auto put = [&](const void* data, size_t size) { bytes.append(static_cast<const char*>(data), size); };
  put(kMagic, sizeof kMagic);
  put(&kVersion, sizeof kVersion);
  put(&fingerprint, sizeof fingerprint);
  const std::int64_t points = state.points.cols();
  put(&points, sizeof points);
  for_each_scalar(state, [&](const auto& v) { put(&v, sizeof v); });
  put(state.points.data(), sizeof(double) * 3 * points);
  put(state.velocities.data(), sizeof(double) * 3 * points);
  Hash h;
  h.add(bytes.data(), bytes.size());
  const std::uint64_t sum = h.value();
  put(&sum, sizeof sum);
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); }, true);
}

YarnState read_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint, int num_points) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(file, "", "cannot open the checkpoint");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  size_t at = 0;
  const auto fail = [&](const std::string& rule) -> void { throw Error(file, "byte " + std::to_string(at), rule); };
  const auto get = [&](void* out, size_t size) {
    if (at + size > bytes.size()) fail("the checkpoint ends early (" + std::to_string(bytes.size()) + " bytes): truncated");
    std::memcpy(out, bytes.data() + at, size);
    at += size;
  };
  char magic[8];
  get(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof magic) != 0) {
    at = 0;
    fail("not a skein checkpoint (expected \"SKEINCKP\")");
  }
  std::uint32_t version;
  get(&version, sizeof version);
  if (version != kVersion) fail("checkpoint format " + std::to_string(version) + ", this skein reads " + std::to_string(kVersion));
  if (bytes.size() < at + 8) fail("the checkpoint ends early: truncated");
  {
    Hash h;
    h.add(bytes.data(), bytes.size() - 8);
    std::uint64_t stored;
    std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
    if (stored != h.value()) {
      at = bytes.size() - 8;
      fail("the checksum does not match the contents: the checkpoint is damaged or truncated");
    }
  }
  std::uint64_t stored_fingerprint;
  get(&stored_fingerprint, sizeof stored_fingerprint);
  if (stored_fingerprint != fingerprint)
    fail("the checkpoint belongs to another yarn or method (its fingerprint differs): resume with the input and --method it was made with");
  std::int64_t points;
  get(&points, sizeof points);
  if (points != num_points) fail("the checkpoint holds " + std::to_string(points) + " control points, the yarn has " + std::to_string(num_points));
  YarnState state;
  for_each_scalar(state, [&](auto& v) { get(&v, sizeof v); });
  state.points.resize(3, points);
  state.velocities.resize(3, points);
  get(state.points.data(), sizeof(double) * 3 * points);
  get(state.velocities.data(), sizeof(double) * 3 * points);
  if (at + 8 != bytes.size()) fail("unexpected bytes after the state");
  if (!state.points.allFinite() || !state.velocities.allFinite() || !std::isfinite(state.time_step) || state.step < 0)
    fail("the state holds values that are not finite");
  return state;
}

}  // namespace skein::relax
