// Upper bounds of phi over intervals of a ray field (ray_field.h): each particle at its
// largest value there, exactly (at the point of the interval closest to it). The root search
// (first_crossing.h) uses them to prove that phi stays below the level, which lets it jump
// ahead to a hint or stop a ray that goes away from the surface.
#pragma once

#include "raymarch/ray_field.h"

namespace twinrender::raymarch {

// An upper bound of phi on [t, tEnd].
double intervalBound(const RayField& field, double t, double tEnd);

// intervalBound over each of the pieces between consecutive points (ascending) at once.
// Tighter than one bound over the whole: each particle's peak counts only in its own piece.
constexpr int BOUND_PIECES = 3;
void piecewiseBound(const RayField& field, const double (&points)[BOUND_PIECES + 1],
                    double (&bounds)[BOUND_PIECES]);

}  // namespace twinrender::raymarch
