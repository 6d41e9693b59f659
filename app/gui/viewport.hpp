#pragma once

#include <optional>

#include <QOpenGLBuffer>
#include <QOpenGLExtraFunctions>
#include <QOpenGLShaderProgram>
#include <QOpenGLVertexArrayObject>
#include <QOpenGLWidget>
#include <QMatrix4x4>

#include "scene_geometry.hpp"

namespace skein::gui {

/// The 3D view: draws a Geometry with OpenGL 3.3 core and turns mouse input into camera moves and picks.
/// Right-drag orbits, middle-drag (or Shift+right-drag) pans, the wheel zooms; the left button belongs to
/// the active tool (pressed/dragged/released), or orbits when `left_orbits` is set.
class Viewport : public QOpenGLWidget, protected QOpenGLExtraFunctions {
  Q_OBJECT
public:
  explicit Viewport(QWidget* parent = nullptr);
  ~Viewport() override;

  /// Shows new geometry; `fit` points the camera at all of it.
  void show_geometry(Geometry geometry, bool fit);
  const Geometry& geometry() const { return m_geometry; }
  void fit();
  void set_left_orbits(bool orbits) { m_left_orbits = orbits; }

  /// The widget pixel a model point is drawn at (tests click through it).
  QPoint to_screen(const Eigen::Vector3d& point) const;
  /// What the model shows at a widget pixel.
  std::optional<Hit> hit_at(const QPoint& pixel) const;
  /// Empty while OpenGL works; else why it does not (no 3.3 context, a shader that failed).
  const QString& gl_error() const { return m_gl_error; }
  /// How long the last frame took to draw [ms] (with a software renderer, far from free).
  qint64 last_paint_ms() const { return m_paint_ms; }

signals:
  void pressed(const skein::gui::Hit& hit, Qt::KeyboardModifiers modifiers);
  void dragged(const skein::gui::Hit& hit, Qt::KeyboardModifiers modifiers);
  void released();
  void gl_failed(const QString& reason);

protected:
  void initializeGL() override;
  void resizeGL(int width, int height) override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

private:
  QMatrix4x4 view_matrix() const;
  QMatrix4x4 projection_matrix() const;
  void fail(const QString& reason);
  void upload();

  Geometry m_geometry;
  bool m_dirty = false;
  QString m_gl_error;
  QOpenGLShaderProgram m_program;
  QOpenGLVertexArrayObject m_triangle_vao, m_line_vao;
  QOpenGLBuffer m_triangle_vbo{QOpenGLBuffer::VertexBuffer}, m_line_vbo{QOpenGLBuffer::VertexBuffer};
  int m_triangle_count = 0, m_line_count = 0;
  qint64 m_paint_ms = 0;

  // Camera: orbit about a target point.
  Eigen::Vector3d m_target = Eigen::Vector3d::Zero();
  double m_distance = 100, m_yaw = 0.35, m_pitch = 0.3, m_radius = 50;
  bool m_left_orbits = true;
  enum class Drag { None, Orbit, Pan, Tool } m_drag = Drag::None;
  QPoint m_last;
};

}  // namespace skein::gui
