#include "relax_jobs.hpp"

#include <tuple>

#include <spdlog/spdlog.h>

#include "common/error.hpp"
#include "cuda/yarn_relaxer.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/garment_fabric.hpp"
#include "workflow/yarn_shape.hpp"

namespace skein::gui {

QString RelaxJob::error() const {
  std::lock_guard lock(m_mutex);
  return m_error;
}

RelaxJob::Progress RelaxJob::progress() const {
  std::lock_guard lock(m_mutex);
  return m_progress;
}

bool RelaxJob::due() {
  const auto now = std::chrono::steady_clock::now();
  if (now - m_last < std::chrono::milliseconds(200)) return false;
  m_last = now;
  return true;
}

void RelaxJob::fail(const QString& reason) {
  std::lock_guard lock(m_mutex);
  m_error = reason;
  m_progress.stopped_by = tr("failed");
}

MeshRelaxJob::MeshRelaxJob(const mesh::InputMesh& input, mesh::StitchMesh stitch, surface::MeshRelaxOptions options, QObject* parent)
    : RelaxJob(parent), m_control_points(input.points()), m_control_faces(input.faces()), m_options(options), m_stitch(std::move(stitch)) {
  m_options.interrupt = &m_interrupt;
  m_progress.max_steps = m_options.max_steps;
}

MeshRelaxJob::~MeshRelaxJob() {
  interrupt();
  wait();
}

mesh::StitchMesh MeshRelaxJob::stitch() const {
  std::lock_guard lock(m_mutex);
  return m_stitch;
}

RestSize MeshRelaxJob::rest() const {
  std::lock_guard lock(m_mutex);
  return m_rest;
}

void MeshRelaxJob::run() {
  m_interrupt = false;
  try {
    surface::MeshRelaxer relaxer(m_control_points, m_control_faces, m_stitch, m_options);
    {
      std::lock_guard lock(m_mutex);
      m_rest = {relaxer.r_course(), relaxer.r_wale()};
    }
    const auto report = relaxer.run([&](const surface::MeshRelaxStep& s) {
      const bool publish = due();
      {
        std::lock_guard lock(m_mutex);
        m_progress.step = s.step;
        m_progress.energy = s.energy;
        m_progress.measure = s.max_displacement;
        if (publish) m_stitch = relaxer.relaxed();
      }
      if (publish) emit updated();
    });
    std::lock_guard lock(m_mutex);
    m_stitch = relaxer.relaxed();
    m_progress.converged = report.converged;
    m_progress.stopped_by = report.converged ? tr("converged") : m_interrupt ? tr("interrupted") : tr("step cap");
  } catch (const std::exception& e) {
    fail(QString::fromStdString(e.what()));
  }
  emit updated();
}

namespace {

/// The yarn as it relaxes (a weight's at its contact radius) and its take-up (a weight's to Munden's loop length).
std::pair<relax::YarnCurves, double> relaxed_as(relax::YarnCurves yarn, const mesh::StitchMesh& stitch, const mesh::StitchSize& size,
                                               const YarnSettings& settings) {
  if (settings.weight.empty()) return {std::move(yarn), settings.take_up};
  const auto fabric = workflow::garment_fabric(settings.weight, size);
  yarn.radius = fabric.contact_radius;
  const double loop = workflow::garment_loop_length(relax::make_yarn_system(yarn, 1.0, {}, settings.relax.sampling), static_cast<int>(stitch.faces.size()));
  return {std::move(yarn), workflow::take_up_to_munden(loop, fabric.munden_loop_length, "", "yarn weight " + fabric.yarn,
                                                    "choose another yarn weight or stitch size (Stitch > Stitch size from gauge)")};
}

}  // namespace

YarnRelaxJob::YarnRelaxJob(relax::YarnCurves yarn, const mesh::StitchMesh& stitch, const mesh::StitchSize& size, const YarnSettings& settings,
                           relax::Backend backend, QObject* parent)
    : RelaxJob(parent),
      m_drawn_radius(yarn.radius),
      m_weight(settings.weight),
      m_stitch(stitch),
      m_options(settings.relax),
      m_local_options(settings.local),
      m_backend(backend) {
  std::tie(m_yarn, m_take_up) = relaxed_as(std::move(yarn), stitch, size, settings);
  m_system = relax::make_yarn_system(m_yarn, m_take_up, {}, settings.relax.sampling);
  m_targets = workflow::shape_targets(stitch, m_yarn, m_options.shape);
  m_options.interrupt = &m_interrupt;
  m_progress.max_steps = m_options.max_steps;
  m_points = m_system.points;
}

YarnRelaxJob::~YarnRelaxJob() {
  interrupt();
  wait();
}

void YarnRelaxJob::warm_start(const mesh::StitchMesh& previous_stitch, const relax::YarnCurves& previous_relaxed) {
  mesh::EmitOptions emission;
  emission.yarn_radius = m_yarn.radius;
  const auto previous_emitted = mesh::emit_yarn(previous_stitch, mesh::StitchLibrary::bundled(), emission);
  try {
    m_splice = workflow::splice_previous(m_yarn, previous_emitted, previous_relaxed);
    m_points = m_splice->points;
  } catch (const Error& e) {
    spdlog::warn("{}; relaxing the whole yarn from its emission", e.what());  // not that mesh's yarn
  }
}

std::optional<workflow::LocalRelaxReport> YarnRelaxJob::local() const {
  std::lock_guard lock(m_mutex);
  return m_local;
}

std::optional<relax::ActiveSetCounters> YarnRelaxJob::active_set() const {
  std::lock_guard lock(m_mutex);
  return m_active;
}

relax::YarnCurves YarnRelaxJob::yarn() const {
  std::lock_guard lock(m_mutex);
  auto out = relax::with_points(m_yarn, m_points);
  out.radius = m_drawn_radius;
  return out;
}

QString YarnRelaxJob::backend() const {
  std::lock_guard lock(m_mutex);
  return m_backend_name;
}

void YarnRelaxJob::publish(const relax::YarnStepLog& log) {
  const bool shape = due();
  {
    std::lock_guard lock(m_mutex);
    m_progress.step = log.step;
    m_progress.energy = log.energy;
    m_progress.measure = log.residual;
    if (shape) m_points = m_state.points;
  }
  if (shape) emit updated();
}

void YarnRelaxJob::run() {
  m_interrupt = false;
  {
    std::lock_guard lock(m_mutex);
    m_progress.stopped_by.clear();
  }
  try {
    if (m_splice) {
      // After stitch edits: the changed stitches and rings around them, from the previous relaxed yarn.
      workflow::LocalRelaxReport local;
      const auto points = workflow::relax_locally(m_stitch, m_yarn, *m_splice, m_options, m_local_options, m_take_up, {}, local);
      m_splice.reset();
      if (local.stopped_by != relax::StopReason::UnsafeSplice) {
        std::lock_guard lock(m_mutex);
        m_local = local;
        m_points = points;
        m_backend_name = "cpu";
        m_progress.step = local.steps;
        m_progress.converged = local.converged;
        m_progress.stopped_by = QString::fromStdString(relax::to_string(local.stopped_by));
        m_progress.pull_through = local.pull_through_events;
      }
      if (local.stopped_by != relax::StopReason::UnsafeSplice && local.stopped_by != relax::StopReason::Interrupted) {
        emit updated();
        return;
      }
      // Interrupted: a resume goes on with the whole yarn from here. Unsafe: the whole yarn from its emission.
      if (local.stopped_by == relax::StopReason::Interrupted) m_system.points = points;
      if (m_interrupt) {
        emit updated();
        return;
      }
    }
    if (!m_relaxer) {
      m_relaxer = cuda::make_yarn_relaxer(m_backend, m_system, m_targets, m_options);
      m_state = relax::initial_state(m_system, m_options);
    }
    const auto report = m_relaxer->run(m_state, [&](const relax::YarnStepLog& log) { publish(log); });
    std::lock_guard lock(m_mutex);
    m_points = m_state.points;
    m_backend_name = QString::fromStdString(report.backend);
    m_progress.step = report.steps;
    m_progress.converged = report.converged;
    m_progress.stopped_by = QString::fromStdString(relax::to_string(report.stopped_by));
    m_progress.pull_through = report.pull_through_events;
    if (m_options.active_set.enabled) m_active = report.active;
    if (report.first_residual_peak >= 0) m_progress.first_residual_peak = report.first_residual_peak;
  } catch (const std::exception& e) {
    fail(QString::fromStdString(e.what()));
  }
  emit updated();
}

}  // namespace skein::gui
