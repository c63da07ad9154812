#include "compare/metrics.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "compare/flip.h"
#include "compare/psnr.h"
#include "compare/ssim.h"
#include "core/error.h"
#include "core/frame.h"

namespace twinrender::compare {
namespace {

const std::set<std::string> BEAUTY_KEYS = {"beauty.psnr",     "beauty.ssim",
                                           "beauty.flip",     "beauty.flip_p95",
                                           "beauty.flip_p99", "beauty.flip_over"};
const std::set<std::string> ALL_KEYS = {"beauty.psnr",
                                        "beauty.ssim",
                                        "beauty.flip",
                                        "beauty.flip_p95",
                                        "beauty.flip_p99",
                                        "beauty.flip_over",
                                        "beauty.hdrflip",
                                        "coverage.iou",
                                        "silhouette.mean_px",
                                        "depth.rel_mean",
                                        "id.mismatch",
                                        "normal.mean_deg",
                                        "normal.p95_deg",
                                        "uv.mean",
                                        "emission.rmse",
                                        "flux.ratio",
                                        "smoothness.ratio",
                                        "shadow.iou",
                                        "shadow.false_shadow",
                                        "shadow.missed_shadow",
                                        "shadow.mae",
                                        "shadow.leak",
                                        "ao.mean_abs",
                                        "ao.bias",
                                        "ao.halo",
                                        "ao.grain",
                                        "ao.banding",
                                        "indirect.rmse",
                                        "indirect.missed",
                                        "indirect.false"};
const std::set<std::string> MAP_KEYS = {
    "beauty.flip", "beauty.hdrflip", "normal",   "depth", "uv",
    "id",          "shadow",         "emission", "ao",    "irradiance"};

template <typename Map>
std::set<std::string> keys(const Map& m) {
    std::set<std::string> k;
    for (const auto& [name, value] : m) k.insert(name);
    return k;
}

// Two overlapping spheres seen from +z (body 0 on the left, body 1 in front on the right), lit
// from the upper left, shadowed where body 1 hides body 0 from the light, body 1 glowing and
// casting its light (irradiance 0.5 max(n.x, 0)) on body 0. The
// test may shift everything right by `shift` pixels and perturb the normals by `noise`.
core::Image spheres(int w, int h, int shift = 0, float noise = 0.0f) {
    core::Image img = core::aov::makeImage(w, h);
    auto set = [&](int x, int y, const char* c, float v) { img.at(x, y, img.channelIndex(c)) = v; };
    const glm::vec3 toLight = glm::normalize(glm::vec3(-0.5f, 0.6f, 0.6f));
    std::uint32_t state = 11u;
    auto next = [&] {
        state = 1664525u * state + 1013904223u;
        return static_cast<float>(state >> 8) / 16777216.0f - 0.5f;
    };
    struct Sphere {
        float cx, cy, r, z, id;
    };
    const Sphere bodies[2] = {{0.38f * w, 0.5f * h, 0.3f * h, 20.0f, 0.0f},
                              {0.62f * w, 0.55f * h, 0.25f * h, 10.0f, 1.0f}};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float px = x + 0.5f - shift, py = y + 0.5f;
            for (int b = 1; b >= 0; --b) {  // the front body first
                const Sphere& s = bodies[b];
                const float dx = (px - s.cx) / s.r, dy = -(py - s.cy) / s.r;
                const float d2 = dx * dx + dy * dy;
                if (d2 >= 1.0f) continue;
                glm::vec3 n(dx, dy, std::sqrt(1.0f - d2));
                n = glm::normalize(n + noise * glm::vec3(next(), next(), next()));
                const float lit =
                    (b == 0 && px > 0.35f * w && px < 0.45f * w && py < 0.45f * h) ? 0.0f : 1.0f;
                const float diffuse = std::max(0.0f, glm::dot(n, toLight)) * lit;
                const float glow = b == 1 ? 0.2f : 0.0f;
                set(x, y, "R", 0.8f * diffuse + glow + 0.02f);
                set(x, y, "G", 0.6f * diffuse + 0.02f);
                set(x, y, "B", 0.4f * diffuse + 0.02f);
                set(x, y, "A", 1.0f);
                set(x, y, "Z", s.z - s.r * 0.01f * n.z);
                set(x, y, "N.X", n.x);
                set(x, y, "N.Y", n.y);
                set(x, y, "N.Z", n.z);
                set(x, y, "uv.U",
                    std::fmod(std::atan2(n.x, n.z) / (2 * std::numbers::pi_v<float>)+1.0f, 1.0f));
                set(x, y, "uv.V", 0.5f + std::asin(n.y) / std::numbers::pi_v<float>);
                set(x, y, "id", s.id);
                set(x, y, "emission.R", glow);
                set(x, y, "irradiance.R", b == 0 ? 0.5f * std::max(n.x, 0.0f) : 0.0f);
                set(x, y, "shadow", lit);
                break;
            }
        }
    return img;
}

core::Image pick(const core::Image& image, const std::vector<std::string>& channels) {
    return image.select(channels);
}

MetricSettings withLight() {
    MetricSettings s;
    s.hasLight = true;
    s.lightDirection = -glm::dvec3(-0.5, 0.6, 0.6);
    return s;
}

TEST(Metrics, IdenticalAovImagesArePerfect) {
    const core::Image img = spheres(96, 64);
    const MetricResult r = computeMetrics(img, img, withLight());
    EXPECT_EQ(keys(r.values), ALL_KEYS);
    EXPECT_EQ(keys(r.errorMaps), MAP_KEYS);
    EXPECT_EQ(r.values.at("beauty.psnr"), std::numeric_limits<double>::infinity());
    EXPECT_EQ(r.values.at("beauty.ssim"), 1.0);
    EXPECT_EQ(r.values.at("beauty.flip"), 0.0);
    EXPECT_EQ(r.values.at("beauty.flip_p95"), 0.0);
    EXPECT_EQ(r.values.at("beauty.flip_p99"), 0.0);
    EXPECT_EQ(r.values.at("beauty.flip_over"), 0.0);
    EXPECT_EQ(r.values.at("beauty.hdrflip"), 0.0);
    ASSERT_TRUE(r.hdrExposures.has_value());
    EXPECT_EQ(r.hdrExposures->start, exposureRange(img).start);
    EXPECT_EQ(r.values.at("coverage.iou"), 1.0);
    EXPECT_EQ(r.values.at("silhouette.mean_px"), 0.0);
    EXPECT_EQ(r.values.at("depth.rel_mean"), 0.0);
    EXPECT_EQ(r.values.at("id.mismatch"), 0.0);
    EXPECT_EQ(r.values.at("normal.mean_deg"), 0.0);
    EXPECT_EQ(r.values.at("normal.p95_deg"), 0.0);
    EXPECT_EQ(r.values.at("uv.mean"), 0.0);
    EXPECT_EQ(r.values.at("emission.rmse"), 0.0);
    EXPECT_EQ(r.values.at("smoothness.ratio"), 1.0);
    EXPECT_EQ(r.values.at("shadow.iou"), 1.0);
    EXPECT_EQ(r.values.at("shadow.false_shadow"), 0.0);
    EXPECT_EQ(r.values.at("shadow.missed_shadow"), 0.0);
    EXPECT_EQ(r.values.at("shadow.mae"), 0.0);
    EXPECT_EQ(r.values.at("shadow.leak"), 0.0);
    for (const auto& [name, map] : r.errorMaps) {
        EXPECT_EQ(map.channelCount(), 1) << name;
        EXPECT_EQ(map.width(), 96) << name;
        EXPECT_EQ(map.height(), 64) << name;
        for (float v : map.pixels()) ASSERT_EQ(v, 0.0f) << name;
    }
}

TEST(Metrics, TheMetricsOfABufferNeitherImageFillsDoNotApply) {
    core::Image img = spheres(48, 32);
    const int ao = img.requireChannel("ao");
    for (std::size_t p = 0; p < img.pixelCount(); ++p) {
        img.at(p, ao) = 1.0f;  // no occlusion anywhere
        for (const char* c : {"emission.R", "emission.G", "emission.B"})
            img.at(p, img.requireChannel(c)) = 0.0f;  // and no emission
    }
    MetricResult r = computeMetrics(img, img, withLight());
    for (const char* m : {"ao.mean_abs", "ao.bias", "ao.halo", "ao.grain", "ao.banding"}) {
        EXPECT_EQ(r.notApplicable.at(m),
                  "neither render has any occlusion (light.ao_radius 0, or nothing occludes)");
        EXPECT_EQ(r.values.at(m), 0.0) << m;  // the value stays
    }
    EXPECT_EQ(r.notApplicable.at("emission.rmse"), "neither render has any emission");
    EXPECT_EQ(r.notApplicable.size(), 6u);
    // Occlusion in one covered pixel of one image: its metrics apply.
    core::Image occluded = img;
    const int alpha = img.requireChannel("A");
    std::size_t covered = 0;
    while (img.at(covered, alpha) < 1.0f) ++covered;
    occluded.at(covered, ao) = 0.5f;
    r = computeMetrics(img, occluded, withLight());
    EXPECT_EQ(r.notApplicable.count("ao.mean_abs"), 0u);
    EXPECT_EQ(r.notApplicable.count("emission.rmse"), 1u);
}

TEST(Metrics, TheSceneHasShadowsAndBothBodies) {
    // The fixture must exercise what the perfect case claims: shadowed pixels facing the light,
    // two bodies, emission.
    const core::Image img = spheres(96, 64);
    int shadowed = 0, body1 = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 96; ++x) {
            if (img.at(x, y, img.channelIndex("A")) < 0.5f) continue;
            shadowed += img.at(x, y, img.channelIndex("shadow")) < 0.5f &&
                        img.at(x, y, img.channelIndex("N.Z")) > 0.5f;
            body1 += img.at(x, y, img.channelIndex("id")) == 1.0f;
        }
    EXPECT_GT(shadowed, 50);
    EXPECT_GT(body1, 500);
}

TEST(Metrics, ADifferentTestIsWorseOnEveryMetric) {
    const core::Image ref = spheres(96, 64);
    const core::Image test = spheres(96, 64, 2, 0.3f);
    const MetricResult r = computeMetrics(ref, test, withLight());
    EXPECT_LT(r.values.at("beauty.psnr"), 40.0);
    EXPECT_LT(r.values.at("beauty.ssim"), 1.0);
    EXPECT_GT(r.values.at("beauty.flip"), 0.0);
    EXPECT_EQ(r.values.at("beauty.hdrflip"), hdrFlip(ref, test).mean);
    EXPECT_GT(r.values.at("beauty.hdrflip"), 0.0);
    EXPECT_LT(r.values.at("coverage.iou"), 1.0);
    // Outlines shifted 2 pixels horizontally: the mean distance lies between 0 and 2.
    EXPECT_GT(r.values.at("silhouette.mean_px"), 0.5);
    EXPECT_LE(r.values.at("silhouette.mean_px"), 2.0);
    EXPECT_GT(r.values.at("depth.rel_mean"), 0.0);
    EXPECT_GT(r.values.at("id.mismatch"), 0.0);
    EXPECT_GT(r.values.at("normal.mean_deg"), 1.0);
    EXPECT_GT(r.values.at("normal.p95_deg"), r.values.at("normal.mean_deg"));
    EXPECT_GT(r.values.at("uv.mean"), 0.0);
    EXPECT_GT(r.values.at("emission.rmse"), 0.0);
    EXPECT_GT(r.values.at("smoothness.ratio"), 1.0);
    EXPECT_LT(r.values.at("shadow.iou"), 1.0);
    EXPECT_GT(r.values.at("shadow.false_shadow") + r.values.at("shadow.missed_shadow"), 0.0);
}

TEST(Metrics, BeautyIsTakenOnTheTonemappedImage) {
    const core::Image ref = spheres(96, 64);
    const core::Image test = spheres(96, 64, 1);
    MetricSettings settings;
    settings.exposure = 1.5;
    const MetricResult r = computeMetrics(ref, test, settings);
    const core::Image refDisplay = core::tonemappedBeauty(ref, 1.5f);
    const core::Image testDisplay = core::tonemappedBeauty(test, 1.5f);
    EXPECT_EQ(r.values.at("beauty.psnr"), psnr(refDisplay, testDisplay).psnr);
    EXPECT_EQ(r.values.at("beauty.ssim"), ssim(refDisplay, testDisplay).ssim);
    const FlipResult f = flip(refDisplay, testDisplay);
    EXPECT_EQ(r.values.at("beauty.flip"), f.mean);
    EXPECT_EQ(r.errorMaps.at("beauty.flip"), f.errorMap);
    const FlipPooled pooled = poolFlip(f.errorMap);
    EXPECT_EQ(r.values.at("beauty.flip_p95"), pooled.p95);
    EXPECT_EQ(r.values.at("beauty.flip_p99"), pooled.p99);
    EXPECT_EQ(r.values.at("beauty.flip_over"), pooled.over);
    // The pooled statistics see the tail the mean averages away.
    EXPECT_GT(r.values.at("beauty.flip_p99"), r.values.at("beauty.flip_p95"));
    EXPECT_GT(r.values.at("beauty.flip_p95"), r.values.at("beauty.flip"));
}

TEST(Metrics, FlipOverLevelReachesThePooling) {
    const core::Image ref = spheres(96, 64), test = spheres(96, 64, 1);
    MetricSettings low;
    low.flipOver = 0.05;
    const double atDefault = computeMetrics(ref, test).values.at("beauty.flip_over");
    const double atLow = computeMetrics(ref, test, low).values.at("beauty.flip_over");
    FlipPoolingSettings pooling;
    pooling.overLevel = 0.05;
    EXPECT_EQ(
        atLow,
        poolFlip(
            flip(core::tonemappedBeauty(ref, 1.0f), core::tonemappedBeauty(test, 1.0f)).errorMap,
            pooling)
            .over);
    EXPECT_GT(atLow, atDefault);
}

TEST(Metrics, PpdReachesFlip) {
    const core::Image ref = spheres(96, 64), test = spheres(96, 64, 1);
    MetricSettings settings;
    settings.ppd = 20.0;
    FlipSettings flipSettings;
    flipSettings.ppd = 20.0;
    EXPECT_EQ(
        computeMetrics(ref, test, settings).values.at("beauty.flip"),
        flip(core::tonemappedBeauty(ref, 1.0f), core::tonemappedBeauty(test, 1.0f), flipSettings)
            .mean);
}

TEST(Metrics, PlainImagesGetTheBeautyMetricsOnThePixelsAsGiven) {
    const core::Image ref = core::tonemappedBeauty(spheres(96, 64), 1.0f);
    const core::Image test = core::tonemappedBeauty(spheres(96, 64, 1), 1.0f);
    const MetricResult r = computeMetrics(ref, test);
    EXPECT_EQ(keys(r.values), BEAUTY_KEYS);
    EXPECT_EQ(keys(r.errorMaps), std::set<std::string>{"beauty.flip"});
    EXPECT_FALSE(r.hdrExposures.has_value());
    EXPECT_EQ(r.values.at("beauty.psnr"), psnr(ref, test).psnr);
    EXPECT_EQ(r.values.at("beauty.flip"), flip(ref, test).mean);
    // A PNG with alpha (R, G, B, A) is a plain image too.
    core::Image withAlpha(96, 64, {"R", "G", "B", "A"});
    EXPECT_EQ(keys(computeMetrics(withAlpha, withAlpha).values), BEAUTY_KEYS);
}

TEST(Metrics, SameResultOnOneThread) {
    const core::Image ref = spheres(96, 64), test = spheres(96, 64, 2, 0.3f);
    const MetricResult many = computeMetrics(ref, test, withLight());
    tbb::task_arena one(1);
    const MetricResult single = one.execute([&] { return computeMetrics(ref, test, withLight()); });
    EXPECT_EQ(many.values, single.values);
    EXPECT_EQ(many.errorMaps, single.errorMaps);
}

void expectNotComparable(const core::Image& ref, const core::Image& test,
                         const std::vector<std::string>& mentioned) {
    try {
        computeMetrics(ref, test);
        FAIL() << "expected NotComparableError";
    } catch (const core::NotComparableError& e) {
        for (const auto& m : mentioned)
            EXPECT_NE(std::string(e.what()).find(m), std::string::npos) << e.what();
    }
}

TEST(Metrics, DifferentSizesNameBoth) {
    expectNotComparable(spheres(96, 64), spheres(64, 48), {"96x64", "64x48"});
    expectNotComparable(core::Image(30, 20, {"R", "G", "B"}), core::Image(20, 30, {"R", "G", "B"}),
                        {"30x20", "20x30"});
}

TEST(Metrics, MissingChannelsAreNamed) {
    const core::Image full = spheres(32, 32);
    // An AOV image against a plain one: the message names what the plain one has and lacks.
    expectNotComparable(full, core::Image(32, 32, {"R", "G", "B"}),
                        {"test has no AOV channel", "only R, G, B", "uv.V"});
    // A plain image without G.
    expectNotComparable(core::Image(32, 32, {"R", "B"}), core::Image(32, 32, {"R", "G", "B"}),
                        {"\"G\"", "reference"});
}

TEST(Metrics, IsAovImage) {
    EXPECT_TRUE(isAovImage(core::aov::makeImage(4, 4)));
    EXPECT_FALSE(isAovImage(core::Image(4, 4, {"R", "G", "B"})));
    EXPECT_FALSE(isAovImage(core::Image(4, 4, {"R", "G", "B", "A"})));
    EXPECT_TRUE(isAovImage(core::Image(4, 4, {"R", "G", "B", "A", "Z"})));
    EXPECT_EQ(missingAovChannels(core::aov::makeImage(4, 4)), std::vector<std::string>{});
    std::vector<std::string> names = core::aov::channelNames();
    std::erase(names, std::string("inscatter.G"));
    EXPECT_EQ(missingAovChannels(core::aov::makeImage(4, 4).select(names)),
              std::vector<std::string>{"inscatter.G"});
}

// A test image with some AOV channels (a renderer that writes beauty, coverage, depth and
// normals): every metric their channels give, equal to the full pair's, and the rest listed as
// not provided, never present as a value.
TEST(Metrics, PartialAovsGiveEveryMetricTheirChannelsAllow) {
    const core::Image ref = spheres(96, 64);
    const core::Image full = spheres(96, 64, 2, 0.3f);
    const core::Image partial = pick(full, {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"});
    const MetricResult all = computeMetrics(ref, full, withLight());
    const MetricResult some = computeMetrics(ref, partial, withLight());
    // Same masks where the id is missing only if no pixel's bodies differ; here they do (the
    // shift moves body 1 over body 0), so the masks are "covered in both": the coverage, depth
    // and beauty metrics agree exactly, the normals' within what the id boundary changes.
    for (const char* key : {"beauty.psnr", "beauty.flip", "beauty.hdrflip", "coverage.iou",
                            "silhouette.mean_px", "flux.ratio"})
        EXPECT_EQ(some.values.at(key), all.values.at(key)) << key;
    for (const char* key :
         {"depth.rel_mean", "normal.mean_deg", "normal.p95_deg", "smoothness.ratio"}) {
        ASSERT_TRUE(some.values.count(key)) << key;
        EXPECT_TRUE(std::isfinite(some.values.at(key))) << key;
    }
    const std::set<std::string> notProvided(some.notProvided.begin(), some.notProvided.end());
    // Every AOV metric of the full pair but those of beauty, coverage, depth and normals.
    std::set<std::string> expected;
    for (const std::string& key : ALL_KEYS)
        if (!BEAUTY_KEYS.count(key) && !key.starts_with("coverage.") &&
            !key.starts_with("silhouette.") && !key.starts_with("depth.") &&
            !key.starts_with("normal.") && key != "smoothness.ratio" && key != "flux.ratio" &&
            key != "beauty.hdrflip")
            expected.insert(key);
    EXPECT_EQ(notProvided, expected);
    for (const std::string& key : some.notProvided) EXPECT_FALSE(some.values.count(key)) << key;
    // Every metric of the full pair is either given or listed.
    for (const auto& [key, value] : all.values)
        EXPECT_TRUE(some.values.count(key) || notProvided.count(key)) << key;
    EXPECT_EQ(some.missingChannels.size(), core::aov::channelNames().size() - 8);
    EXPECT_TRUE(all.notProvided.empty());
}

// The same images with id: the masks are the full pair's, so every metric the partial image
// gives is the full pair's exactly.
TEST(Metrics, PartialAovsWithIdsMeasureAsTheFullImages) {
    const core::Image ref = spheres(96, 64);
    const core::Image full = spheres(96, 64, 2, 0.3f);
    const core::Image partial =
        pick(full, {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z", "id", "shadow"});
    const MetricResult all = computeMetrics(ref, full, withLight());
    const MetricResult some = computeMetrics(ref, partial, withLight());
    for (const auto& [key, value] : some.values) EXPECT_EQ(value, all.values.at(key)) << key;
    EXPECT_EQ(some.values.size() + some.notProvided.size(), all.values.size());
}

// Without A nothing has a mask: only the beauty metrics and the flux.
TEST(Metrics, WithoutCoverageOnlyTheBeautyIsMeasured) {
    const core::Image ref = spheres(64, 48);
    const MetricResult r = computeMetrics(ref, pick(ref, {"R", "G", "B", "Z"}), withLight());
    EXPECT_EQ(r.values.size(), BEAUTY_KEYS.size() + 2);  // and beauty.hdrflip, flux.ratio
    EXPECT_TRUE(r.values.count("flux.ratio"));
    EXPECT_EQ(std::count(r.notProvided.begin(), r.notProvided.end(), "coverage.iou"), 1);
    EXPECT_EQ(std::count(r.notProvided.begin(), r.notProvided.end(), "depth.rel_mean"), 1);
}

TEST(Metrics, SettingsOutOfRange) {
    const core::Image img = spheres(32, 32);
    MetricSettings s;
    s.ppd = 0.0;
    EXPECT_THROW(computeMetrics(img, img, s), std::invalid_argument);
    s = {};
    s.exposure = -1.0;
    EXPECT_THROW(computeMetrics(img, img, s), std::invalid_argument);
    s = {};
    s.interiorRadius = -2;
    EXPECT_THROW(computeMetrics(img, img, s), std::invalid_argument);
    for (double level : {0.0, 1.0}) {
        s = {};
        s.flipOver = level;
        EXPECT_THROW(computeMetrics(img, img, s), std::invalid_argument) << level;
    }
}

}  // namespace
}  // namespace twinrender::compare
