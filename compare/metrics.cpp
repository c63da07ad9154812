#include "compare/metrics.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <stdexcept>
#include <string_view>

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

// The first AOV channel the image lacks, or "" when it has them all.
std::string firstMissingAovChannel(const core::Image& image) {
    for (const auto& name : core::aov::channelNames())
        if (!image.hasChannel(name)) return name;
    return {};
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
    const bool anyAov = std::any_of(names.begin(), names.end(), [](const std::string& n) {
        if (isDisplayChannel(n)) return false;
        const auto& aov = core::aov::channelNames();
        return std::find(aov.begin(), aov.end(), n) != aov.end();
    });
    if (!anyAov) return false;
    const std::string missing = firstMissingAovChannel(image);
    if (!missing.empty())
        throw core::NotComparableError(fmt::format(
            "metrics: the image has some AOV channels but no channel \"{}\"; an AOV image "
            "carries all of {}",
            missing, fmt::join(core::aov::channelNames(), ", ")));
    return true;
}

MaskSettings maskSettings(const MetricSettings& settings) {
    MaskSettings m;
    m.interiorRadius = settings.interiorRadius;
    m.hasLight = settings.hasLight;
    m.lightDirection = settings.lightDirection;
    return m;
}

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
            "metrics: the {} is an AOV image but the {} has no channel \"{}\"; compare two AOV "
            "EXRs (all metrics) or two display images such as PNGs (beauty metrics)",
            refAov ? "reference" : "test", refAov ? "test" : "reference",
            firstMissingAovChannel(refAov ? test : reference)));

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

    const Masks masks = computeMasks(reference, test, maskSettings(settings));

    result.values["coverage.iou"] = coverageIou(masks);
    result.values["silhouette.mean_px"] = silhouetteMeanPx(masks);

    DepthResult depth = depthError(reference, test, masks);
    result.values["depth.rel_mean"] = depth.relMean;
    result.errorMaps["depth"] = std::move(depth.errorMap);

    IdResult id = idMismatch(reference, test, masks);
    result.values["id.mismatch"] = id.mismatch;
    result.errorMaps["id"] = std::move(id.errorMap);

    NormalResult normal = normalError(reference, test, masks);
    result.values["normal.mean_deg"] = normal.meanDeg;
    result.values["normal.p95_deg"] = normal.p95Deg;
    result.errorMaps["normal"] = std::move(normal.errorMap);

    UvResult uv = uvError(reference, test, masks);
    result.values["uv.mean"] = uv.mean;
    result.errorMaps["uv"] = std::move(uv.errorMap);

    EmissionResult emission = emissionError(reference, test, masks);
    result.values["emission.rmse"] = emission.rmse;
    result.errorMaps["emission"] = std::move(emission.errorMap);

    result.values["flux.ratio"] = fluxRatio(reference, test);
    result.values["smoothness.ratio"] = smoothness(reference, test, masks).ratio;

    ShadowResult shadow = shadowError(reference, test, masks);
    result.values["shadow.iou"] = shadow.iou;
    result.values["shadow.false_shadow"] = shadow.falseShadow;
    result.values["shadow.missed_shadow"] = shadow.missedShadow;
    result.values["shadow.mae"] = shadow.mae;
    result.values["shadow.leak"] = shadow.leak;
    result.errorMaps["shadow"] = std::move(shadow.errorMap);

    // Frames written before the ambient occlusion channel have none: no ao metrics for them.
    if (reference.hasChannel("ao") && test.hasChannel("ao")) {
        AoResult ao = aoError(reference, test, masks);
        result.values["ao.mean_abs"] = ao.meanAbs;
        result.values["ao.bias"] = ao.bias;
        result.values["ao.halo"] = ao.halo;
        result.values["ao.grain"] = ao.grain;
        result.values["ao.banding"] = ao.banding;
        result.errorMaps["ao"] = std::move(ao.errorMap);
    }
    // The light of emitting surfaces, where either frame has any (light.emissive_light).
    if (reference.hasChannel("irradiance.R") && test.hasChannel("irradiance.R") &&
        hasIrradiance(reference, test)) {
        IndirectResult indirect = indirectError(reference, test, masks);
        result.values["indirect.rmse"] = indirect.rmse;
        result.values["indirect.missed"] = indirect.missed;
        result.values["indirect.false"] = indirect.falseLight;
        result.errorMaps["irradiance"] = std::move(indirect.errorMap);
    }
    // A body's atmosphere, where either frame has in-scatter.
    if (reference.hasChannel("inscatter.R") && test.hasChannel("inscatter.R") &&
        hasInscatter(reference, test)) {
        InscatterResult inscatter = inscatterError(reference, test);
        result.values["inscatter.rmse"] = inscatter.rmse;
        result.values["inscatter.rel"] = inscatter.rel;
        result.errorMaps["inscatter"] = std::move(inscatter.errorMap);
    }
    return result;
}

}  // namespace twinrender::compare
