#pragma once
// The OpenGL view of the studio (paper A's "surfel model with hardware support"): the shell's
// surfels (core's extractSurfels: one oriented disc per boundary voxel) drawn as point sprites
// on the GPU, with the camera and the light of the CPU panes; the mouse and keys move that
// camera as in the CPU panes (ViewInput.h). Runs on any OpenGL 3.3 core implementation,
// Mesa's llvmpipe under Xvfb included.
#include "ViewInput.h"

#include "octrace/render/Camera.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/render/Surfels.h"

#include <QElapsedTimer>
#include <QOpenGLBuffer>
#include <QOpenGLFunctions_3_3_Core>
#include <QOpenGLShaderProgram>
#include <QOpenGLVertexArrayObject>
#include <QOpenGLWidget>

#include <memory>
#include <vector>

class QLabel;

namespace octrace::studio {

class SurfelView : public QOpenGLWidget, protected QOpenGLFunctions_3_3_Core {
    Q_OBJECT
public:
    explicit SurfelView(QWidget* parent = nullptr);
    ~SurfelView() override;
    /// The surfels to draw (uploaded at the next paint).
    void setSurfels(std::shared_ptr<const std::vector<Surfel>> surfels);
    /// The camera, and from the settings the light, ambient, diffuse and background.
    void setView(const Camera& camera, const RenderSettings& settings);
    /// Text drawn over the view (statistics), under the view's own line.
    void setOverlay(const QString& text);
    /// Milliseconds of the last frame (glFinish included), the number of surfels drawn.
    double lastFrameMs() const { return lastMs_; }
    std::size_t surfelCount() const { return surfels_ ? surfels_->size() : 0; }
    /// The GL_RENDERER string once initialised (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
    QString rendererName() const { return glRenderer_; }
    /// The camera moves asked for in this view.
    ViewInput* input() const { return input_; }

signals:
    void frameDrawn(double ms);

protected:
    void initializeGL() override;
    void paintGL() override;

private:
    std::shared_ptr<const std::vector<Surfel>> surfels_;
    bool uploaded_ = false;
    Camera camera_;
    RenderSettings settings_;
    QOpenGLShaderProgram program_;
    QOpenGLBuffer buffer_{QOpenGLBuffer::VertexBuffer};
    QOpenGLVertexArrayObject vao_;
    QString glRenderer_, overlay_;
    QLabel* label_ = nullptr;
    ViewInput* input_;
    double lastMs_ = 0.0;
    bool ready_ = false;
};

}  // namespace octrace::studio
