#include "core/symmetric_eigen.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <random>

namespace twinrender::core {
namespace {

void expectDecomposes(const glm::dmat3& m, const SymmetricEigen& e, double tolerance) {
    const glm::dmat3 diagonal(glm::dvec3(e.values[0], 0.0, 0.0), glm::dvec3(0.0, e.values[1], 0.0),
                              glm::dvec3(0.0, 0.0, e.values[2]));
    const glm::dmat3 rebuilt = e.vectors * diagonal * glm::transpose(e.vectors);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(rebuilt[c][r], m[c][r], tolerance) << r << c;
    const glm::dmat3 identity = glm::transpose(e.vectors) * e.vectors;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(identity[c][r], r == c ? 1.0 : 0.0, 1e-14);
    EXPECT_NEAR(glm::determinant(e.vectors), 1.0, 1e-14);
    EXPECT_GE(e.values[0], e.values[1]);
    EXPECT_GE(e.values[1], e.values[2]);
}

TEST(SymmetricEigen, RandomMatricesDecompose) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int n = 0; n < 200; ++n) {
        glm::dmat3 m(0.0);
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r <= c; ++r) m[c][r] = m[r][c] = u(rng);
        expectDecomposes(m, symmetricEigen(m), 1e-13);
    }
}

// A covariance flattened along one axis, rotated: its eigenvalues in descending order, the
// smallest one's eigenvector along the flattened axis.
TEST(SymmetricEigen, FindsTheFlatAxisOfARotatedCovariance) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(1.0, 2.0, 2.0));
    const glm::dmat3 m = 4.0 * glm::dmat3(1.0) - 3.0 * glm::outerProduct(n, n);  // 4, 4, 1
    const SymmetricEigen e = symmetricEigen(m);
    EXPECT_NEAR(e.values[0], 4.0, 1e-14);
    EXPECT_NEAR(e.values[1], 4.0, 1e-14);
    EXPECT_NEAR(e.values[2], 1.0, 1e-14);
    EXPECT_NEAR(std::abs(glm::dot(e.vectors[2], n)), 1.0, 1e-14);
    expectDecomposes(m, e, 1e-14);
}

TEST(SymmetricEigen, DiagonalAndZeroMatrices) {
    const SymmetricEigen d = symmetricEigen(glm::dmat3(
        glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 3.0, 0.0), glm::dvec3(0.0, 0.0, 2.0)));
    EXPECT_EQ(d.values, glm::dvec3(3.0, 2.0, 1.0));
    EXPECT_EQ(d.vectors[0], glm::dvec3(0.0, 1.0, 0.0));
    const SymmetricEigen z = symmetricEigen(glm::dmat3(0.0));
    EXPECT_EQ(z.values, glm::dvec3(0.0));
    EXPECT_NEAR(glm::determinant(z.vectors), 1.0, 0.0);
}

}  // namespace
}  // namespace twinrender::core
