#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>

#include <QString>
#include <QThread>

#include "document.hpp"
#include "relax/yarn_relax.hpp"
#include "surface/mesh_relax.hpp"
#include "workflow/yarn_local.hpp"
#include "yarn_settings.hpp"

namespace skein::gui {

/// A relaxation on its own thread, so that the app stays responsive. The thread publishes its progress and
/// latest shape under a lock, at most five times a second (`updated`); interrupt() ends the run after the step
/// in progress, and for yarn start() goes on from there (pause and resume).
class RelaxJob : public QThread {
  Q_OBJECT
public:
  using QThread::QThread;
  void interrupt() { m_interrupt = true; }
  /// Why the job failed (a skein::Error's text); empty when it did not.
  QString error() const;

  struct Progress {
    long step = 0, max_steps = 0;
    double energy = 0;
    double measure = 0;  ///< mesh: largest move [mm]; yarn: residual |∇E| / |∇E_0|
    bool converged = false;
    QString stopped_by;  ///< empty while running
    long pull_through = -1;
    double first_residual_peak = -1;  ///< yarn: relax::YarnRelaxReport's, from the run that set the stop rule's scale
  };
  Progress progress() const;

signals:
  void updated();

protected:
  /// True when a new shape is due for the live view (every 0.2 s).
  bool due();
  void fail(const QString& reason);

  std::atomic<bool> m_interrupt{false};
  mutable std::mutex m_mutex;  ///< guards what the thread publishes
  Progress m_progress;
  QString m_error;

private:
  std::chrono::steady_clock::time_point m_last{};
};

/// Mesh relaxation (Yuksel 2012 §6.1) of a stitch mesh on its input mesh's limit surface.
class MeshRelaxJob final : public RelaxJob {
  Q_OBJECT
public:
  MeshRelaxJob(const mesh::InputMesh& input, mesh::StitchMesh stitch, surface::MeshRelaxOptions options, QObject* parent = nullptr);
  ~MeshRelaxJob() override;
  mesh::StitchMesh stitch() const;  ///< the latest positions
  RestSize rest() const;

protected:
  void run() override;

private:
  std::vector<Eigen::Vector3d> m_control_points;
  std::vector<std::vector<int>> m_control_faces;
  surface::MeshRelaxOptions m_options;
  mesh::StitchMesh m_stitch;
  RestSize m_rest;
};

/// Yarn relaxation (Yuksel 2012 §6.3, Leaf 2018 §3) with shape preservation from the stitch mesh, on the
/// backend asked for (auto: the GPU when one answers, else the CPU).
class YarnRelaxJob final : public RelaxJob {
  Q_OBJECT
public:
  /// With a yarn weight in the settings, `yarn` is emitted at its contact radius (its `radius` the full one, as drawn):
  /// it relaxes at the contact radius with its rest lengths cut to Munden's loop length for `size` (workflow::garment_fabric).
  YarnRelaxJob(relax::YarnCurves yarn, const mesh::StitchMesh& stitch, const mesh::StitchSize& size, const YarnSettings& settings,
               relax::Backend backend, QObject* parent = nullptr);
  ~YarnRelaxJob() override;
  /// Before the first start: begin from `previous_relaxed`, the relaxed yarn of `previous_stitch`, and relax
  /// only the stitches changed since and the settings' rings around them (workflow::relax_locally, on the CPU). A splice that
  /// would pass yarn through yarn is not used: the whole yarn relaxes then.
  void warm_start(const mesh::StitchMesh& previous_stitch, const relax::YarnCurves& previous_relaxed);
  relax::YarnCurves yarn() const;  ///< the latest points (at the radius the yarn is drawn at)
  double take_up() const { return m_take_up; }  ///< the take-up the yarn relaxes with (a weight's: to Munden's loop length)
  const std::string& weight() const { return m_weight; }  ///< the yarn weight it relaxes as ("": none)
  QString backend() const;
  /// What the local relaxation did, once it ran.
  std::optional<workflow::LocalRelaxReport> local() const;
  /// With the active set: what it did, once the whole yarn ran.
  std::optional<relax::ActiveSetCounters> active_set() const;

protected:
  void run() override;

private:
  void publish(const relax::YarnStepLog& log);

  relax::YarnCurves m_yarn;  ///< at the radius it relaxes at
  double m_drawn_radius;    ///< the radius yarn() gives it
  std::string m_weight;
  mesh::StitchMesh m_stitch;
  std::optional<workflow::Splice> m_splice;          ///< a warm start not yet run
  std::optional<workflow::LocalRelaxReport> m_local;  ///< a warm start run
  std::optional<relax::ActiveSetCounters> m_active;  ///< a whole run with the active set
  relax::YarnSystem m_system;
  relax::ShapeTargets m_targets;
  relax::YarnRelaxOptions m_options;
  double m_take_up;
  workflow::LocalRelaxOptions m_local_options;
  relax::Backend m_backend;
  std::unique_ptr<relax::YarnRelaxer> m_relaxer;  ///< made on the first run, kept for resuming
  relax::YarnState m_state;
  Eigen::Matrix3Xd m_points;  ///< published copy of m_state.points
  QString m_backend_name;
};

}  // namespace skein::gui
