// A pinhole camera. Pixel (x, y) covers [x, x+1) x [y, y+1) with y = 0 the top row; the
// pixel centre is (x + 0.5, y + 0.5). Eye depth is the distance along the view axis (the Z
// channel of the AOV image).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/scene.h"

namespace twinrender::core {

struct Ray {
    glm::dvec3 origin;
    glm::dvec3 direction;  // unit
};

class Camera {
  public:
    explicit Camera(const CameraSettings& settings);

    const CameraSettings& settings() const { return mSettings; }
    int width() const { return mSettings.width; }
    int height() const { return mSettings.height; }
    const glm::dvec3& position() const { return mSettings.position; }
    const glm::dvec3& forward() const { return mForward; }  // unit view direction
    const glm::dvec3& right() const { return mRight; }      // unit, image +x
    const glm::dvec3& up() const { return mUp; }            // unit, image -y (rows go down)
    double tanHalfFovY() const { return mTanHalfFovY; }
    double aspect() const { return double(mSettings.width) / mSettings.height; }

    // The primary ray through image position (px, py) in pixels.
    Ray ray(double px, double py) const;
    // Distance from the camera plane along the view axis.
    double eyeDepth(const glm::dvec3& p) const {
        return glm::dot(p - mSettings.position, mForward);
    }
    // Image position in pixels of a world point in front of the camera.
    glm::dvec2 project(const glm::dvec3& p) const;
    // World-to-eye matrix (OpenGL convention: the camera looks down -z).
    glm::dmat4 viewMatrix() const;

  private:
    CameraSettings mSettings;
    glm::dvec3 mForward, mRight, mUp;
    double mTanHalfFovY;
};

}  // namespace twinrender::core
