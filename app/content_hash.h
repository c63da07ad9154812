// A content hash for cache keys (the reference cache's, the per-set self-check's).
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>

#include "core/error.h"

namespace twinrender::app {

// FNV-1a, 64 bits: a cache key, not a security boundary.
class Hash {
  public:
    void add(std::string_view bytes) {
        for (unsigned char c : bytes) {
            mState ^= c;
            mState *= 0x100000001b3ULL;
        }
        // A separator, so that ("ab", "c") and ("a", "bc") differ.
        mState ^= 0xff;
        mState *= 0x100000001b3ULL;
    }
    void addFile(const std::filesystem::path& file) {
        std::ifstream in(file, std::ios::binary);
        if (!in) throw core::InputError(fmt::format("{}: cannot be read", file.string()));
        add(file.string());
        add(std::string(std::istreambuf_iterator<char>(in), {}));
    }
    std::string hex() const { return fmt::format("{:016x}", mState); }

  private:
    std::uint64_t mState = 0xcbf29ce484222325ULL;
};

}  // namespace twinrender::app
