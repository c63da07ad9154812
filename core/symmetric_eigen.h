// Eigenvalues and eigenvectors of a symmetric 3 x 3 matrix (a covariance, a Hessian) by cyclic
// Jacobi rotations (Golub & Van Loan, "Matrix Computations", 8.5): each rotation zeroes one
// off-diagonal entry, and a few sweeps bring them all below rounding. Accurate for every
// symmetric matrix, including repeated eigenvalues, and deterministic (a fixed sequence of
// rotations).
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace twinrender::core {

struct SymmetricEigen {
    glm::dvec3 values{0.0};   // descending
    glm::dmat3 vectors{1.0};  // column k: the unit eigenvector of values[k]; a rotation
};

// `m` must be symmetric (only its upper triangle is read).
SymmetricEigen symmetricEigen(const glm::dmat3& m);

}  // namespace twinrender::core
