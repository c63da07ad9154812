// A file body's path that names a sequence of particle files, one per frame: a printf pattern
// (`out_%04d.ssf`, `%d`) or a glob (`splash_*.ply`, `?` for one character) in the file name
// (the folders are plain). Frames are ordered by number, numerically: the number a printf
// pattern prints, or for a glob the last run of digits in the text its wildcards match
// (splash_9.ply before splash_10.ply).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace twinrender::core {

struct FrameFile {
    std::int64_t number = 0;
    std::filesystem::path path;
};

class FramePattern {
  public:
    // The pattern of `path`, or nullopt when its file name has neither a printf conversion
    // (%d, %0Nd; %% is a literal %) nor a glob wildcard. Throws InputError naming `where` for
    // a malformed pattern (another conversion, two of them, a printf conversion with a glob).
    static std::optional<FramePattern> parse(const std::filesystem::path& path,
                                             const std::string& where);

    // Every existing file that matches, by ascending number. Throws InputError naming `where`
    // when the folder cannot be listed, when two files have the same number (splash_1.ply and
    // splash_01.ply) or when a glob's match holds no digits.
    std::vector<FrameFile> list() const;

    // The file of frame `number`: a printf pattern prints it; a glob looks it up in `listed`
    // (list()'s result) and gives an empty path when no file has that number.
    std::filesystem::path file(std::int64_t number, const std::vector<FrameFile>& listed) const;

    const std::filesystem::path& path() const { return mPath; }  // as given, absolute
    bool isGlob() const { return mGlob; }

  private:
    std::filesystem::path mPath;
    std::string mWhere;
    bool mGlob = false;
    // printf: the name is mPrefix + the number (at least mWidth digits, zero-padded when
    // mZeroPad) + mSuffix.
    std::string mPrefix, mSuffix;
    int mWidth = 0;
    bool mZeroPad = false;
};

}  // namespace twinrender::core
