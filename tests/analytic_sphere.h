// What the external renderer's tests share: one particle's scenes, still and a short sequence,
// and the analytic renderer of its exact sphere (tests/adapters/analytic_sphere.py).
#pragma once

#include <string>

#include "tests/scratch_dir.h"

namespace twinrender::test {

inline const std::string SPHERE =
    ::twinrender::testing::sourceDir().string() + "/tests/scenes/one_sphere.toml";
inline const std::string SPHERE_ORBIT =
    ::twinrender::testing::sourceDir().string() + "/tests/scenes/one_sphere_orbit.toml";
inline const std::string ADAPTER = "/usr/bin/python3 " +
                                   ::twinrender::testing::sourceDir().string() +
                                   "/tests/adapters/analytic_sphere.py";

}  // namespace twinrender::test
