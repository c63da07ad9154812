// What each study's file (app/studies/<name>.cpp) gives the list of studies
// (app/studies/registry.cpp): the points it renders and the conclusion it draws from their rows.
// The layouts of the particle_size and view_angle scenes are here too: the methods study renders
// its methods along them.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/render_job.h"
#include "app/studies.h"
#include "app/studies/common.h"
#include "report/study_report.h"

namespace twinrender::app::study {

// ---- depth_range (depth_range.cpp) ----
std::vector<StudyPoint> depthRangePoints(bool quick);
void depthRangeConclude(report::StudyResult& s);

// ---- thin_casters (thin_casters.cpp) ----
std::vector<StudyPoint> thinCastersPoints(bool quick);
void thinCastersConclude(report::StudyResult& s);

// ---- particle_size (particle_size.cpp) ----
std::vector<StudyPoint> particleSizePoints(bool quick);
void particleSizeConclude(report::StudyResult& s);
// Pixels per particle at the camera's target: the x of a point of the particle_size scene.
double particlePixels(const LoadedScene& s);
// The camera's distances from the target (quick: fewer), and its position at one of them.
std::vector<double> sizeDistances(bool quick);
std::string sizeCamera(double distance);
// What quick runs of the particle_size scene add: fewer, larger particles.
inline constexpr char SIZE_QUICK_PARTICLES[] = "bodies.slab.particles=6000";
// The rows of SSSS on and off (the particle_size and view_angle studies) paired by x, and how
// on's normal error stands to off's beyond the two rows' spreads. Per x, keyed `key(x)`, the
// facts get the gain 1 - on/off (normal_gain), that order (against_off) and both spreads
// (spread); empty when the two series do not pair.
struct SsssPairs {
    std::vector<const StudyRow*> on, off;  // by x
    std::vector<Order> against;            // on against off, per x
};
SsssPairs ssssAgainstOff(StudyResult& s, const SeriesRows& all,
                         const std::function<std::string(double)>& key);

// ---- view_angle (view_angle.cpp) ----
std::vector<StudyPoint> viewAnglePoints(bool quick);
void viewAngleConclude(report::StudyResult& s);
// The camera's angles from the slab's normal in degrees (quick: fewer), and its overrides at
// one of them.
std::vector<double> viewAngles(bool quick);
std::vector<std::string> angleCamera(double deg);

// ---- temporal (temporal.cpp) ----
std::vector<StudyPoint> temporalPoints(bool quick);
void temporalConclude(report::StudyResult& s);

// ---- flicker (flicker.cpp) ----
std::vector<StudyPoint> flickerPoints(bool quick);
void flickerConclude(report::StudyResult& s);

// ---- collision (collision.cpp) ----
std::vector<StudyPoint> collisionPoints(bool quick);
void collisionConclude(report::StudyResult& s);

// ---- ambient_occlusion (ambient_occlusion.cpp) ----
std::vector<StudyPoint> ambientOcclusionPoints(bool quick);
void ambientOcclusionConclude(report::StudyResult& s);

// ---- emissive_light, emissive_occluder (emissive_light.cpp) ----
std::vector<StudyPoint> emissiveLightPoints(bool quick);
void emissiveLightConclude(report::StudyResult& s);
std::vector<StudyPoint> emissiveOccluderPoints(bool quick);
void emissiveOccluderConclude(report::StudyResult& s);

// ---- subpixel_emitters (subpixel_emitters.cpp) ----
std::vector<StudyPoint> subpixelEmittersPoints(bool quick);
void subpixelEmittersConclude(report::StudyResult& s);
// The glowing ball's diameter on screen (pixels): the x of a point of its scene.
double subpixelEmitterPixels(const LoadedScene& s);

// ---- atmosphere (atmosphere.cpp) ----
std::vector<StudyPoint> atmospherePoints(bool quick);
void atmosphereConclude(report::StudyResult& s);

// ---- body_sphere (body_sphere.cpp) ----
std::vector<StudyPoint> bodySpherePoints(bool quick);
void bodySphereConclude(report::StudyResult& s);
// The x of a point: the ball's level-set sphere's radius on screen, pixels.
double bodySphereRadiusPixels(const LoadedScene& s);

// ---- methods (methods.cpp) ----
std::vector<StudyPoint> methodsPoints(bool quick);
void methodsConclude(report::StudyResult& s);

}  // namespace twinrender::app::study
