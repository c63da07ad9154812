#include "compare/metrics.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "compare/buffer_metrics.h"
#include "compare/flip.h"
#include "compare/hdr_flip.h"
#include "compare/masks.h"
#include "compare/psnr.h"
#include "compare/ssim.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/shading.h"

namespace twinrender::compare {

namespace {

bool isDisplayChannel(std::string_view name) {
    return name == "R" || name == "G" || name == "B" || name == "A";
}

// Whether both images carry every one of `channels`.
bool bothHave(const core::Image& a, const core::Image& b,
              std::initializer_list<std::string_view> channels) {
    return std::all_of(channels.begin(), channels.end(), [&](std::string_view c) {
        return a.hasChannel(std::string(c)) && b.hasChannel(std::string(c));
    });
}

// Whether every pixel of both images has no emission: a buffer neither render wrote into.
bool neitherEmits(const core::Image& a, const core::Image& b) {
    for (const core::Image* image : {&a, &b})
        for (const char* name : {"emission.R", "emission.G", "emission.B"}) {
            const int c = image->requireChannel(name);
            for (std::size_t p = 0; p < image->pixelCount(); ++p)
                if (image->at(p, c) != 0.0f) return false;
        }
    return true;
}

// Whether no covered pixel of either image is occluded: ao is at least the coverage A there
// (1 on the surface, 0 where nothing is hit, edge pixels in between; to 1e-6).
bool neitherOccludes(const core::Image& a, const core::Image& b) {
    for (const core::Image* image : {&a, &b}) {
        const int ao = image->requireChannel("ao"), alpha = image->channelIndex("A");
        for (std::size_t p = 0; p < image->pixelCount(); ++p) {
            const float covered = alpha < 0 ? 1.0f : image->at(p, alpha);
            if (!(image->at(p, ao) >= covered - 1e-6f)) return false;
        }
    }
    return true;
}

// core::tonemappedBeauty, rows in parallel: the same values (core::tonemap per pixel).
core::Image tonemapped(const core::Image& aovImage, float exposure) {
    core::Image out(aovImage.width(), aovImage.height(), {"R", "G", "B"});
    const int r = aovImage.requireChannel("R");
    const int g = aovImage.requireChannel("G");
    const int b = aovImage.requireChannel("B");
    const int w = aovImage.width();
    tbb::parallel_for(
        tbb::blocked_range<int>(0, aovImage.height()), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < w; ++x) {
                    const glm::vec3 c = core::tonemap(
                        {aovImage.at(x, y, r), aovImage.at(x, y, g), aovImage.at(x, y, b)},
                        exposure);
                    for (int k = 0; k < 3; ++k) out.at(x, y, k) = c[k];
                }
        });
    return out;
}

void validate(const MetricSettings& settings) {
    if (!(settings.ppd > 0.0))
        throw std::invalid_argument(fmt::format("metrics: ppd must be > 0, got {}", settings.ppd));
    if (!(settings.flipOver > 0.0 && settings.flipOver < 1.0))
        throw std::invalid_argument(fmt::format(
            "metrics: the ꟻLIP error level of beauty.flip_over must be in (0, 1), got {}",
            settings.flipOver));
    if (!(settings.exposure > 0.0))
        throw std::invalid_argument(
            fmt::format("metrics: exposure must be > 0, got {}", settings.exposure));
    if (settings.interiorRadius < 0)
        throw std::invalid_argument(fmt::format(
            "metrics: the interior radius must be >= 0 pixels, got {}", settings.interiorRadius));
}

}  // namespace

bool isAovImage(const core::Image& image) {
    const auto& names = image.channelNames();
    return std::any_of(names.begin(), names.end(), [](const std::string& n) {
        if (isDisplayChannel(n)) return false;
        const auto& aov = core::aov::channelNames();
        return std::find(aov.begin(), aov.end(), n) != aov.end();
    });
}

std::vector<std::string> missingAovChannels(const core::Image& image) {
    std::vector<std::string> missing;
    for (const auto& name : core::aov::channelNames())
        if (!image.hasChannel(name)) missing.push_back(name);
    return missing;
}

MaskSettings maskSettings(const MetricSettings& settings) {
    MaskSettings m;
    m.interiorRadius = settings.interiorRadius;
    m.hasLight = settings.hasLight;
    m.lightDirection = settings.lightDirection;
    return m;
}

namespace {

// A test image whose Z is not eye depth (a depth buffer's value in [0, 1], NDC, 1/z) measures
// nothing but the convention: where both images are covered, the median of test Z over
// reference Z lies within [0.5, 2] for any renderer that writes eye depth at all (a distance
// along the ray instead is at most 1/cos(half the field of view) longer).
void checkDepthConvention(const core::Image& reference, const core::Image& test,
                          const Mask& coveredInBoth) {
    const int rz = reference.requireChannel("Z"), tz = test.requireChannel("Z");
    std::vector<double> ratios;
    for (std::size_t p = 0; p < coveredInBoth.pixelCount(); ++p)
        if (coveredInBoth[p] && reference.at(p, rz) > 0.0f)
            ratios.push_back(double(test.at(p, tz)) / reference.at(p, rz));
    if (ratios.empty()) return;
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    const double median = ratios[ratios.size() / 2];
    if (!(median >= 0.5 && median <= 2.0))
        throw core::NotComparableError(fmt::format(
            "metrics: the test image's Z is {:.3g} times the reference's eye depth (the median "
            "over the {} pixels covered in both): Z must be the eye depth along the view axis in "
            "scene units, +inf where nothing is hit, not a depth buffer's value or NDC "
            "(docs/external.md)",
            median, ratios.size()));
}

// The per-buffer metrics of an AOV pair, each where both images carry its channels (an image
// may carry only some: a renderer that writes beauty, depth and normals gets those metrics);
// the others are listed in result.notProvided. The masks need A in both (computeMasks says what
// they are without id or normals).
void addBufferMetrics(const core::Image& reference, const core::Image& test,
                      const MetricSettings& settings, MetricResult& result) {
    result.missingChannels = missingAovChannels(test);
    for (const std::string& c : missingAovChannels(reference))
        if (std::find(result.missingChannels.begin(), result.missingChannels.end(), c) ==
            result.missingChannels.end())
            result.missingChannels.push_back(c);
    auto notProvided = [&](std::initializer_list<const char*> keys) {
        for (const char* k : keys) result.notProvided.emplace_back(k);
    };
    result.values["flux.ratio"] = fluxRatio(reference, test);
    const bool covered = bothHave(reference, test, {"A"});
    if (!covered) {
        notProvided({"coverage.iou", "silhouette.mean_px", "depth.rel_mean", "id.mismatch",
                     "normal.mean_deg", "normal.p95_deg", "uv.mean", "emission.rmse",
                     "smoothness.ratio", "shadow.iou", "shadow.false_shadow",
                     "shadow.missed_shadow", "shadow.mae", "shadow.leak"});
    }
    std::optional<Masks> masks;
    if (covered) {
        masks = computeMasks(reference, test, maskSettings(settings));
        result.values["coverage.iou"] = coverageIou(*masks);
        result.values["silhouette.mean_px"] = silhouetteMeanPx(*masks);
    }
    if (!masks) return;
    if (bothHave(reference, test, {"Z"})) {
        checkDepthConvention(reference, test, masks->coveredInBoth);
        DepthResult depth = depthError(reference, test, *masks);
        result.values["depth.rel_mean"] = depth.relMean;
        result.errorMaps["depth"] = std::move(depth.errorMap);
    } else {
        notProvided({"depth.rel_mean"});
    }
    if (bothHave(reference, test, {"id"})) {
        IdResult id = idMismatch(reference, test, *masks);
        result.values["id.mismatch"] = id.mismatch;
        result.errorMaps["id"] = std::move(id.errorMap);
    } else {
        notProvided({"id.mismatch"});
    }
    if (bothHave(reference, test, {"N.X", "N.Y", "N.Z"})) {
        NormalResult normal = normalError(reference, test, *masks);
        result.values["normal.mean_deg"] = normal.meanDeg;
        result.values["normal.p95_deg"] = normal.p95Deg;
        result.errorMaps["normal"] = std::move(normal.errorMap);
        result.values["smoothness.ratio"] = smoothness(reference, test, *masks).ratio;
    } else {
        notProvided({"normal.mean_deg", "normal.p95_deg", "smoothness.ratio"});
    }
    if (bothHave(reference, test, {"uv.U", "uv.V"})) {
        UvResult uv = uvError(reference, test, *masks);
        result.values["uv.mean"] = uv.mean;
        result.errorMaps["uv"] = std::move(uv.errorMap);
    } else {
        notProvided({"uv.mean"});
    }
    if (bothHave(reference, test, {"emission.R", "emission.G", "emission.B"})) {
        EmissionResult emission = emissionError(reference, test, *masks);
        result.values["emission.rmse"] = emission.rmse;
        result.errorMaps["emission"] = std::move(emission.errorMap);
        if (neitherEmits(reference, test))
            result.notApplicable["emission.rmse"] = "neither render has any emission";
    } else {
        notProvided({"emission.rmse"});
    }
    if (bothHave(reference, test, {"shadow"})) {
        ShadowResult shadow = shadowError(reference, test, *masks);
        result.values["shadow.iou"] = shadow.iou;
        result.values["shadow.false_shadow"] = shadow.falseShadow;
        result.values["shadow.missed_shadow"] = shadow.missedShadow;
        result.values["shadow.mae"] = shadow.mae;
        result.values["shadow.leak"] = shadow.leak;
        result.errorMaps["shadow"] = std::move(shadow.errorMap);
    } else {
        notProvided({"shadow.iou", "shadow.false_shadow", "shadow.missed_shadow", "shadow.mae",
                     "shadow.leak"});
    }
    // Frames written before the ambient occlusion channel have none: no ao metrics for them;
    // a test image without it beside a reference with it: not provided.
    if (bothHave(reference, test, {"ao"}) && reference.hasChannel("Z") &&
        reference.hasChannel("id")) {
        AoResult ao = aoError(reference, test, *masks);
        result.values["ao.mean_abs"] = ao.meanAbs;
        result.values["ao.bias"] = ao.bias;
        result.values["ao.halo"] = ao.halo;
        result.values["ao.grain"] = ao.grain;
        result.values["ao.banding"] = ao.banding;
        result.errorMaps["ao"] = std::move(ao.errorMap);
        if (neitherOccludes(reference, test))
            for (const char* k : {"ao.mean_abs", "ao.bias", "ao.halo", "ao.grain", "ao.banding"})
                result.notApplicable[k] =
                    "neither render has any occlusion (light.ao_radius 0, or nothing occludes)";
    } else if (reference.hasChannel("ao")) {
        notProvided({"ao.mean_abs", "ao.bias", "ao.halo", "ao.grain", "ao.banding"});
    }
    // The light of emitting surfaces, where either frame has any (light.emissive_light).
    if (bothHave(reference, test, {"irradiance.R", "irradiance.G", "irradiance.B"})) {
        if (hasIrradiance(reference, test)) {
            IndirectResult indirect = indirectError(reference, test, *masks);
            result.values["indirect.rmse"] = indirect.rmse;
            result.values["indirect.missed"] = indirect.missed;
            result.values["indirect.false"] = indirect.falseLight;
            result.errorMaps["irradiance"] = std::move(indirect.errorMap);
        }
    } else if (reference.hasChannel("irradiance.R") && hasIrradiance(reference, reference)) {
        notProvided({"indirect.rmse", "indirect.missed", "indirect.false"});
    }
    // A body's atmosphere, where either frame has in-scatter.
    if (bothHave(reference, test, {"inscatter.R", "inscatter.G", "inscatter.B"})) {
        if (hasInscatter(reference, test)) {
            InscatterResult inscatter = inscatterError(reference, test);
            result.values["inscatter.rmse"] = inscatter.rmse;
            result.values["inscatter.rel"] = inscatter.rel;
            result.errorMaps["inscatter"] = std::move(inscatter.errorMap);
        }
    } else if (reference.hasChannel("inscatter.R") && hasInscatter(reference, reference)) {
        notProvided({"inscatter.rmse", "inscatter.rel"});
    }
}

}  // namespace

MetricResult computeMetrics(const core::Image& reference, const core::Image& test,
                            const MetricSettings& settings) {
    validate(settings);
    if (reference.width() != test.width() || reference.height() != test.height())
        throw core::NotComparableError(fmt::format(
            "metrics: the reference is {}x{} pixels but the test is {}x{}; render both at the "
            "same camera.width and camera.height",
            reference.width(), reference.height(), test.width(), test.height()));
    for (const char* c : {"R", "G", "B"}) {
        if (!reference.hasChannel(c))
            throw core::NotComparableError(
                fmt::format("metrics: the reference image has no channel \"{}\"", c));
        if (!test.hasChannel(c))
            throw core::NotComparableError(
                fmt::format("metrics: the test image has no channel \"{}\"", c));
    }
    const bool refAov = isAovImage(reference);
    const bool testAov = isAovImage(test);
    if (refAov != testAov)
        throw core::NotComparableError(fmt::format(
            "metrics: the {} is an AOV image but the {} has no AOV channel (only {}); compare two "
            "AOV EXRs (every metric their channels allow: at least R, G, B and one of {}) or two "
            "display images such as PNGs (beauty metrics)",
            refAov ? "reference" : "test", refAov ? "test" : "reference",
            fmt::join((refAov ? test : reference).channelNames(), ", "),
            fmt::join(missingAovChannels(refAov ? test : reference), ", ")));

    MetricResult result;
    {
        // Beauty on the display image: tonemapped for AOV images, as given for plain ones.
        core::Image refDisplay, testDisplay;
        if (refAov) {
            refDisplay = tonemapped(reference, static_cast<float>(settings.exposure));
            testDisplay = tonemapped(test, static_cast<float>(settings.exposure));
        }
        const core::Image& r = refAov ? refDisplay : reference;
        const core::Image& t = refAov ? testDisplay : test;
        // PSNR and SSIM beside ꟻLIP and its pooling: each is parallel over rows, but ꟻLIP's
        // pooling is not, and the other's rows fill the second core meanwhile. Each result is
        // its own, so the same whatever runs where.
        double psnrValue = 0.0, ssimValue = 0.0;
        FlipResult f;
        FlipPooled pooled;
        tbb::parallel_invoke(
            [&] {
                psnrValue = psnr(r, t).psnr;
                SsimSettings ssimSettings;
                ssimSettings.ssimMap = false;
                ssimValue = ssim(r, t, ssimSettings).ssim;
            },
            [&] {
                FlipSettings flipSettings;
                flipSettings.ppd = settings.ppd;
                f = flip(r, t, flipSettings);
                FlipPoolingSettings pooling;
                pooling.overLevel = settings.flipOver;
                pooled = poolFlip(f.errorMap, pooling);
            });
        result.values["beauty.psnr"] = psnrValue;
        result.values["beauty.ssim"] = ssimValue;
        result.values["beauty.flip"] = f.mean;
        result.values["beauty.flip_p95"] = pooled.p95;
        result.values["beauty.flip_p99"] = pooled.p99;
        result.values["beauty.flip_over"] = pooled.over;
        result.errorMaps["beauty.flip"] = std::move(f.errorMap);
    }
    if (!refAov) return result;

    HdrFlipSettings hdrSettings;
    hdrSettings.ppd = settings.ppd;
    HdrFlipResult hdr = hdrFlip(reference, test, hdrSettings);
    result.values["beauty.hdrflip"] = hdr.mean;
    result.hdrExposures = hdr.range;
    result.errorMaps["beauty.hdrflip"] = std::move(hdr.errorMap);
    addBufferMetrics(reference, test, settings, result);
    return result;
}

}  // namespace twinrender::compare
