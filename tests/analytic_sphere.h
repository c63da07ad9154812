// What the external renderer's tests share: one particle's scenes, still and a short sequence,
// and the analytic renderer of its exact sphere (tests/adapters/analytic_sphere.py).
#pragma once

#include <string>

namespace twinrender::test {

inline const std::string SPHERE =
    std::string(TWINRENDER_SOURCE_DIR) + "/tests/scenes/one_sphere.toml";
inline const std::string SPHERE_ORBIT =
    std::string(TWINRENDER_SOURCE_DIR) + "/tests/scenes/one_sphere_orbit.toml";
inline const std::string ADAPTER =
    "/usr/bin/python3 " + std::string(TWINRENDER_SOURCE_DIR) + "/tests/adapters/analytic_sphere.py";

}  // namespace twinrender::test
