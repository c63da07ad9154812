// OpenSPH binary output (.ssf).
//
// Layout (OpenSPH core/io/Output.cpp, BinaryOutput::dump; Serializer<true>): little-endian,
// every integer (counts, ids, enums) as int64, every floating-point value as double, strings
// zero-terminated, fixed char arrays as is.
//   header, 256 bytes:
//     0 "SPH\0"  4 run time  12 particle count  20 quantity count  28 material count
//     36 time step  44 format version  52 run type char[16]  68 build date char[16]
//     84 wallclock time  92 attractor count  100..255 zero padding
//   quantity table: per quantity (id, order, value type); order 0..2 = number of derivatives
//   per material (a single block when the material count is 0):
//     "MAT\0", material index, parameter count, per parameter (id, settings type, value),
//     per quantity (id, range lower, range upper, minimal value); or "NOMAT\0"
//     first and one-past-last particle index of the material
//     per quantity: the values of the material's particles, then (order >= 1) the first
//     derivatives, then (order 2) the second derivatives
//   attractors (version >= 20210808): point masses, not SPH particles; not read here.
// Vectors are 4 doubles (x, y, z, h): OpenSPH keeps the smoothing length in the position's
// 4th component.
#include "core/ssf_reader.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/particle_file_reading.h"

namespace twinrender::core::particle_io {
namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t SSF_HEADER_SIZE = 256;

// OpenSPH's BinaryIoVersion values (core/io/Output.h). All share the 256-byte header: later
// fields took over bytes that earlier versions left as zero padding.
constexpr std::array<std::int64_t, 5> SSF_VERSIONS = {
    0,         // FIRST: no version field yet (reads as zero padding)
    20180407,  // enum settings stored as (value, type hash)
    20181024,  // enum settings stored as (value, 0), run type in the header
    20210320,  // wallclock time and build date in the header
    20210808,  // attractors after the particle data (LATEST in OpenSPH master)
};

// QuantityId values (OpenSPH core/quantities/QuantityIds.h); OpenSPH never renumbers them so
// that old files stay readable.
constexpr std::int64_t Q_POSITION = 0;
constexpr std::int64_t Q_MASS = 1;
constexpr std::int64_t Q_DENSITY = 3;
constexpr std::int64_t Q_FLAG = 42;
constexpr std::int64_t Q_TEMPERATURE = 46;
constexpr std::int64_t Q_UVW = 1000;

// Names of OpenSPH quantities (QuantityIds.h), for messages.
std::string ssfQuantityName(std::int64_t id) {
    static constexpr std::array<std::pair<std::int64_t, std::string_view>, 32> NAMES = {
        {{0, "position"},
         {1, "mass"},
         {2, "pressure"},
         {3, "density"},
         {4, "energy"},
         {5, "sound speed"},
         {6, "deviatoric stress"},
         {7, "specific entropy"},
         {8, "generalized energy"},
         {9, "generalized pressure"},
         {10, "damage"},
         {11, "eps_min"},
         {12, "m_zero"},
         {13, "explicit growth"},
         {14, "n_flaws"},
         {16, "stress reducing"},
         {17, "distention"},
         {19, "aggregate id"},
         {20, "angular frequency"},
         {21, "angular momentum"},
         {22, "phase angle"},
         {23, "moment of inertia"},
         {24, "local frame"},
         {38, "neighbor count"},
         {39, "surface normal"},
         {40, "initial position"},
         {41, "smoothing length"},
         {42, "flag"},
         {44, "persistent index"},
         {46, "temperature"},
         {47, "vibrational velocity"},
         {1000, "uvw"}}};
    for (const auto& [key, name] : NAMES)
        if (key == id) return std::string(name);
    return fmt::format("quantity id {}", id);
}

// OpenSPH ValueEnum: SCALAR, VECTOR, TENSOR, SYMMETRIC_TENSOR, TRACELESS_TENSOR, INDEX; bytes
// per value (Vector: x, y, z, h; Tensor 3x3; symmetric 6; traceless 5; index an int64).
constexpr std::array<std::uint64_t, 6> SSF_VALUE_SIZES = {8, 32, 72, 48, 40, 8};
constexpr std::array<std::string_view, 6> SSF_VALUE_NAMES = {
    "scalar", "vector", "tensor", "symmetric tensor", "traceless tensor", "index"};
constexpr std::int64_t V_SCALAR = 0;
constexpr std::int64_t V_VECTOR = 1;
constexpr std::int64_t V_INDEX = 5;

// Settings::Value variant order (core/system/Settings.h), stable since the version field
// exists: bool, int, Float, Interval, String, Vector, SymmetricTensor, TracelessTensor,
// EnumWrapper (value + a zero or hash). 0 marks the zero-terminated string.
constexpr std::array<std::uint64_t, 9> SSF_SETTING_SIZES = {8, 8, 8, 16, 0, 32, 48, 40, 16};
constexpr std::size_t SSF_SETTING_STRING = 4;

struct SsfQuantity {
    std::int64_t id = 0;
    std::int64_t order = 0;      // number of stored derivatives, 0..2
    std::int64_t valueType = 0;  // index into SSF_VALUE_SIZES
};

class SsfReader {
  public:
    explicit SsfReader(const fs::path& path) : mPath(path), mIn(path, std::ios::binary) {
        if (!mIn)
            throw InputError(
                fmt::format("{}: cannot open the particle file; check the path", mPath.string()));
        mIn.seekg(0, std::ios::end);
        mSize = static_cast<std::uint64_t>(mIn.tellg());
        mIn.seekg(0, std::ios::beg);
    }

    ParticleFileData read() {
        readHeader();
        readQuantityTable();
        checkParticleCountFits();

        const std::uint64_t n = static_cast<std::uint64_t>(mParticleCount);
        ParticleFileData data;
        data.position.resize(n);
        data.h.resize(n);
        if (wanted(Q_MASS)) data.mass.resize(n);
        if (wanted(Q_DENSITY)) data.density.resize(n);
        if (wanted(Q_TEMPERATURE)) data.temperature.resize(n);
        if (wanted(Q_FLAG)) data.body.resize(n);
        if (wanted(Q_UVW)) data.uv.resize(n);

        std::uint64_t begin = 0;
        const std::int64_t blocks = std::max<std::int64_t>(mMaterialCount, 1);
        for (std::int64_t m = 0; m < blocks; ++m) {
            if (mMaterialCount > 0)
                skipMaterial(m);
            else
                expectTag("NOMAT");
            const std::int64_t from = readInt64("the first particle index of a material");
            const std::int64_t to = readInt64("the end particle index of a material");
            if (from != static_cast<std::int64_t>(begin) || to < from || to > mParticleCount)
                corrupt(
                    fmt::format("material {} covers particles [{}, {}), expected a range "
                                "starting at {} and ending at most at {}",
                                m, from, to, begin, mParticleCount));
            readMaterialQuantities(data, begin, static_cast<std::uint64_t>(to - from));
            begin = static_cast<std::uint64_t>(to);
        }
        if (begin != n)
            corrupt(fmt::format("the material blocks hold {} particles but the header says {}",
                                begin, n));
        return data;
    }

  private:
    [[noreturn]] void corrupt(const std::string& what) const {
        throw InputError(
            fmt::format("{}: not a valid OpenSPH binary output: {}; the file is "
                        "corrupt or not written by OpenSPH's BinaryOutput",
                        mPath.string(), what));
    }

    [[noreturn]] void truncated(const std::string& what) const {
        throw InputError(
            fmt::format("{}: truncated: expected {} at byte {}, file has {} bytes; "
                        "the file is incomplete (interrupted run or copy): write or copy it again",
                        mPath.string(), what, mOffset, mSize));
    }

    // Throws the truncation error unless `bytes` more bytes exist at the current offset.
    void require(std::uint64_t bytes, const std::string& what) const {
        if (bytes > mSize || mOffset > mSize - bytes) truncated(what);
    }

    void readBytes(void* dst, std::uint64_t bytes, const std::string& what) {
        require(bytes, what);
        if (!mIn.read(static_cast<char*>(dst), static_cast<std::streamsize>(bytes)))
            throw InputError(
                fmt::format("{}: reading {} at byte {} failed; check the disk and the file",
                            mPath.string(), what, mOffset));
        mOffset += bytes;
    }

    void skip(std::uint64_t bytes, const std::string& what) {
        require(bytes, what);
        mOffset += bytes;
        mIn.seekg(static_cast<std::streamoff>(mOffset), std::ios::beg);
    }

    std::int64_t readInt64(const std::string& what) {
        unsigned char b[8];
        readBytes(b, 8, what);
        return loadBytes<std::int64_t>(b, false);
    }

    std::string readCString(const std::string& what) {
        std::string s;
        const std::uint64_t start = mOffset;
        for (;;) {
            if (mOffset >= mSize)
                throw InputError(
                    fmt::format("{}: truncated: expected {} (a zero-terminated "
                                "string) at byte {}, file has {} bytes; the file is "
                                "incomplete: write or copy it again",
                                mPath.string(), what, start, mSize));
            char c = 0;
            readBytes(&c, 1, what);
            if (c == '\0') return s;
            s += c;
        }
    }

    void expectTag(std::string_view tag) {
        const std::uint64_t at = mOffset;
        const std::string found = readCString(fmt::format("the block tag \"{}\"", tag));
        if (found != tag)
            corrupt(fmt::format("expected the block tag \"{}\" at byte {}, found \"{}\"", tag, at,
                                found.substr(0, 32)));
    }

    void readHeader() {
        constexpr std::string_view MAGIC{"SPH\0", 4};
        constexpr std::string_view COMPRESSED_MAGIC{"CPRSPH\0", 7};
        unsigned char head[SSF_HEADER_SIZE] = {};
        const std::uint64_t probe = std::min<std::uint64_t>(mSize, SSF_HEADER_SIZE);
        readBytes(head, probe, "the header");
        const std::string_view start(reinterpret_cast<const char*>(head), probe);
        if (start.starts_with(COMPRESSED_MAGIC))
            throw InputError(
                fmt::format("{}: this is OpenSPH's compressed output (\"CPRSPH\"), "
                            "which this reader does not read; save the run with "
                            "OpenSPH's binary output (.ssf) instead",
                            mPath.string()));
        if (!start.starts_with(MAGIC))
            throw InputError(
                fmt::format("{}: not an OpenSPH binary output file (it does not "
                            "start with \"SPH\"); give a file written by OpenSPH's "
                            "BinaryOutput, or use .ply or .csv",
                            mPath.string()));
        if (probe < SSF_HEADER_SIZE) {
            mOffset = 0;
            require(SSF_HEADER_SIZE, "the 256-byte header");
        }
        auto i64 = [&](std::size_t at) { return loadBytes<std::int64_t>(head + at, false); };
        mParticleCount = i64(12);
        mQuantityCount = i64(20);
        mMaterialCount = i64(28);
        mVersion = i64(44);
        if (std::find(SSF_VERSIONS.begin(), SSF_VERSIONS.end(), mVersion) == SSF_VERSIONS.end())
            throw InputError(
                fmt::format("{}: unknown OpenSPH binary format version {} (this "
                            "reader knows {}); convert the file with a matching "
                            "OpenSPH to PLY or CSV, or extend this reader",
                            mPath.string(), mVersion, fmt::join(SSF_VERSIONS, ", ")));
        if (mParticleCount < 0 || mQuantityCount < 0 || mMaterialCount < 0)
            corrupt(
                fmt::format("the header has negative counts (particles {}, quantities {}, "
                            "materials {})",
                            mParticleCount, mQuantityCount, mMaterialCount));
        if (mParticleCount == 0)
            throw InputError(
                fmt::format("{}: the file holds no particles; give a dump of a run with particles",
                            mPath.string()));
    }

    // Called before allocating: a damaged count must not turn into a huge allocation.
    void checkParticleCountFits() const {
        const std::uint64_t n = static_cast<std::uint64_t>(mParticleCount);
        if (n > mSize / SSF_VALUE_SIZES[V_VECTOR])
            throw InputError(
                fmt::format("{}: truncated: the header announces {} particles, "
                            "whose positions alone need {} bytes, file has {} bytes; "
                            "the file is incomplete: write or copy it again",
                            mPath.string(), n, n * SSF_VALUE_SIZES[V_VECTOR], mSize));
    }

    void readQuantityTable() {
        // Each entry is 3 int64; checking the whole table first gives one clear message (and
        // keeps a damaged count from overflowing the product).
        const std::string table = fmt::format("a table of {} quantities", mQuantityCount);
        if (static_cast<std::uint64_t>(mQuantityCount) > mSize / 24) truncated(table);
        require(static_cast<std::uint64_t>(mQuantityCount) * 24, table);
        bool hasPosition = false;
        for (std::int64_t i = 0; i < mQuantityCount; ++i) {
            SsfQuantity q;
            q.id = readInt64("a quantity id");
            q.order = readInt64("a quantity order");
            q.valueType = readInt64("a quantity value type");
            if (q.order < 0 || q.order > 2)
                corrupt(fmt::format("quantity '{}' has {} derivatives (0 to 2 expected)",
                                    ssfQuantityName(q.id), q.order));
            if (q.valueType < 0 || q.valueType >= static_cast<std::int64_t>(SSF_VALUE_SIZES.size()))
                corrupt(fmt::format("quantity '{}' has unknown value type {}",
                                    ssfQuantityName(q.id), q.valueType));
            checkWantedType(q);
            hasPosition = hasPosition || q.id == Q_POSITION;
            mQuantities.push_back(q);
        }
        if (!hasPosition)
            throw InputError(
                fmt::format("{}: the file has no position quantity, so no particle "
                            "positions; give a dump of an SPH or N-body run",
                            mPath.string()));
    }

    // A quantity we extract must have the type OpenSPH gives it, or the bytes mean something
    // else than we would read.
    void checkWantedType(const SsfQuantity& q) const {
        std::vector<std::int64_t> allowed;
        switch (q.id) {
            case Q_POSITION:
            case Q_UVW:
                allowed = {V_VECTOR};
                break;
            case Q_MASS:
            case Q_DENSITY:
            case Q_TEMPERATURE:
                allowed = {V_SCALAR};
                break;
            case Q_FLAG:
                allowed = {V_INDEX, V_SCALAR};
                break;
            default:
                return;
        }
        if (std::find(allowed.begin(), allowed.end(), q.valueType) == allowed.end())
            corrupt(fmt::format("quantity '{}' is stored as {}, expected {}", ssfQuantityName(q.id),
                                SSF_VALUE_NAMES[q.valueType], SSF_VALUE_NAMES[allowed.front()]));
    }

    bool wanted(std::int64_t id) const {
        return std::any_of(mQuantities.begin(), mQuantities.end(),
                           [&](const SsfQuantity& q) { return q.id == id; });
    }

    // Material parameters and per-quantity ranges only steer OpenSPH's solver: skipped.
    void skipMaterial(std::int64_t m) {
        expectTag("MAT");
        const std::int64_t index = readInt64("a material index");
        if (index != m) corrupt(fmt::format("material block {} carries the index {}", m, index));
        const std::int64_t params = readInt64("a material parameter count");
        if (params < 0) corrupt(fmt::format("material {} has {} parameters", m, params));
        for (std::int64_t p = 0; p < params; ++p) {
            const std::int64_t id = readInt64("a material parameter id");
            const std::int64_t type = readInt64("a material parameter type");
            if (type < 0 || type >= static_cast<std::int64_t>(SSF_SETTING_SIZES.size()))
                corrupt(
                    fmt::format("material {} parameter {} has unknown value type {}", m, id, type));
            const std::string what = fmt::format("the value of material {} parameter {}", m, id);
            if (static_cast<std::size_t>(type) == SSF_SETTING_STRING)
                readCString(what);
            else
                skip(SSF_SETTING_SIZES[type], what);
        }
        for (const SsfQuantity& q : mQuantities) {
            const std::int64_t id = readInt64("a quantity id of a material's ranges");
            if (id != q.id)
                corrupt(
                    fmt::format("material {} lists the ranges of quantity '{}' where '{}' "
                                "was expected",
                                m, ssfQuantityName(id), ssfQuantityName(q.id)));
            skip(24, fmt::format("the range of quantity '{}'", ssfQuantityName(q.id)));
        }
    }

    void readMaterialQuantities(ParticleFileData& data, std::uint64_t begin, std::uint64_t count) {
        static constexpr std::array<std::string_view, 3> BUFFER_SUFFIX = {"", " (1st derivative)",
                                                                          " (2nd derivative)"};
        for (const SsfQuantity& q : mQuantities) {
            const std::uint64_t valueSize = SSF_VALUE_SIZES[q.valueType];
            for (std::int64_t k = 0; k <= q.order; ++k) {
                const std::string what = fmt::format("{} values of quantity '{}'{}", count,
                                                     ssfQuantityName(q.id), BUFFER_SUFFIX[k]);
                if (k > 0 || !isExtracted(q.id)) {
                    skip(count * valueSize, what);
                    continue;
                }
                mBuffer.resize(count * valueSize);
                readBytes(mBuffer.data(), mBuffer.size(), what);
                decode(data, q, begin, count);
            }
        }
    }

    static bool isExtracted(std::int64_t id) {
        return id == Q_POSITION || id == Q_MASS || id == Q_DENSITY || id == Q_TEMPERATURE ||
               id == Q_FLAG || id == Q_UVW;
    }

    void decode(ParticleFileData& data, const SsfQuantity& q, std::uint64_t begin,
                std::uint64_t count) const {
        const unsigned char* b = mBuffer.data();
        auto f64 = [&](std::uint64_t i) { return loadBytes<double>(b + 8 * i, false); };
        for (std::uint64_t i = 0; i < count; ++i) {
            const std::uint64_t p = begin + i;
            switch (q.id) {
                case Q_POSITION:
                    data.position[p] = glm::dvec3(f64(4 * i), f64(4 * i + 1), f64(4 * i + 2));
                    data.h[p] = f64(4 * i + 3);
                    break;
                case Q_UVW:
                    data.uv[p] = glm::dvec2(f64(4 * i), f64(4 * i + 1));
                    break;
                case Q_MASS:
                    data.mass[p] = f64(i);
                    break;
                case Q_DENSITY:
                    data.density[p] = f64(i);
                    break;
                case Q_TEMPERATURE:
                    data.temperature[p] = f64(i);
                    break;
                case Q_FLAG:
                    data.body[p] = q.valueType == V_INDEX
                                       ? loadBytes<std::int64_t>(b + 8 * i, false)
                                       : static_cast<std::int64_t>(std::llround(f64(i)));
                    break;
                default:
                    break;
            }
        }
    }

    fs::path mPath;
    std::ifstream mIn;
    std::uint64_t mSize = 0;    // bytes
    std::uint64_t mOffset = 0;  // bytes from the file start, for messages and seeking
    std::int64_t mParticleCount = 0;
    std::int64_t mQuantityCount = 0;
    std::int64_t mMaterialCount = 0;
    std::int64_t mVersion = 0;
    std::vector<SsfQuantity> mQuantities;
    std::vector<unsigned char> mBuffer;  // one quantity buffer of one material
};

}  // namespace

ParticleFileData readSsf(const fs::path& path) {
    ParticleFileData data = SsfReader(path).read();
    validateParticles(data, path, [&](std::size_t i) {
        return fmt::format("{}: particle {}", path.string(), i);
    });
    return data;
}

}  // namespace twinrender::core::particle_io
