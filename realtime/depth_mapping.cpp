#include "realtime/depth_mapping.h"

#include <cmath>

namespace twinrender::realtime {

double logDepth(double z, double near, double far) {
    return std::log2(1.0 + z / near) / std::log2(1.0 + far / near);
}

double logDepthToEye(double d, double near, double far) {
    return near * (std::exp2(d * std::log2(1.0 + far / near)) - 1.0);
}

double standardDepth(double z, double near, double far) {
    return far * (z - near) / (z * (far - near));
}

double standardDepthToEye(double d, double near, double far) {
    return far * near / (far - d * (far - near));
}

double reversedDepth(double z, double near, double far) {
    return near * (far - z) / (z * (far - near));
}

double reversedDepthToEye(double d, double near, double far) {
    return far * near / (near + d * (far - near));
}

double windowDepth(DepthMode mode, double z, double near, double far) {
    switch (mode) {
        case DepthMode::Standard:
            return standardDepth(z, near, far);
        case DepthMode::Log:
            return logDepth(z, near, far);
        case DepthMode::Reversed:
            return reversedDepth(z, near, far);
    }
    return logDepth(z, near, far);
}

double eyeDepth(DepthMode mode, double d, double near, double far) {
    switch (mode) {
        case DepthMode::Standard:
            return standardDepthToEye(d, near, far);
        case DepthMode::Log:
            return logDepthToEye(d, near, far);
        case DepthMode::Reversed:
            return reversedDepthToEye(d, near, far);
    }
    return logDepthToEye(d, near, far);
}

}  // namespace twinrender::realtime
