#include "viewport.hpp"

#include <algorithm>
#include <cmath>

#include <QElapsedTimer>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QWheelEvent>

namespace skein::gui {
namespace {

const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
uniform mat4 mvp;
uniform mat4 view;
out vec3 v_normal;
out vec3 v_color;
void main() {
  gl_Position = mvp * vec4(position, 1.0);
  v_normal = mat3(view) * normal;
  v_color = color;
})";

// A head-light, both sides lit alike; lines are unlit.
const char* kFragmentShader = R"(#version 330 core
in vec3 v_normal;
in vec3 v_color;
uniform bool lit;
out vec4 fragment;
void main() {
  float shade = 1.0;
  if (lit) shade = 0.3 + 0.7 * abs(normalize(v_normal).z);
  fragment = vec4(v_color * shade, 1.0);
})";

QVector3D qt(const Eigen::Vector3d& v) { return QVector3D(float(v.x()), float(v.y()), float(v.z())); }

}  // namespace

Viewport::Viewport(QWidget* parent) : QOpenGLWidget(parent) {
  setMinimumSize(320, 240);
  setFocusPolicy(Qt::StrongFocus);
}

Viewport::~Viewport() {
  if (!context()) return;
  makeCurrent();
  m_triangle_vbo.destroy();
  m_line_vbo.destroy();
  m_triangle_vao.destroy();
  m_line_vao.destroy();
  doneCurrent();
}

void Viewport::show_geometry(Geometry geometry, bool fit_camera) {
  m_geometry = std::move(geometry);
  m_dirty = true;
  if (fit_camera) fit();
  update();
}

void Viewport::fit() {
  if (m_geometry.bounds.isEmpty()) return;
  m_target = m_geometry.bounds.center();
  m_radius = std::max(0.5 * m_geometry.bounds.diagonal().norm(), 1e-6);
  m_distance = 3.6 * m_radius;  // the whole bounding sphere inside the 35° field of view
  update();
}

void Viewport::fail(const QString& reason) {
  m_gl_error = reason;
  emit gl_failed(reason);
}

void Viewport::initializeGL() {
  const auto* ctx = context();
  if (!ctx || !ctx->isValid()) return fail(tr("no OpenGL context could be created"));
  const auto format = ctx->format();
  if (format.majorVersion() * 10 + format.minorVersion() < 33)
    return fail(tr("OpenGL 3.3 is needed, this display gives %1.%2").arg(format.majorVersion()).arg(format.minorVersion()));
  initializeOpenGLFunctions();
  if (!m_program.addShaderFromSourceCode(QOpenGLShader::Vertex, kVertexShader) ||
      !m_program.addShaderFromSourceCode(QOpenGLShader::Fragment, kFragmentShader) || !m_program.link())
    return fail(tr("the shaders did not build: %1").arg(m_program.log()));
  m_triangle_vao.create();
  m_line_vao.create();
  m_triangle_vbo.create();
  m_line_vbo.create();
  for (auto [vao, vbo] : {std::pair{&m_triangle_vao, &m_triangle_vbo}, std::pair{&m_line_vao, &m_line_vbo}}) {
    QOpenGLVertexArrayObject::Binder bind(vao);
    vbo->bind();
    for (int attribute = 0; attribute < 3; ++attribute) {
      glEnableVertexAttribArray(attribute);
      glVertexAttribPointer(attribute, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(attribute * 3 * sizeof(float)));
    }
    vbo->release();
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  m_dirty = true;
}

void Viewport::upload() {
  const auto fill = [](QOpenGLBuffer& vbo, const std::vector<Vertex>& vertices) {
    vbo.bind();
    vbo.allocate(vertices.data(), static_cast<int>(vertices.size() * sizeof(Vertex)));
    vbo.release();
  };
  fill(m_triangle_vbo, m_geometry.triangles);
  fill(m_line_vbo, m_geometry.lines);
  m_triangle_count = static_cast<int>(m_geometry.triangles.size());
  m_line_count = static_cast<int>(m_geometry.lines.size());
  m_dirty = false;
}

void Viewport::resizeGL(int, int) {}

QMatrix4x4 Viewport::view_matrix() const {
  const Eigen::Vector3d eye =
      m_target + m_distance * Eigen::Vector3d(std::cos(m_pitch) * std::sin(m_yaw), std::sin(m_pitch), std::cos(m_pitch) * std::cos(m_yaw));
  QMatrix4x4 view;
  view.lookAt(qt(eye), qt(m_target), QVector3D(0, 1, 0));
  return view;
}

QMatrix4x4 Viewport::projection_matrix() const {
  QMatrix4x4 projection;
  const float aspect = height() > 0 ? float(width()) / float(height()) : 1.0f;
  projection.perspective(35.0f, aspect, float(std::max(m_distance - 2 * m_radius, 1e-3 * m_distance)), float(m_distance + 2 * m_radius));
  return projection;
}

void Viewport::paintGL() {
  QElapsedTimer clock;
  clock.start();
  glClearColor(0.93f, 0.94f, 0.96f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (!m_gl_error.isEmpty()) return;
  if (m_dirty) upload();
  const QMatrix4x4 view = view_matrix();
  m_program.bind();
  m_program.setUniformValue("mvp", projection_matrix() * view);
  m_program.setUniformValue("view", view);
  // Faces pushed back a little so that their edges draw on top of them.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  m_program.setUniformValue("lit", true);
  {
    QOpenGLVertexArrayObject::Binder bind(&m_triangle_vao);
    glDrawArrays(GL_TRIANGLES, 0, m_triangle_count);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  m_program.setUniformValue("lit", false);
  {
    QOpenGLVertexArrayObject::Binder bind(&m_line_vao);
    glDrawArrays(GL_LINES, 0, m_line_count);
  }
  m_program.release();
  glFinish();
  m_paint_ms = clock.elapsed();
}

QPoint Viewport::to_screen(const Eigen::Vector3d& point) const {
  const QVector3D ndc = (projection_matrix() * view_matrix()).map(qt(point));
  return QPoint(int(std::lround((ndc.x() + 1) * 0.5 * width())), int(std::lround((1 - ndc.y()) * 0.5 * height())));
}

std::optional<Hit> Viewport::hit_at(const QPoint& pixel) const {
  const QMatrix4x4 inverse = (projection_matrix() * view_matrix()).inverted();
  const float x = 2.0f * (float(pixel.x()) + 0.5f) / float(width()) - 1.0f, y = 1.0f - 2.0f * (float(pixel.y()) + 0.5f) / float(height());
  const QVector3D near = inverse.map(QVector3D(x, y, -1)), far = inverse.map(QVector3D(x, y, 1));
  const Eigen::Vector3d origin(near.x(), near.y(), near.z()), end(far.x(), far.y(), far.z());
  return pick(m_geometry, origin, (end - origin).normalized());
}

void Viewport::mousePressEvent(QMouseEvent* event) {
  m_last = event->position().toPoint();
  const bool shift = event->modifiers() & Qt::ShiftModifier;
  if (event->button() == Qt::MiddleButton || (event->button() == Qt::RightButton && shift)) m_drag = Drag::Pan;
  else if (event->button() == Qt::RightButton || (event->button() == Qt::LeftButton && m_left_orbits)) m_drag = Drag::Orbit;
  else if (event->button() == Qt::LeftButton) {
    m_drag = Drag::Tool;
    if (const auto hit = hit_at(m_last)) emit pressed(*hit, event->modifiers());
  }
}

void Viewport::mouseMoveEvent(QMouseEvent* event) {
  const QPoint now = event->position().toPoint();
  const QPoint d = now - m_last;
  m_last = now;
  switch (m_drag) {
    case Drag::Orbit:
      m_yaw -= 0.01 * d.x();
      m_pitch = std::clamp(m_pitch + 0.01 * d.y(), -1.5, 1.5);
      update();
      break;
    case Drag::Pan: {
      const QMatrix4x4 view = view_matrix();
      const Eigen::Vector3d right(view(0, 0), view(0, 1), view(0, 2)), up(view(1, 0), view(1, 1), view(1, 2));
      const double per_pixel = 2 * m_distance * std::tan(0.5 * 35.0 * M_PI / 180) / std::max(height(), 1);
      m_target += per_pixel * (-d.x() * right + d.y() * up);
      update();
      break;
    }
    case Drag::Tool:
      if (const auto hit = hit_at(now)) emit dragged(*hit, event->modifiers());
      break;
    case Drag::None:
      break;
  }
}

void Viewport::mouseReleaseEvent(QMouseEvent*) {
  if (m_drag == Drag::Tool) emit released();
  m_drag = Drag::None;
}

void Viewport::wheelEvent(QWheelEvent* event) {
  m_distance *= std::pow(0.999, event->angleDelta().y());
  m_distance = std::clamp(m_distance, 0.05 * m_radius, 50 * m_radius);
  update();
}

}  // namespace skein::gui
