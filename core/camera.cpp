#include "core/camera.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace twinrender::core {

Camera::Camera(const CameraSettings& settings) : mSettings(settings) {
    mForward = glm::normalize(settings.target - settings.position);
    mRight = glm::normalize(glm::cross(mForward, settings.up));
    mUp = glm::cross(mRight, mForward);
    mTanHalfFovY = std::tan(glm::radians(settings.fovYDeg) * 0.5);
}

Ray Camera::ray(double px, double py) const {
    // Normalised device coordinates in [-1, 1], y up.
    const double ndcX = 2.0 * px / mSettings.width - 1.0;
    const double ndcY = 1.0 - 2.0 * py / mSettings.height;
    const glm::dvec3 d =
        mForward + mRight * (ndcX * mTanHalfFovY * aspect()) + mUp * (ndcY * mTanHalfFovY);
    return Ray{mSettings.position, glm::normalize(d)};
}

glm::dvec2 Camera::project(const glm::dvec3& p) const {
    const glm::dvec3 v = p - mSettings.position;
    const double z = glm::dot(v, mForward);
    const double ndcX = glm::dot(v, mRight) / (z * mTanHalfFovY * aspect());
    const double ndcY = glm::dot(v, mUp) / (z * mTanHalfFovY);
    return {(ndcX + 1.0) * 0.5 * mSettings.width, (1.0 - ndcY) * 0.5 * mSettings.height};
}

glm::dmat4 Camera::viewMatrix() const {
    glm::dmat4 m(1.0);
    for (int i = 0; i < 3; ++i) {
        m[i][0] = mRight[i];
        m[i][1] = mUp[i];
        m[i][2] = -mForward[i];
    }
    m[3][0] = -glm::dot(mRight, mSettings.position);
    m[3][1] = -glm::dot(mUp, mSettings.position);
    m[3][2] = glm::dot(mForward, mSettings.position);
    return m;
}

}  // namespace twinrender::core
