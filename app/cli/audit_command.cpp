// skein audit: what changed between two states of one yarn: crossings and linking numbers
#include "subcommand.hpp"

#include <algorithm>
#include <iostream>
#include <memory>
#include <set>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "cuda/device.hpp"
#include "relax/yarn_audit.hpp"
#include "workflow/yarn_io.hpp"

namespace skein::cli {
namespace {

struct AuditCommand final : Subcommand {
  CLI::App* audit = nullptr;
  std::string audit_before, audit_after;
  std::string audit_ids;
  double audit_deviation = 0.1;

  void declare(CLI::App& app) override {
    audit = app.add_subcommand("audit", "what changed between two states of one yarn: crossings and linking numbers");
    audit->add_option("BEFORE", audit_before, "yarn before (.bcc)")->required();
    audit->add_option("AFTER", audit_after, "yarn after (.bcc), the same curves and point counts")->required();
    audit->add_option("--ids", audit_ids, "the stitch ids side file of BEFORE's yarn (skein yarn/relax-yarn/pattern --ids): name each crossing's stitches "
                                          "(face, row, type)");
    audit->add_option("--deviation", audit_deviation, "the linking numbers' polylines stay this close to the curves, × r (refined further where curves come close); "
                                                     "the crossing test is exact and has no deviation")
        ->capture_default_str()->check(in_range(1e-4, 1.0));
  }

  bool chosen() const override { return audit->parsed(); }

  int run(const Context&) override {
    const auto before = workflow::read_bcc(audit_before), after = workflow::read_bcc(audit_after);
    if (before.curve_start != after.curve_start || before.closed != after.closed)
      throw Error(audit_after, "", "holds other curves than " + audit_before + " (curve count, point counts or closed flags differ)");
    const auto ids = audit_ids.empty() ? std::vector<workflow::PointId>{} : workflow::read_point_ids(audit_ids, before);
    const auto a = relax::audit_states(before, after, audit_deviation);
    const double r = before.radius;
    std::cout << "curves: " << a.curves << " (" << a.closed_curves << " closed), control points: " << a.points
              << "\nlargest control-point move: " << a.largest_move << " mm (" << a.largest_move / r << " r)\nRMS control-point move: " << a.rms_move
              << " mm (" << a.rms_move / r << " r)\n"
              << "centreline crossings on the straight path between the two states (exact test, Bezier hulls): " << a.crossings.size();
    if (a.unresolved > 0)
      std::cout << " (" << a.unresolved << " of them pairs the test could not settle in " << relax::kMaxAuditPieces
                << " pieces, centrelines nearly touching along a stretch: counted as crossings)";
    std::cout << "\n";
    // A segment's points, and with the ids its stitch: its first point's, else its second's (a point of no face has none).
    const auto stitch_of = [&](int segment) -> const workflow::PointId* {
      for (const int p : a.segment_ends[segment])
        if (ids[p].face >= 0) return &ids[p];
      return nullptr;
    };
    const auto describe = [&](int segment) {
      const workflow::PointId* id = ids.empty() ? nullptr : stitch_of(segment);
      return " (points " + std::to_string(a.segment_ends[segment][0]) + "-" + std::to_string(a.segment_ends[segment][1]) + ")" +
             (id ? " [face " + std::to_string(id->face) + ", row " + std::to_string(id->row) + ", " + id->type + "]" : std::string());
    };
    for (size_t i = 0; i < std::min<size_t>(a.crossings.size(), 20); ++i) {
      const auto& c = a.crossings[i];
      std::cout << "  segments " << c.segment_a << describe(c.segment_a) << " and " << c.segment_b << describe(c.segment_b) << " near (" << c.where.x()
                << ", " << c.where.y() << ", " << c.where.z() << ")\n";
    }
    if (!ids.empty()) {
      std::set<int> faces, rows;
      for (const auto& c : a.crossings)
        for (int segment : {c.segment_a, c.segment_b})
          if (const auto* id = stitch_of(segment)) faces.insert(id->face), rows.insert(id->row);
      std::cout << "stitches in the crossings: " << faces.size() << " (in " << rows.size() << " rows)";
      int shown = 0;
      for (int f : faces) std::cout << (shown++ == 0 ? ": faces " : ", ") << f;
      std::cout << "\n";
    }
    for (size_t i = 0; i < std::min<size_t>(a.linking_changes.size(), 20); ++i) {
      const auto& l = a.linking_changes[i];
      std::cout << "linking number of closed curves " << l.a << " and " << l.b << ": " << l.before << " -> " << l.after << "\n";
    }
    std::cout << "linking numbers changed: " << a.linking_changes.size() << " (of " << a.linked_pairs << " pairs of closed curves that come near)\n";
    return a.unchanged() ? 0 : 1;
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_audit_command() { return std::make_unique<AuditCommand>(); }

}  // namespace skein::cli
