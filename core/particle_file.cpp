// Readers for particle files written by other software: OpenSPH binary output (.ssf), PLY and
// CSV. Each reader fills ParticleFileData; one validation pass then checks what every reader
// must deliver (finite positions, finite h > 0), naming the particle by what the user can find
// in the file: the particle index (.ssf), the vertex index (PLY) or the line (CSV).
#include "core/particle_file.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"

namespace twinrender::core {
namespace fs = std::filesystem;

namespace {

constexpr std::string_view SUPPORTED_EXTENSIONS =
    ".ssf (OpenSPH binary output), .ply (ascii or binary) and .csv";
constexpr std::string_view COLUMNS_HINT = "x, y, z, h (optional: m, rho, u, v, temperature, body)";

// ------------------------------------------------------------------------------------------
// Shared helpers
// ------------------------------------------------------------------------------------------

std::string readWholeFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(
            fmt::format("{}: cannot open the particle file; check the path", path.string()));
    std::string bytes;
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    if (size < 0)
        throw InputError(
            fmt::format("{}: cannot read the particle file; check the path", path.string()));
    bytes.resize(static_cast<std::size_t>(size));
    if (!in.read(bytes.data(), size))
        throw InputError(
            fmt::format("{}: reading the particle file failed after {} of {} bytes; "
                        "check the disk and the file",
                        path.string(), in.gcount(), size));
    return bytes;
}

// Unsigned integer of the same size as T, to assemble T from bytes in a given order.
template <std::size_t N>
struct UnsignedOfSize;
template <>
struct UnsignedOfSize<1> {
    using Type = std::uint8_t;
};
template <>
struct UnsignedOfSize<2> {
    using Type = std::uint16_t;
};
template <>
struct UnsignedOfSize<4> {
    using Type = std::uint32_t;
};
template <>
struct UnsignedOfSize<8> {
    using Type = std::uint64_t;
};

// Decodes a T stored with the given byte order, independent of the host's order.
template <typename T>
T loadBytes(const unsigned char* p, bool bigEndian) {
    using U = typename UnsignedOfSize<sizeof(T)>::Type;
    U u = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        const std::size_t shift = 8 * (bigEndian ? sizeof(T) - 1 - i : i);
        u = static_cast<U>(u | (static_cast<U>(p[i]) << shift));
    }
    return std::bit_cast<T>(u);
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

// Parses the whole of `text` as a number; accepts a leading '+', nan and inf (which the
// validation then rejects with the particle's location, a clearer message than "not a number").
std::optional<double> parseNumber(std::string_view text) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    if (text.empty()) return std::nullopt;
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

// The attributes a PLY or CSV file may give per particle, by column / property name.
enum class Field { X, Y, Z, H, MASS, DENSITY, U, V, TEMPERATURE, BODY, COUNT };
constexpr std::size_t FIELD_COUNT = static_cast<std::size_t>(Field::COUNT);
constexpr std::array<std::string_view, FIELD_COUNT> FIELD_NAMES = {
    "x", "y", "z", "h", "m", "rho", "u", "v", "temperature", "body"};

std::optional<Field> fieldByName(std::string_view name) {
    for (std::size_t f = 0; f < FIELD_COUNT; ++f)
        if (FIELD_NAMES[f] == name) return static_cast<Field>(f);
    return std::nullopt;
}

// Collects per-particle field values of a PLY or CSV file into ParticleFileData.
class FieldSink {
public:
    // `present[f]` says which fields the file has; x, y, z, h and a u/v pair are checked by the
    // caller, which knows how to name the header location.
    explicit FieldSink(const std::array<bool, FIELD_COUNT>& present) : mPresent(present) {}

    bool has(Field f) const { return mPresent[static_cast<std::size_t>(f)]; }

    // Appends one particle. `where` names it for an error ("<path>:12: particle 10").
    void add(const std::array<double, FIELD_COUNT>& v, const std::function<std::string()>& where) {
        auto at = [&](Field f) { return v[static_cast<std::size_t>(f)]; };
        mData.position.emplace_back(at(Field::X), at(Field::Y), at(Field::Z));
        mData.h.push_back(at(Field::H));
        if (has(Field::MASS)) mData.mass.push_back(at(Field::MASS));
        if (has(Field::DENSITY)) mData.density.push_back(at(Field::DENSITY));
        if (has(Field::U)) mData.uv.emplace_back(at(Field::U), at(Field::V));
        if (has(Field::TEMPERATURE)) mData.temperature.push_back(at(Field::TEMPERATURE));
        if (has(Field::BODY)) {
            const double b = at(Field::BODY);
            // 2^62: far beyond any body count, and exactly convertible to int64.
            if (!std::isfinite(b) || b != std::floor(b) || std::abs(b) > 0x1p62)
                throw InputError(fmt::format("{} has body = {}; write the body as an integer index",
                                             where(), b));
            mData.body.push_back(static_cast<std::int64_t>(b));
        }
    }

    ParticleFileData take() { return std::move(mData); }

private:
    std::array<bool, FIELD_COUNT> mPresent;
    ParticleFileData mData;
};

// Checks what every reader must deliver. `where(i)` names particle i as the user finds it in
// the file, e.g. "ball.ssf: particle 17" or "dump.csv:19: particle 17".
void validate(const ParticleFileData& d, const fs::path& path,
              const std::function<std::string(std::size_t)>& where) {
    if (d.size() == 0)
        throw InputError(fmt::format("{}: the file holds no particles; write at least one particle",
                                     path.string()));
    const std::string fix = "fix the file or drop the particle";
    for (std::size_t i = 0; i < d.size(); ++i) {
        const glm::dvec3& p = d.position[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError(fmt::format("{} has a non-finite position ({}, {}, {}); {}", where(i),
                                         p.x, p.y, p.z, fix));
        if (!std::isfinite(d.h[i]) || d.h[i] <= 0.0)
            throw InputError(
                fmt::format("{} has smoothing length h = {}; h must be finite and > 0: {}",
                            where(i), d.h[i], fix));
        // Volume = m / rho feeds the colour field: both must be positive and finite.
        if (!d.mass.empty() && !(std::isfinite(d.mass[i]) && d.mass[i] > 0.0))
            throw InputError(fmt::format("{} has mass m = {}; m must be finite and > 0: {}",
                                         where(i), d.mass[i], fix));
        if (!d.density.empty() && !(std::isfinite(d.density[i]) && d.density[i] > 0.0))
            throw InputError(fmt::format("{} has density rho = {}; rho must be finite and > 0: {}",
                                         where(i), d.density[i], fix));
        if (!d.temperature.empty() && !(std::isfinite(d.temperature[i]) && d.temperature[i] >= 0.0))
            throw InputError(
                fmt::format("{} has temperature = {} K; it must be finite and >= 0: {}", where(i),
                            d.temperature[i], fix));
        if (!d.uv.empty() && !(std::isfinite(d.uv[i].x) && std::isfinite(d.uv[i].y)))
            throw InputError(fmt::format("{} has non-finite texture coordinates ({}, {}); {}",
                                         where(i), d.uv[i].x, d.uv[i].y, fix));
    }
}

// ------------------------------------------------------------------------------------------
// OpenSPH binary output (.ssf)
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
// ------------------------------------------------------------------------------------------

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

ParticleFileData readSsf(const fs::path& path) {
    ParticleFileData data = SsfReader(path).read();
    validate(data, path,
             [&](std::size_t i) { return fmt::format("{}: particle {}", path.string(), i); });
    return data;
}

// ------------------------------------------------------------------------------------------
// PLY (http://paulbourke.net/dataformats/ply/): ascii, binary_little_endian and (as it costs
// nothing more) binary_big_endian. Elements other than "vertex" and unknown properties are
// skipped, list properties included.
// ------------------------------------------------------------------------------------------

enum class PlyType { INT8, UINT8, INT16, UINT16, INT32, UINT32, FLOAT32, FLOAT64 };

std::optional<PlyType> plyTypeByName(std::string_view name) {
    static constexpr std::array<std::pair<std::string_view, PlyType>, 16> TYPES = {{
        {"char", PlyType::INT8},
        {"int8", PlyType::INT8},
        {"uchar", PlyType::UINT8},
        {"uint8", PlyType::UINT8},
        {"short", PlyType::INT16},
        {"int16", PlyType::INT16},
        {"ushort", PlyType::UINT16},
        {"uint16", PlyType::UINT16},
        {"int", PlyType::INT32},
        {"int32", PlyType::INT32},
        {"uint", PlyType::UINT32},
        {"uint32", PlyType::UINT32},
        {"float", PlyType::FLOAT32},
        {"float32", PlyType::FLOAT32},
        {"double", PlyType::FLOAT64},
        {"float64", PlyType::FLOAT64},
    }};
    for (const auto& [n, t] : TYPES)
        if (n == name) return t;
    return std::nullopt;
}

std::size_t plyTypeSize(PlyType t) {
    switch (t) {
        case PlyType::INT8:
        case PlyType::UINT8:
            return 1;
        case PlyType::INT16:
        case PlyType::UINT16:
            return 2;
        case PlyType::INT32:
        case PlyType::UINT32:
        case PlyType::FLOAT32:
            return 4;
        case PlyType::FLOAT64:
            return 8;
    }
    return 0;
}

double plyLoad(PlyType t, const unsigned char* p, bool bigEndian) {
    switch (t) {
        case PlyType::INT8:
            return loadBytes<std::int8_t>(p, bigEndian);
        case PlyType::UINT8:
            return loadBytes<std::uint8_t>(p, bigEndian);
        case PlyType::INT16:
            return loadBytes<std::int16_t>(p, bigEndian);
        case PlyType::UINT16:
            return loadBytes<std::uint16_t>(p, bigEndian);
        case PlyType::INT32:
            return loadBytes<std::int32_t>(p, bigEndian);
        case PlyType::UINT32:
            return loadBytes<std::uint32_t>(p, bigEndian);
        case PlyType::FLOAT32:
            return loadBytes<float>(p, bigEndian);
        case PlyType::FLOAT64:
            return loadBytes<double>(p, bigEndian);
    }
    return 0.0;
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::FLOAT32;  // of the values (of a list's items)
    bool isList = false;
    PlyType countType = PlyType::UINT8;  // of a list's item count
    std::optional<Field> field;          // set for vertex properties we read
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
    int headerLine = 0;
};

enum class PlyFormat { ASCII, BINARY_LITTLE_ENDIAN, BINARY_BIG_ENDIAN };

class PlyReader {
public:
    explicit PlyReader(const fs::path& path) : mPath(path), mBytes(readWholeFile(path)) {}

    ParticleFileData read() {
        if (mBytes.empty()) throw InputError(fmt::format("{}: the file is empty", mPath.string()));
        parseHeader();
        const PlyElement& vertex = findVertex();
        std::array<bool, FIELD_COUNT> present{};
        for (const PlyProperty& p : vertex.properties)
            if (p.field) present[static_cast<std::size_t>(*p.field)] = true;
        mSink.emplace(present);
        if (mFormat == PlyFormat::ASCII)
            readAscii();
        else
            readBinary(mFormat == PlyFormat::BINARY_BIG_ENDIAN);
        ParticleFileData data = mSink->take();
        validate(data, mPath,
                 [&](std::size_t i) { return fmt::format("{}: vertex {}", mPath.string(), i); });
        return data;
    }

private:
    [[noreturn]] void headerError(int line, const std::string& what) const {
        throw InputError(fmt::format("{}: header line {}: {}", mPath.string(), line, what));
    }

    void parseHeader() {
        std::size_t pos = 0;
        int line = 0;
        bool sawFormat = false;
        for (;;) {
            if (pos >= mBytes.size())
                throw InputError(
                    fmt::format("{}: the PLY header has no end_header line; the file "
                                "is truncated or not a PLY file",
                                mPath.string()));
            std::size_t eol = mBytes.find('\n', pos);
            const std::size_t next = eol == std::string::npos ? mBytes.size() : eol + 1;
            if (eol == std::string::npos) eol = mBytes.size();
            std::string_view text(mBytes.data() + pos, eol - pos);
            if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
            pos = next;
            ++line;
            std::vector<std::string_view> words = splitWords(text);
            if (line == 1) {
                if (words.size() != 1 || words[0] != "ply")
                    throw InputError(
                        fmt::format("{}: not a PLY file (the first line is not "
                                    "\"ply\"); give a PLY, .ssf or .csv file",
                                    mPath.string()));
                continue;
            }
            if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
            if (words[0] == "end_header") {
                if (!sawFormat) headerError(line, "end_header before any format line");
                mDataStart = pos;
                mDataLine = line + 1;
                return;
            }
            if (words[0] == "format") {
                if (words.size() != 3) headerError(line, "expected \"format <type> 1.0\"");
                if (words[1] == "ascii")
                    mFormat = PlyFormat::ASCII;
                else if (words[1] == "binary_little_endian")
                    mFormat = PlyFormat::BINARY_LITTLE_ENDIAN;
                else if (words[1] == "binary_big_endian")
                    mFormat = PlyFormat::BINARY_BIG_ENDIAN;
                else
                    headerError(line, fmt::format("unknown format '{}'; use ascii or "
                                                  "binary_little_endian",
                                                  words[1]));
                sawFormat = true;
            } else if (words[0] == "element") {
                std::uint64_t count = 0;
                if (words.size() != 3 || !parseCount(words[2], count))
                    headerError(line, "expected \"element <name> <count>\"");
                mElements.push_back({std::string(words[1]), count, {}, line});
            } else if (words[0] == "property") {
                if (mElements.empty()) headerError(line, "property before any element");
                mElements.back().properties.push_back(parseProperty(words, line));
            } else {
                headerError(line, fmt::format("unknown keyword '{}'; expected format, element, "
                                              "property, comment or end_header",
                                              words[0]));
            }
        }
    }

    PlyProperty parseProperty(const std::vector<std::string_view>& words, int line) const {
        PlyProperty p;
        const bool vertex = mElements.back().name == "vertex";
        if (words.size() == 5 && words[1] == "list") {
            const auto countType = plyTypeByName(words[2]);
            const auto type = plyTypeByName(words[3]);
            if (!countType || !type)
                headerError(line, fmt::format("unknown type in list property '{}'", words[4]));
            if (*countType == PlyType::FLOAT32 || *countType == PlyType::FLOAT64)
                headerError(line, fmt::format("list property '{}' has a floating-point count type",
                                              words[4]));
            p = {std::string(words[4]), *type, true, *countType, std::nullopt};
            if (vertex && fieldByName(p.name))
                headerError(line, fmt::format("vertex property '{}' is a list; it must be a "
                                              "single value",
                                              p.name));
            return p;
        }
        if (words.size() != 3)
            headerError(line,
                        "expected \"property <type> <name>\" or \"property list "
                        "<count type> <type> <name>\"");
        const auto type = plyTypeByName(words[1]);
        if (!type)
            headerError(line, fmt::format("unknown type '{}' of property '{}'; use char, uchar, "
                                          "short, ushort, int, uint, float or double",
                                          words[1], words[2]));
        p.name = std::string(words[2]);
        p.type = *type;
        if (vertex) {
            p.field = fieldByName(p.name);
            if (p.field)
                for (const PlyProperty& other : mElements.back().properties)
                    if (other.name == p.name)
                        headerError(line,
                                    fmt::format("vertex property '{}' appears twice", p.name));
        }
        return p;
    }

    const PlyElement& findVertex() const {
        const PlyElement* vertex = nullptr;
        for (const PlyElement& e : mElements)
            if (e.name == "vertex") {
                if (vertex) headerError(e.headerLine, "a second 'element vertex'");
                vertex = &e;
            }
        if (!vertex)
            throw InputError(
                fmt::format("{}: the PLY header has no 'element vertex'; particles "
                            "are vertices with properties {}",
                            mPath.string(), COLUMNS_HINT));
        std::array<bool, FIELD_COUNT> present{};
        for (const PlyProperty& p : vertex->properties)
            if (p.field) present[static_cast<std::size_t>(*p.field)] = true;
        for (Field f : {Field::X, Field::Y, Field::Z, Field::H})
            if (!present[static_cast<std::size_t>(f)])
                headerError(vertex->headerLine,
                            fmt::format("element vertex has no property '{}'; particles need "
                                        "properties {}",
                                        FIELD_NAMES[static_cast<std::size_t>(f)], COLUMNS_HINT));
        if (present[static_cast<std::size_t>(Field::U)] !=
            present[static_cast<std::size_t>(Field::V)])
            headerError(vertex->headerLine,
                        "element vertex has only one of the texture "
                        "coordinates 'u' and 'v'; give both or neither");
        if (vertex->count == 0)
            throw InputError(
                fmt::format("{}: the file holds no particles (element vertex 0); "
                            "write at least one vertex",
                            mPath.string()));
        return *vertex;
    }

    static std::vector<std::string_view> splitWords(std::string_view text) {
        std::vector<std::string_view> words;
        std::size_t i = 0;
        while (i < text.size()) {
            while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
            const std::size_t start = i;
            while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
            if (i > start) words.push_back(text.substr(start, i - start));
        }
        return words;
    }

    static bool parseCount(std::string_view text, std::uint64_t& count) {
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), count);
        return ec == std::errc() && end == text.data() + text.size();
    }

    // "vertex 12" or "'face' element 3", for messages.
    static std::string itemName(const PlyElement& e, std::uint64_t i) {
        return e.name == "vertex" ? fmt::format("vertex {}", i)
                                  : fmt::format("'{}' element {}", e.name, i);
    }

    // Ascii: whitespace-separated tokens; an item need not sit on one line.
    void readAscii() {
        std::size_t pos = mDataStart;
        int line = mDataLine;
        auto nextToken = [&](std::string_view& token) {
            while (pos < mBytes.size() && std::isspace(static_cast<unsigned char>(mBytes[pos]))) {
                if (mBytes[pos] == '\n') ++line;
                ++pos;
            }
            const std::size_t start = pos;
            while (pos < mBytes.size() && !std::isspace(static_cast<unsigned char>(mBytes[pos])))
                ++pos;
            token = std::string_view(mBytes.data() + start, pos - start);
            return !token.empty();
        };
        for (const PlyElement& e : mElements) {
            for (std::uint64_t i = 0; i < e.count; ++i) {
                std::array<double, FIELD_COUNT> values{};
                for (const PlyProperty& p : e.properties) {
                    std::string_view token;
                    auto need = [&] {
                        if (!nextToken(token))
                            throw InputError(fmt::format(
                                "{}: truncated: expected {} '{}' elements, the data ends in "
                                "{} (line {}); the file is incomplete: write it again",
                                mPath.string(), e.count, e.name, itemName(e, i), line));
                    };
                    need();
                    if (p.isList) {
                        const auto n = parseNumber(token);
                        if (!n || *n < 0 || *n != std::floor(*n))
                            throw InputError(
                                fmt::format("{}: {} (line {}): list property '{}' "
                                            "has count '{}'; expected a non-negative integer",
                                            mPath.string(), itemName(e, i), line, p.name, token));
                        for (double k = 0; k < *n; ++k) need();
                        continue;
                    }
                    if (!p.field) continue;
                    const auto v = parseNumber(token);
                    if (!v)
                        throw InputError(
                            fmt::format("{}: {} (line {}): property '{}': cannot "
                                        "parse '{}' as a number; write a decimal number",
                                        mPath.string(), itemName(e, i), line, p.name, token));
                    values[static_cast<std::size_t>(*p.field)] = *v;
                }
                if (e.name == "vertex")
                    mSink->add(values, [&] {
                        return fmt::format("{}: vertex {} (line {})", mPath.string(), i, line);
                    });
            }
        }
    }

    void readBinary(bool bigEndian) {
        const auto* bytes = reinterpret_cast<const unsigned char*>(mBytes.data());
        std::uint64_t pos = mDataStart;
        const std::uint64_t size = mBytes.size();
        auto require = [&](std::uint64_t n, const PlyElement& e, std::uint64_t i) {
            if (n > size || pos > size - n)
                throw InputError(
                    fmt::format("{}: truncated: expected {} '{}' elements, the data "
                                "ends in {} at byte {}, file has {} bytes; the file "
                                "is incomplete: write it again",
                                mPath.string(), e.count, e.name, itemName(e, i), pos, size));
        };
        for (const PlyElement& e : mElements) {
            const bool isVertex = e.name == "vertex";
            const bool fixedSize = std::none_of(e.properties.begin(), e.properties.end(),
                                                [](const PlyProperty& p) { return p.isList; });
            if (!isVertex && fixedSize) {
                // Whole element at once; per item only to name the truncated one.
                std::uint64_t stride = 0;
                for (const PlyProperty& p : e.properties) stride += plyTypeSize(p.type);
                if (stride > 0 && e.count > (size - pos) / stride) {
                    const std::uint64_t complete = (size - pos) / stride;
                    pos += stride * complete;
                    require(stride, e, complete);
                }
                pos += stride * e.count;
                continue;
            }
            for (std::uint64_t i = 0; i < e.count; ++i) {
                std::array<double, FIELD_COUNT> values{};
                for (const PlyProperty& p : e.properties) {
                    if (p.isList) {
                        require(plyTypeSize(p.countType), e, i);
                        const double n = plyLoad(p.countType, bytes + pos, bigEndian);
                        pos += plyTypeSize(p.countType);
                        if (n < 0)
                            throw InputError(
                                fmt::format("{}: {}: list property '{}' has a "
                                            "negative count {}; the file is corrupt",
                                            mPath.string(), itemName(e, i), p.name, n));
                        const std::uint64_t listBytes =
                            static_cast<std::uint64_t>(n) * plyTypeSize(p.type);
                        require(listBytes, e, i);
                        pos += listBytes;
                        continue;
                    }
                    const std::size_t valueSize = plyTypeSize(p.type);
                    require(valueSize, e, i);
                    if (p.field)
                        values[static_cast<std::size_t>(*p.field)] =
                            plyLoad(p.type, bytes + pos, bigEndian);
                    pos += valueSize;
                }
                if (isVertex)
                    mSink->add(values,
                               [&] { return fmt::format("{}: vertex {}", mPath.string(), i); });
            }
        }
    }

    fs::path mPath;
    std::string mBytes;
    PlyFormat mFormat = PlyFormat::ASCII;
    std::vector<PlyElement> mElements;
    std::size_t mDataStart = 0;  // byte offset of the first element's data
    int mDataLine = 0;           // line of mDataStart (ascii messages)
    std::optional<FieldSink> mSink;
};

// ------------------------------------------------------------------------------------------
// CSV: a header row naming the columns, then one particle per row. Lines whose first
// non-blank character is '#' and blank lines are skipped anywhere. Columns not listed in
// FIELD_NAMES are ignored (velocities and the like are common).
// ------------------------------------------------------------------------------------------

std::vector<std::string_view> splitCommas(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trim(line.substr(start, comma - start)));
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

ParticleFileData readCsv(const fs::path& path) {
    const std::string text = readWholeFile(path);
    if (text.empty()) throw InputError(fmt::format("{}: the file is empty", path.string()));
    std::string_view rest(text);
    if (rest.starts_with("\xEF\xBB\xBF")) rest.remove_prefix(3);  // UTF-8 byte order mark

    std::vector<std::optional<Field>> columns;  // per CSV column: the field it fills
    std::vector<std::string> columnNames;
    int headerLine = 0;
    std::optional<FieldSink> sink;
    std::vector<int> lineOf;  // per particle, for validation messages
    int line = 0;
    while (!rest.empty()) {
        const std::size_t eol = rest.find('\n');
        std::string_view row = rest.substr(0, eol);
        rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
        ++line;
        const std::string_view content = trim(row);
        if (content.empty() || content.front() == '#') continue;
        const std::vector<std::string_view> cells = splitCommas(content);

        if (!sink) {
            headerLine = line;
            std::array<bool, FIELD_COUNT> present{};
            for (std::size_t c = 0; c < cells.size(); ++c) {
                std::string_view name = cells[c];
                if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
                    name = trim(name.substr(1, name.size() - 2));
                if (name.empty())
                    throw InputError(
                        fmt::format("{}:{}: header column {} has no name; name every column",
                                    path.string(), line, c + 1));
                const std::optional<Field> f = fieldByName(name);
                if (f) {
                    if (present[static_cast<std::size_t>(*f)])
                        throw InputError(
                            fmt::format("{}:{}: column '{}' appears twice in the header; keep one",
                                        path.string(), line, name));
                    present[static_cast<std::size_t>(*f)] = true;
                }
                columns.push_back(f);
                columnNames.emplace_back(name);
            }
            for (Field f : {Field::X, Field::Y, Field::Z, Field::H})
                if (!present[static_cast<std::size_t>(f)])
                    throw InputError(
                        fmt::format("{}:{}: the header has no column '{}'; CSV "
                                    "particle files need columns {}",
                                    path.string(), line, FIELD_NAMES[static_cast<std::size_t>(f)],
                                    COLUMNS_HINT));
            if (present[static_cast<std::size_t>(Field::U)] !=
                present[static_cast<std::size_t>(Field::V)])
                throw InputError(
                    fmt::format("{}:{}: the header has only one of the texture "
                                "coordinate columns 'u' and 'v'; give both or neither",
                                path.string(), line));
            sink.emplace(present);
            continue;
        }

        if (cells.size() != columns.size())
            throw InputError(
                fmt::format("{}:{}: expected {} columns (as the header on line {}), "
                            "found {}; give every row one value per column",
                            path.string(), line, columns.size(), headerLine, cells.size()));
        std::array<double, FIELD_COUNT> values{};
        for (std::size_t c = 0; c < cells.size(); ++c) {
            if (!columns[c]) continue;
            const std::optional<double> v = parseNumber(cells[c]);
            if (!v)
                throw InputError(
                    fmt::format("{}:{}: column '{}' (column {}): cannot parse '{}' "
                                "as a number; write a decimal number",
                                path.string(), line, columnNames[c], c + 1, cells[c]));
            values[static_cast<std::size_t>(*columns[c])] = *v;
        }
        const std::size_t index = lineOf.size();
        sink->add(values,
                  [&] { return fmt::format("{}:{}: particle {}", path.string(), line, index); });
        lineOf.push_back(line);
    }
    if (!sink)
        throw InputError(
            fmt::format("{}: the file has no header row (only comments or blank "
                        "lines); start with a header naming the columns {}",
                        path.string(), COLUMNS_HINT));
    ParticleFileData data = sink->take();
    validate(data, path, [&](std::size_t i) {
        return fmt::format("{}:{}: particle {}", path.string(), lineOf[i], i);
    });
    return data;
}

}  // namespace

ParticleFileData readParticleFile(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".ssf" && ext != ".ply" && ext != ".csv")
        throw InputError(fmt::format("{}: unknown particle file extension '{}'; supported are {}",
                                     path.string(), ext, SUPPORTED_EXTENSIONS));
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (!fs::exists(status))
        throw InputError(fmt::format("{}: no such particle file; check the path", path.string()));
    if (!fs::is_regular_file(status))
        throw InputError(
            fmt::format("{}: not a regular file; give a particle file", path.string()));
    if (fs::file_size(path, ec) == 0 && !ec)
        throw InputError(
            fmt::format("{}: the file is empty; give a file with particles", path.string()));
    if (ext == ".ssf") return readSsf(path);
    if (ext == ".ply") return PlyReader(path).read();
    return readCsv(path);
}

}  // namespace twinrender::core
