#include "compare/distance_transform.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

namespace twinrender::compare {

namespace {

constexpr float FAR = std::numeric_limits<float>::infinity();
// Columns handled together in the vertical pass, so it walks memory row by row.
constexpr int COLUMN_BLOCK = 256;

// Felzenszwalb & Huttenlocher's 1-D algorithm (section 2.1): d[q] = min_p (q - p)^2 + f[p].
// Samples with f = +inf are no parabola and are skipped; when all are, d is +inf. v (n ints) and
// z (n + 1 doubles) are scratch: the envelope's parabola vertices and the boundaries between
// them. Values stay integers below 2^24 (squared pixel distances), exact in float.
void transform1d(const float* f, int n, float* d, int* v, double* z) {
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (f[q] == FAR) continue;
        if (k < 0) {
            k = 0;
            v[0] = q;
            z[0] = -std::numeric_limits<double>::infinity();
            z[1] = std::numeric_limits<double>::infinity();
            continue;
        }
        const double fq = static_cast<double>(f[q]) + static_cast<double>(q) * q;
        double s;
        for (;;) {
            const int p = v[k];
            // Where the parabolas from q and from p intersect; z[0] = -inf ends the loop.
            s = (fq - (static_cast<double>(f[p]) + static_cast<double>(p) * p)) / (2.0 * (q - p));
            if (s > z[k]) break;
            --k;
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = std::numeric_limits<double>::infinity();
    }
    if (k < 0) {
        std::fill(d, d + n, FAR);
        return;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < q) ++k;
        const float dq = static_cast<float>(q - v[k]);
        d[q] = dq * dq + f[v[k]];
    }
}

}  // namespace

std::vector<float> squaredDistanceTransform(const Mask& features) {
    const int w = features.width();
    const int h = features.height();
    std::vector<float> g(features.pixelCount(), FAR);
    if (features.pixelCount() == 0) return g;

    // Columns: the vertical distance to the nearest feature in the same column, by a downward
    // and an upward sweep (the 1-D transform of a 0/inf function), squared.
    tbb::parallel_for(tbb::blocked_range<int>(0, (w + COLUMN_BLOCK - 1) / COLUMN_BLOCK),
                      [&](const tbb::blocked_range<int>& blocks) {
                          for (int b = blocks.begin(); b != blocks.end(); ++b) {
                              const int x0 = b * COLUMN_BLOCK;
                              const int x1 = std::min(w, x0 + COLUMN_BLOCK);
                              for (int y = 0; y < h; ++y) {
                                  float* row = &g[static_cast<std::size_t>(y) * w];
                                  const float* above = y > 0 ? row - w : nullptr;
                                  for (int x = x0; x < x1; ++x)
                                      row[x] =
                                          features(x, y) ? 0.0f : (above ? above[x] + 1.0f : FAR);
                              }
                              for (int y = h - 2; y >= 0; --y) {
                                  float* row = &g[static_cast<std::size_t>(y) * w];
                                  const float* below = row + w;
                                  for (int x = x0; x < x1; ++x)
                                      row[x] = std::min(row[x], below[x] + 1.0f);
                              }
                              for (int y = 0; y < h; ++y) {
                                  float* row = &g[static_cast<std::size_t>(y) * w];
                                  for (int x = x0; x < x1; ++x) row[x] = row[x] * row[x];
                              }
                          }
                      });

    // Rows: the 1-D transform of each row of squared vertical distances.
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        std::vector<float> in(static_cast<std::size_t>(w));
        std::vector<int> v(static_cast<std::size_t>(w));
        std::vector<double> z(static_cast<std::size_t>(w) + 1);
        for (int y = rows.begin(); y != rows.end(); ++y) {
            float* row = &g[static_cast<std::size_t>(y) * w];
            std::copy(row, row + w, in.begin());
            transform1d(in.data(), w, row, v.data(), z.data());
        }
    });
    return g;
}

}  // namespace twinrender::compare
