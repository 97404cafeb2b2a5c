#include "SurfelView.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <QOpenGLContext>
#include <QLabel>
#include <QSurfaceFormat>

#include <algorithm>
#include <cmath>

namespace octrace::studio {
namespace {

// The CPU renderers' shading (Shader::shadeLambert): two-sided Lambert with RenderSettings'
// ambient and diffuse over the surfel's albedo, in linear RGB; sRGB encoded on output.
const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in float radius;
layout(location = 3) in vec4 colour;
uniform mat4 view;
uniform mat4 projection;
uniform float pixelsPerUnit;  // perspective: pixels per world unit at distance 1
uniform vec3 light;           // camera space, unit
uniform float ambient;
uniform float diffuse;
out vec3 shaded;
vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
void main() {
    vec4 p = view * vec4(position, 1.0);
    gl_Position = projection * p;
    vec3 n = normalize(mat3(view) * normal);
    shaded = srgbToLinear(colour.rgb) * (ambient + diffuse * abs(dot(n, light)));
    gl_PointSize = max(1.0, 2.0 * radius * pixelsPerUnit / max(-p.z, 1e-6));
}
)";

const char* kFragmentShader = R"(#version 330 core
in vec3 shaded;
out vec4 fragColour;
vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
void main() {
    vec2 d = gl_PointCoord * 2.0 - 1.0;
    if (dot(d, d) > 1.0) discard;  // a disc, not a square
    fragColour = vec4(linearToSrgb(shaded), 1.0);
}
)";

float srgb(float linear) {
    linear = std::clamp(linear, 0.0f, 1.0f);
    return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

SurfelView::SurfelView(QWidget* parent) : QOpenGLWidget(parent), input_(new ViewInput(this)) {
    setFocusPolicy(Qt::StrongFocus);
    QSurfaceFormat f = format();
    f.setVersion(3, 3);
    f.setProfile(QSurfaceFormat::CoreProfile);
    f.setDepthBufferSize(24);
    setFormat(f);
    setMinimumSize(64, 64);
    label_ = new QLabel(this);
    label_->setObjectName(QStringLiteral("surfelStats"));
    label_->setStyleSheet(QStringLiteral("QLabel { background: rgba(0, 0, 0, 150); color: white; padding: 2px 4px; font-family: monospace; }"));
    label_->move(6, 6);
}

SurfelView::~SurfelView() {
    if (!ready_) return;
    makeCurrent();
    buffer_.destroy();
    vao_.destroy();
    doneCurrent();
}

void SurfelView::setSurfels(std::shared_ptr<const std::vector<Surfel>> surfels) {
    surfels_ = std::move(surfels);
    uploaded_ = false;
    update();
}

void SurfelView::setView(const Camera& camera, const RenderSettings& settings) {
    camera_ = camera;
    settings_ = settings;
    update();
}

void SurfelView::setOverlay(const QString& text) {
    overlay_ = text;
    update();
}

void SurfelView::initializeGL() {
    if (!initializeOpenGLFunctions()) {
        glRenderer_ = tr("no OpenGL 3.3 core context");
        return;
    }
    glRenderer_ = QString::fromLatin1(reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    if (!program_.addShaderFromSourceCode(QOpenGLShader::Vertex, kVertexShader) ||
        !program_.addShaderFromSourceCode(QOpenGLShader::Fragment, kFragmentShader) || !program_.link()) {
        glRenderer_ += tr(" (shaders failed: %1)").arg(program_.log());
        return;
    }
    vao_.create();
    buffer_.create();
    ready_ = true;
}

void SurfelView::paintGL() {
    const qreal dpr = devicePixelRatioF();
    const int w = int(width() * dpr), h = int(height() * dpr);
    glViewport(0, 0, w, h);
    glClearColor(srgb(settings_.background.r), srgb(settings_.background.g), srgb(settings_.background.b), 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!ready_ || !surfels_ || surfels_->empty()) return;
    QElapsedTimer timer;
    timer.start();
    QOpenGLVertexArrayObject::Binder bind(&vao_);
    if (!uploaded_) {
        buffer_.bind();
        buffer_.allocate(surfels_->data(), int(surfels_->size() * sizeof(Surfel)));
        program_.bind();
        const int stride = int(sizeof(Surfel));
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Surfel, position)));
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Surfel, normal)));
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Surfel, radius)));
        glEnableVertexAttribArray(3);
        glVertexAttribPointer(3, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, reinterpret_cast<void*>(offsetof(Surfel, rgba)));
        uploaded_ = true;
    }
    // Near and far planes hug the surfels' bounding sphere, for the depth buffer's precision.
    const glm::dmat4 view = glm::lookAt(camera_.position, camera_.lookAt, camera_.up);
    double lo = 1e300, hi = 0.0;  // distances of the surfels' bounding sphere along the view
    {
        dvec3 bmin(1e300), bmax(-1e300);
        for (const Surfel& s : *surfels_) {
            bmin = glm::min(bmin, dvec3(s.position));
            bmax = glm::max(bmax, dvec3(s.position));
        }
        const dvec3 centre = 0.5 * (bmin + bmax);
        const double radius = 0.5 * glm::length(bmax - bmin) + 2.0 * double((*surfels_)[0].radius);
        const double d = -(view * glm::dvec4(centre, 1.0)).z;
        hi = d + radius;
        lo = std::max(d - radius, hi * 1e-4);
    }
    const double aspect = double(w) / double(std::max(1, h));
    const glm::dmat4 projection = glm::perspective(glm::radians(camera_.fovYDegrees), aspect, lo, hi);
    program_.bind();
    program_.setUniformValue("view", QMatrix4x4(glm::value_ptr(glm::mat4(view))).transposed());
    program_.setUniformValue("projection", QMatrix4x4(glm::value_ptr(glm::mat4(projection))).transposed());
    program_.setUniformValue("pixelsPerUnit", float(h / (2.0 * std::tan(glm::radians(camera_.fovYDegrees) * 0.5))));
    const dvec3 l = glm::length(settings_.lightCamera) > 0.0 ? glm::normalize(settings_.lightCamera) : dvec3(0.4, 0.6, 1.0);
    program_.setUniformValue("light", QVector3D(float(l.x), float(l.y), float(l.z)));
    program_.setUniformValue("ambient", settings_.ambient);
    program_.setUniformValue("diffuse", settings_.diffuse);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glDrawArrays(GL_POINTS, 0, GLsizei(surfels_->size()));
    glFinish();
    lastMs_ = double(timer.nsecsElapsed()) / 1e6;
    // Statistics over the picture, as on the CPU panes (a child label: composited over the GL
    // frame by Qt).
    label_->setText(tr("opengl surfels  %1x%2\n%3 ms/frame\n%4 surfels\n%5")
                        .arg(w)
                        .arg(h)
                        .arg(lastMs_, 0, 'f', 1)
                        .arg(surfels_->size())
                        .arg(glRenderer_) +
                    (overlay_.isEmpty() ? QString() : QStringLiteral("\n") + overlay_));
    label_->adjustSize();
    emit frameDrawn(lastMs_);
}

}  // namespace octrace::studio
