#include "core/part_join.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "core/error.h"

namespace twinrender::core {

namespace {

std::string partName(const FramePart& p) {
    return fmt::format("part {}/{}", p.index, p.count);
}

std::string counterNames(const std::map<std::string, double>& counters) {
    std::string names;
    for (const auto& [k, v] : counters) names += (names.empty() ? "" : ", ") + k;
    return names.empty() ? "none" : names;
}

}  // namespace

void PartJoin::check(const Frame& part, const std::string& where) const {
    const Added& first = mParts.begin()->second;
    const PartRecord& r = *part.part;
    const auto refuse = [&](const std::string& what) {
        return InputError(fmt::format("{} ({}) and {} ({}) are not parts of one frame: {}", where,
                                      partName(r.part), first.where, partName(first.record.part),
                                      what));
    };
    if (r.part.count != first.record.part.count)
        throw refuse(
            fmt::format("split into {} and {} parts", r.part.count, first.record.part.count));
    if (const auto it = mParts.find(r.part.index); it != mParts.end())
        throw InputError(fmt::format("{} and {} are both {}; give each part once", it->second.where,
                                     where, partName(r.part)));
    if (r.tileSize != first.record.tileSize)
        throw refuse(fmt::format("tiles of {} and {} pixels", r.tileSize, first.record.tileSize));
    // A part that holds no row has no channels to compare.
    const Image& a = part.image;
    auto names = a.channelNames(), ours = mFrame.image.channelNames();
    std::sort(names.begin(), names.end());
    std::sort(ours.begin(), ours.end());
    if (a.width() != mWidth || r.height != first.record.height ||
        (a.height() > 0 && !ours.empty() && names != ours))
        throw refuse(fmt::format("{}x{} with {} channels against {}x{} with {}", a.width(),
                                 r.height, a.channelCount(), mWidth, first.record.height,
                                 mFrame.image.channelCount()));
    if (part.renderer != mFrame.renderer)
        throw refuse(fmt::format("renderers {} and {}", part.renderer, mFrame.renderer));
    if (part.settings != mFrame.settings) {
        std::string diff;
        if (part.settings.is_object() && mFrame.settings.is_object())
            for (const auto& [k, v] : part.settings.items())
                if (!mFrame.settings.contains(k) || mFrame.settings.at(k) != v)
                    diff += fmt::format("{}{} {} against {}", diff.empty() ? "" : "; ", k, v.dump(),
                                        mFrame.settings.value(k, nlohmann::json()).dump());
        throw refuse("other renderer settings (" + (diff.empty() ? "keys differ" : diff) + ")");
    }
    if (part.particleCount != mFrame.particleCount)
        throw refuse(fmt::format("{} and {} particles", part.particleCount, mFrame.particleCount));
    const bool sameCounters =
        part.counters.size() == mFrame.counters.size() &&
        std::equal(part.counters.begin(), part.counters.end(), mFrame.counters.begin(),
                   [](const auto& x, const auto& y) { return x.first == y.first; });
    if (!sameCounters || r.shared != first.record.shared || r.maxima != first.record.maxima)
        throw refuse(fmt::format("counters {} against {}", counterNames(part.counters),
                                 counterNames(mFrame.counters)));
    for (const std::string& name : r.shared)
        if (part.counters.at(name) != mFrame.counters.at(name))
            throw refuse(fmt::format("{} is {} and {}", name, part.counters.at(name),
                                     mFrame.counters.at(name)));
    for (const auto& [name, mean] : first.record.means)
        if (!r.means.count(name)) throw refuse(fmt::format("the mean {} is in one only", name));
}

void PartJoin::copyRows(const Frame& part) {
    const PartRecord& r = *part.part;
    Image& out = mFrame.image;
    const Image& in = part.image;
    const int channels = out.channelCount();
    std::vector<int> from(static_cast<std::size_t>(channels));
    for (int c = 0; c < channels; ++c) from[c] = in.channelIndex(out.channelNames()[c]);
    const bool sameOrder = in.channelNames() == out.channelNames();
    const std::size_t rowValues = static_cast<std::size_t>(out.width()) * channels;
    for (int row = 0; row < in.height(); ++row) {
        const int y = r.part.frameRow(row, r.tileSize);
        if (sameOrder) {
            std::memcpy(out.pixels().data() + static_cast<std::size_t>(y) * rowValues,
                        in.pixels().data() + static_cast<std::size_t>(row) * rowValues,
                        rowValues * sizeof(float));
            continue;
        }
        for (int x = 0; x < out.width(); ++x)
            for (int c = 0; c < channels; ++c) out.at(x, y, c) = in.at(x, row, from[c]);
    }
}

void PartJoin::add(Frame part, const std::string& where) {
    if (!part.part)
        throw InputError(fmt::format(
            "{}: a whole frame, not a part of one; `render --tiles K/N` and `run --tiles K/N` "
            "write parts",
            where));
    const PartRecord& r = *part.part;
    if (part.image.height() != r.heightHeld())
        throw InputError(fmt::format(
            "{}: an image {} pixels high; {} of a frame {} pixels high in tiles of {} holds {} "
            "rows of pixels",
            where, part.image.height(), partName(r.part), r.height, r.tileSize, r.heightHeld()));
    const int rows = r.part.rowsHeld(r.height, r.tileSize);
    for (const auto& [name, mean] : r.means)
        if (static_cast<int>(mean.rowSums.size()) != rows)
            throw InputError(fmt::format(
                "{}: \"tile\".means.{} has {} row sums; {} of a frame {} pixels high in tiles of "
                "{} holds {} rows",
                where, name, mean.rowSums.size(), partName(r.part), r.height, r.tileSize, rows));
    if (mParts.empty()) {
        mWidth = part.image.width();
        mFrame.renderer = part.renderer;
        mFrame.settings = part.settings;
        mFrame.particleCount = part.particleCount;
        for (const auto& [name, value] : part.counters) mFrame.counters[name] = 0.0;
        for (const std::string& name : r.shared) mFrame.counters[name] = part.counters.at(name);
        for (const std::string& name : r.maxima) mFrame.counters[name] = part.counters.at(name);
    } else {
        check(part, where);
    }
    if (part.image.height() > 0) {
        if (mFrame.image.channelCount() == 0)
            mFrame.image = Image(mWidth, r.height, part.image.channelNames());
        copyRows(part);
    }
    const auto listed = [](const std::vector<std::string>& names, const std::string& name) {
        return std::find(names.begin(), names.end(), name) != names.end();
    };
    for (const auto& [name, value] : part.counters) {
        if (listed(r.maxima, name))
            mFrame.counters[name] = std::max(mFrame.counters[name], value);
        else if (!listed(r.shared, name) && !r.means.count(name))
            mFrame.counters[name] += value;
    }
    mParts.emplace(r.part.index, Added{.record = r,
                                       .where = where,
                                       .device = std::move(part.device),
                                       .timingsMs = std::move(part.timingsMs)});
}

Frame PartJoin::frame(float exposure) {
    if (mParts.empty()) throw InputError("no parts to join");
    const int count = mParts.begin()->second.record.part.count;
    for (int k = 1; k <= count; ++k)
        if (!mParts.count(k))
            throw InputError(
                fmt::format("part {}/{} is missing; give all {} parts", k, count, count));
    if (mFrame.image.channelCount() == 0)
        throw InputError(fmt::format("none of the {} parts holds a row of the frame", count));
    // The means: every row's sum in row order, as one render adds them.
    const Added& first = mParts.begin()->second;
    const int tileRows =
        (mFrame.image.height() + first.record.tileSize - 1) / first.record.tileSize;
    for (const auto& [name, unused] : first.record.means) {
        double sum = 0.0;
        std::int64_t samples = 0;
        std::map<int, std::size_t> next;  // per part, its next row's sum
        for (int row = 0; row < tileRows; ++row) {
            const int k = row % count + 1;
            sum += mParts.at(k).record.means.at(name).rowSums.at(next[k]++);
        }
        for (const auto& [k, p] : mParts) samples += p.record.means.at(name).samples;
        mFrame.counters[name] = samples > 0 ? sum / double(samples) : 0.0;
    }
    std::vector<std::string> devices;
    for (const auto& [k, p] : mParts) {
        for (const auto& [stage, ms] : p.timingsMs) mFrame.timingsMs[stage] += ms;
        if (std::find(devices.begin(), devices.end(), p.device) == devices.end())
            devices.push_back(p.device);
    }
    mFrame.device.clear();
    for (const std::string& d : devices) mFrame.device += (mFrame.device.empty() ? "" : "; ") + d;
    mFrame.display = tonemappedBeauty(mFrame.image, exposure);
    return std::move(mFrame);
}

nlohmann::json PartJoin::parts() const {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& [k, p] : mParts)
        list.push_back({{"part", k}, {"device", p.device}, {"timings_ms", p.timingsMs}});
    return list;
}

}  // namespace twinrender::core
