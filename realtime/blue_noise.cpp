#include "realtime/blue_noise.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace twinrender::realtime {

namespace {

// The pattern's state: which pixels are set, and each pixel's energy, the sum over the set
// pixels of a Gaussian of their toroidal distance (sigma 1.5, Ulichney's choice).
class Pattern {
  public:
    explicit Pattern(int side) : mSide(side), mSet(std::size_t(side) * side, 0) {
        const std::size_t n = mSet.size();
        mEnergy.assign(n, 0.0);
        mKernel.resize(n);
        for (int dy = 0; dy < side; ++dy)
            for (int dx = 0; dx < side; ++dx) {
                const int wx = std::min(dx, side - dx), wy = std::min(dy, side - dy);
                mKernel[std::size_t(dy) * side + dx] =
                    std::exp(-double(wx * wx + wy * wy) / (2.0 * 1.5 * 1.5));
            }
    }

    std::size_t size() const { return mSet.size(); }
    bool set(std::size_t p) const { return mSet[p] != 0; }

    void toggle(std::size_t p) {
        const double sign = mSet[p] ? -1.0 : 1.0;
        mSet[p] = mSet[p] ? 0 : 1;
        const int px = int(p % mSide), py = int(p / mSide);
        for (int y = 0; y < mSide; ++y) {
            const int dy = (y - py + mSide) % mSide;
            for (int x = 0; x < mSide; ++x) {
                const int dx = (x - px + mSide) % mSide;
                mEnergy[std::size_t(y) * mSide + x] += sign * mKernel[std::size_t(dy) * mSide + dx];
            }
        }
    }

    // The set pixel of the largest energy (the tightest cluster), or the unset pixel of the
    // smallest (the largest void); the first in row order on ties.
    std::size_t tightestCluster() const { return extreme(true); }
    std::size_t largestVoid() const { return extreme(false); }

  private:
    std::size_t extreme(bool ofSet) const {
        std::size_t best = size();
        for (std::size_t p = 0; p < size(); ++p) {
            if (set(p) != ofSet) continue;
            if (best == size() || (ofSet ? mEnergy[p] > mEnergy[best] : mEnergy[p] < mEnergy[best]))
                best = p;
        }
        return best;
    }

    int mSide;
    std::vector<std::uint8_t> mSet;
    std::vector<double> mEnergy;
    std::vector<double> mKernel;  // by toroidal offset
};

}  // namespace

std::vector<float> blueNoise(int side) {
    if (side < 4) throw std::invalid_argument("blueNoise: side must be at least 4");
    Pattern pattern(side);
    const std::size_t n = pattern.size();
    // An initial binary pattern of a tenth of the pixels, from a fixed generator.
    std::uint32_t state = 0x9e3779b9u;
    std::size_t ones = 0;
    while (ones < n / 10) {
        state = state * 1664525u + 1013904223u;
        const std::size_t p = (state >> 8) % n;
        if (pattern.set(p)) continue;
        pattern.toggle(p);
        ++ones;
    }
    // Made uniform: the tightest cluster moved into the largest void until it would land where
    // it came from.
    for (std::size_t guard = 0; guard < 4 * n; ++guard) {
        const std::size_t cluster = pattern.tightestCluster();
        pattern.toggle(cluster);
        const std::size_t hole = pattern.largestVoid();
        if (hole == cluster) {
            pattern.toggle(cluster);
            break;
        }
        pattern.toggle(hole);
    }
    std::vector<std::size_t> rank(n, 0);
    // Phase 1: the prototype's pixels ranked down from ones - 1, tightest cluster first out.
    Pattern first = pattern;
    for (std::size_t r = ones; r-- > 0;) {
        const std::size_t p = first.tightestCluster();
        first.toggle(p);
        rank[p] = r;
    }
    // Phases 2 and 3: the rest ranked up from ones, each into the largest void (past half the
    // pixels, the largest void of the set is the tightest cluster of the unset: the same).
    for (std::size_t r = ones; r < n; ++r) {
        const std::size_t p = pattern.largestVoid();
        pattern.toggle(p);
        rank[p] = r;
    }
    std::vector<float> out(n);
    for (std::size_t p = 0; p < n; ++p) out[p] = float((double(rank[p]) + 0.5) / double(n));
    return out;
}

}  // namespace twinrender::realtime
