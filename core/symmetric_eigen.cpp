#include "core/symmetric_eigen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <utility>

namespace twinrender::core {

namespace {

// Sweeps before giving up: quadratic convergence leaves a 3 x 3 matrix diagonal to rounding
// within 5-6 sweeps; the cap only guards against NaN input.
constexpr int MAX_SWEEPS = 32;

}  // namespace

SymmetricEigen symmetricEigen(const glm::dmat3& m) {
    // a[row][col], symmetric; v accumulates the rotations (columns = eigenvectors).
    std::array<std::array<double, 3>, 3> a{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) a[r][c] = r <= c ? m[c][r] : m[r][c];
    std::array<std::array<double, 3>, 3> v{{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
    for (int sweep = 0; sweep < MAX_SWEEPS; ++sweep) {
        const double off = std::abs(a[0][1]) + std::abs(a[0][2]) + std::abs(a[1][2]);
        const double scale = std::abs(a[0][0]) + std::abs(a[1][1]) + std::abs(a[2][2]);
        if (!(off > 1e-300) || off <= 1e-17 * scale) break;
        for (const auto& [p, q] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
            if (a[p][q] == 0.0) continue;
            // The rotation in the (p, q) plane that zeroes a[p][q] (the smaller angle).
            const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            const double t =
                (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
            const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
            for (int k = 0; k < 3; ++k) {  // A <- A J (columns p, q)
                const double akp = a[k][p], akq = a[k][q];
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for (int k = 0; k < 3; ++k) {  // A <- J^T A (rows p, q)
                const double apk = a[p][k], aqk = a[q][k];
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            a[p][q] = a[q][p] = 0.0;
            for (int k = 0; k < 3; ++k) {  // V <- V J
                const double vkp = v[k][p], vkq = v[k][q];
                v[k][p] = c * vkp - s * vkq;
                v[k][q] = s * vkp + c * vkq;
            }
        }
    }
    std::array<int, 3> order{0, 1, 2};
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] > a[j][j]; });
    SymmetricEigen out;
    for (int k = 0; k < 3; ++k) {
        out.values[k] = a[order[k]][order[k]];
        for (int r = 0; r < 3; ++r) out.vectors[k][r] = v[r][order[k]];
    }
    // A rotation (det +1), so that the eigenvectors form a right-handed frame.
    if (glm::dot(glm::cross(out.vectors[0], out.vectors[1]), out.vectors[2]) < 0.0)
        out.vectors[2] = -out.vectors[2];
    return out;
}

}  // namespace twinrender::core
