// Images the metric tests build by hand.
#pragma once

#include "core/image.h"

namespace twinrender::compare::testdata {

// An RGB image of width x height whose every pixel is (r, g, b).
inline core::Image constant(int width, int height, float r, float g, float b) {
    core::Image image(width, height, {"R", "G", "B"});
    image.fillChannel(0, r);
    image.fillChannel(1, g);
    image.fillChannel(2, b);
    return image;
}

}  // namespace twinrender::compare::testdata
