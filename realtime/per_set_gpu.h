// The real-time renderer's per-particle-set work on the GPU (realtime.per_set = "gpu"), where a
// real-time renderer does it: the particles' raw attributes are uploaded as they are, a neighbour
// grid is built from them by counting sort (atomic counts, a prefix sum, a scatter, each cell
// sorted by index), and compute passes over the grid give what the CPU path computes with
// core::ColourField: the impostor radii (impostor_radius.h), the exact occlusion culling
// (occlusion_culling.h), the field normal models (field_normal.h) and the ellipsoids
// (anisotropy.h). Per frame, compute passes mark the drawn particles (kept from the frame
// before where nothing they depend on changed), pack them (camera-relative, subtracted in
// double) into the storage buffers the draw passes read, and write the draw counts into
// indirect draw commands: nothing is read back. The gradient normals are gathered through the
// grid (gatherGradient). Sums over the grid run in a fixed order, so the
// results do not depend on scheduling. The walks read the grid as buffer textures (per_set.glsl
// says why). shaders/per_set_*.comp (a file per group of stages), per_set_stages.glsl,
// per_set.glsl, scan.comp.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/particles.h"
#include "realtime/anisotropy.h"
#include "realtime/gl/buffer.h"
#include "realtime/gl/buffer_texture.h"
#include "realtime/gl/texture.h"
#include "realtime/gl/timer_query.h"
#include "realtime/particle_set_key.h"
#include "realtime/program_variants.h"
#include "realtime/settings.h"
#include "realtime/shader_library.h"

namespace twinrender::realtime {

// What a frame needs of the per-set work.
struct PerSetRequest {
    ParticleSettings particles;
    bool cull = false;      // occlusion culling (spheres)
    bool droplets = false;  // small droplets drawn as ellipsoids (particles.droplet_atoms)
};

// What a frame asks of the packed draw lists.
struct FrameRequest {
    glm::dvec3 camera{0.0};
    double nearReach = 0.0;  // renderer.cpp's cullingIsExact: the near plane's ball
};

// The most texels a set of `particles` has GpuPerSet view as one buffer texture (its grid's
// cells), for the device's GL_MAX_TEXTURE_BUFFER_SIZE.
std::size_t perSetTexels(std::size_t particles);

// The Attributes buffer's words for `particles`, as GpuPerSet lays them out
// (shaders/per_set.glsl: each attribute a run of n values, those a set lacks zero); the
// doctor's check of the upload compares the buffer with them.
std::vector<std::uint32_t> attributeWords(const core::ParticleSet& particles);

// What a frame with these settings asks of the per-set work (per_set = "gpu").
PerSetRequest perSetRequest(const Settings& settings);

// The compute programs GpuPerSet uses for `request`.
std::vector<ProgramVariant> perSetPrograms(const PerSetRequest& request);
// Throws gl::Error where the driver lays out a variable of a per-set program's blocks (the
// Header's commands and counters, the packed particles) at another byte or
// stride than per_set_gpu.cpp writes and reads it (std430 as the C++ structs mirror it).
void checkPerSetLayouts(const gl::Program& program);
// Compiles them (set-up, like the passes'), checks their layouts and probes the stages' clock
// (stageClock()).
void compilePerSetPrograms(ProgramCache& programs, const PerSetRequest& request);

class GpuPerSet {
  public:
    // Builds what `request` needs (and remembers it for pack()) for `particles` that the last
    // sets did not (all of it for a new set, inputs compared exactly as ParticleSetKey), each
    // stage timed; returns whether anything was built. Programs are compiled through
    // `programs` on first use. With `deriveNormalsOf` (the set's bodies), the particles came
    // without normals: compute passes derive them as core::deriveNormals does (stage
    // "particle_normals"), with "field" radii for the particles they need: those the radii
    // search along, then those settled deep inside a body (interior_level) that may be drawn
    // after culling; the other settled ones keep the fallback normal, the radial direction
    // from their body's centre.
    bool update(ProgramCache& programs, const core::ParticleSet& particles,
                const PerSetRequest& request, std::span<const core::BodyInfo> deriveNormalsOf = {});

    // The frame's draw lists: the drawn particles (radius > 0, not hidden unless a sphere
    // reaches into the near plane's ball) as GpuParticle[] (and GpuEllipsoid[] with ellipsoids)
    // and their indirect draw commands. Timed as "pack".
    void pack(ProgramCache& programs, const FrameRequest& frame);

    // realtime.particles.body_sphere_pixels, after pack(): counts into `bodyMask`
    // (shaders/body_mask.glsl, its counts zero, a word per body) the drawn particles of the
    // bodies it marks replaced, and the droplets among them (REPLACED). Timed as "pack".
    void countReplaced(ProgramCache& programs, const gl::Buffer& bodyMask);

    // normal = "gradient": the colour field's gradient at the surface point of each pixel of
    // `surface` (the G-buffer's eye depth, +inf where nothing is), summed over every particle
    // whose support covers it through the grid (shaders/gradient_gather.comp), written into
    // `gradient` (RGBA32F, the surface's size). The frame's uniforms must be bound. With
    // `bodyMask` (body_mask.glsl) the particles of the bodies it marks replaced are left out:
    // their pixels take 0 without a walk, or, where their kernels may reach another body's
    // surface (`testKernelBodies`), every kernel's body is tested.
    void gatherGradient(ProgramCache& programs, const gl::Texture& surface, gl::Texture& gradient,
                        const glm::dvec3& camera, const gl::Buffer* bodyMask = nullptr,
                        bool testKernelBodies = false);
    // Whether the last pack() kept the marks of the frame before (the drawn particles and their
    // prefix: nothing they depend on changed) and redid only the records.
    bool marksReused() const { return mMarksReused; }
    // After a frame has been drawn (the renderer's read-back): reads what later frames decide
    // with, once per set (the levels' boxes, for the marks' reuse). Waits for the frame.
    void afterFrame();
    // A level's box and largest h (LAYOUT's), as NEAR_BOUND reads them.
    struct LevelBox {
        glm::dvec3 low, high;
        double hMax = 0.0;
    };

    const gl::Buffer& particles() const { return *mParticles; }
    // One GpuEllipsoid per drawn particle where ellipsoidsDrawn() (shape = "ellipsoid", the
    // droplets' among them).
    const gl::Buffer& ellipsoids() const { return *mEllipsoids; }
    bool ellipsoidsDrawn() const { return mModels == 2; }
    // Spheres with droplets: the droplets are drawn apart, the first of particles() (the
    // particles' draw starts after them) with dropletEllipsoids() (GpuEllipsoid[] from the
    // first droplet's, then more), their count in the command at dropletDrawOffset() (the CPU
    // does not learn it).
    bool dropletsApart() const { return mRequest.droplets && mModels != 2; }
    const gl::Buffer& dropletEllipsoids() const { return mDroplets; }
    // glDrawArraysIndirect commands: the particles' at particleDrawOffset(), the droplets' at
    // dropletDrawOffset() (bytes).
    const gl::Buffer& drawCommands() const { return mHeader; }
    static std::size_t particleDrawOffset() { return 16; }
    static std::size_t dropletDrawOffset();
    std::size_t capacity() const { return mCount; }
    // Wall-clock milliseconds of the last update's upload (0 when the set was kept): the
    // attributes written into the staging buffer (the device's copy from it is timed in
    // "grid"), the set's key compared and kept.
    double uploadMs() const { return mUploadMs; }

    // The stages run since the last call, milliseconds each ("grid", "particle_normals", "radius",
    // "cull", "field_normals", "anisotropy", "pack"), by stageClock(). With timer
    // queries this waits for their results: call it after the frame.
    std::map<std::string, double> takeTimings();
    // How the stages are timed: GL timer queries where the device's see compute dispatches
    // (nothing waits between stages; a probe once per renderer, when the programs are compiled
    // or on the first update), else the wall clock
    // from a stage's first command to a glFinish after its last (llvmpipe's queries read 1 ns
    // around compute).
    enum class StageClock { Queries, Finish };
    StageClock stageClock() const { return mStageClock.value_or(StageClock::Finish); }
    void setStageClock(StageClock clock) { mStageClock = clock; }  // instead of the probe
    // Read back after the frame (waits): the drawn particles (droplets drawn apart among them).
    std::uint32_t drawnCount() const;
    std::uint32_t dropletCount() const;  // the droplets of the set (0 without droplets)

    // Read back, for tests: per particle of the last set.
    std::vector<float> radii() const;
    std::vector<glm::vec3> normals() const;               // as update() left them
    std::vector<std::uint32_t> visibleParticles() const;  // not hidden, as unoccludedParticles()
    std::vector<glm::vec4> models() const;                // 3 per particle
    // The droplets' first particles (ascending) and their ellipsoids (droplets.h).
    std::vector<std::pair<std::uint32_t, Ellipsoid>> droplets() const;
    // The stages' own records, for the doctor's stage checks (self_check.h): the grid
    // (GATHER's order), each particle's flags (shaders/per_set_stages.glsl's bits) and, after
    // pack(), the exclusive prefix of the drawn particles (n + 1).
    struct Grid {
        std::uint32_t totalCells = 0;
        std::vector<std::uint32_t> sorted;     // particle per grid slot
        std::vector<std::uint32_t> cellStart;  // per cell its first slot, then the count
        std::vector<std::uint32_t> entryIndex;
        std::vector<glm::vec3> entryPosition;
    };
    Grid grid() const;
    // The Attributes buffer's words as the stages left them (attributeWords()'s layout).
    std::vector<std::uint32_t> attributes() const;
    // The grid's levels as H_MIN, LEVELS and LAYOUT left them in the Header: the least h, the
    // cells of all levels, and per level (MAX_LEVELS, per_set_layout.h) its particles' box,
    // count and largest h, its grid's corner and cell size, and its cells along x, y, z and
    // first cell.
    struct Level {
        glm::vec3 low{0.0f}, high{0.0f};
        std::uint32_t count = 0;
        float hMax = 0.0f;
        glm::vec4 originCell{0.0f};
        glm::ivec4 dims{0};
    };
    struct Levels {
        float hMin = 0.0f;
        std::uint32_t totalCells = 0;
        std::vector<Level> levels;
    };
    Levels levels() const;
    std::vector<std::uint32_t> flags() const;
    std::vector<std::uint32_t> drawnPrefix() const;

  private:
    void upload(const core::ParticleSet& particles);
    void fitDroplets(ProgramCache& programs, const ParticleSettings& settings);
    void buildGrid(ProgramCache& programs);
    void uploadBodies(std::span<const core::BodyInfo> bodies);
    // NORMALS over the walk list (`listed`) or every particle.
    void deriveNormals(ProgramCache& programs, bool listed);
    // Exclusive prefix sum of `count` uints of `data` from `offset` (with `cells`: of the
    // grid's cells, at most `count`, their number read on the GPU).
    void scan(ProgramCache& programs, const gl::Buffer& data, std::size_t offset, std::size_t count,
              bool cells = false);
    void bindStorage() const;
    void clearWalks();  // empties the walk list (shaders/per_set_stages.glsl's appendWalk)
    void timed(const char* stage, const auto& work);
    // What the marks were made with (pack()).
    struct Marks {
        bool cull = false, dropletsApart = false;
        // No sphere reached into the near plane's ball (NEAR_BOUND's bound on the CPU, or NEAR's
        // answer read by afterFrame()).
        bool nearFree = false;
    };
    // NEAR, MARK, KERNELS and the scans of the draw lists.
    void mark(ProgramCache& programs, const FrameRequest& frame, const Marks& marks);
    // Poison mode: throws gl::Error naming the stage and the buffer where a stage wrote past a
    // buffer's end (gl::Buffer::overrun); nothing outside it. First, gl::checkConversions.
    void checkOverruns(const char* stage) const;

    std::size_t mCount = 0, mMaxCells = 0;
    gl::StagingBuffer mStaging;  // upload()'s attributes, copied by buildGrid
    std::size_t mStagedBytes = 0;
    double mUploadMs = 0.0;
    ParticleSetKey mKey;
    bool mBuilt = false;
    // What has been built for the current set (std::nullopt: not yet).
    std::optional<ParticleSettings> mRadiusSettings;  // droplet_atoms 0 when not requested
    bool mCulled = false;
    // The particle normals: the set's own; or derived for none yet, for INTERIOR's list (the
    // particles it settled keep a fallback normal), for those and the settled ones that may be
    // drawn after culling, or for every particle.
    enum class Normals { Given, None, Listed, Drawn, All };
    Normals mNormals = Normals::Given;
    PerSetRequest mRequest;                          // the last update's, for pack()
    std::optional<ParticleSettings> mModelSettings;  // normal model and shape they were for
    int mModels = 0;                                 // 0 none, 1 field normals, 2 ellipsoids
    gl::Buffer mAttributes, mHeader, mCells, mCellOf, mSorted, mEntries, mRadii, mFlags, mBlockSums,
        mDirections;
    std::optional<gl::Buffer> mModelBuffer, mDrawLists, mParticles, mEllipsoids;
    // Per droplet its GpuEllipsoid (the droplets' draw reads them), then per droplet its
    // FieldNormal model, each region sized for the most droplets a set may hold.
    gl::Buffer mDroplets;
    gl::Buffer mWalks;        // the walk list, then the next (shaders/per_set_stages.glsl)
    gl::Buffer mDropletWork;  // the sparse particles' list, their clusters (DropletWork)
    gl::Buffer mCullSpheres;  // per grid slot: position, radius (culling)
    gl::Buffer mBodies;       // deriveNormals: 2 vec4 per body, its centre and pole axis
    // Per grid slot, the culling's near shell as INTERIOR found it (shaders/per_set_radius.comp),
    // for the radii of the current settings when mNearMasksFound.
    gl::Buffer mNearMasks;
    gl::Buffer mPlaceholder;  // 16 bytes, bound where a stage's block has no buffer
    bool mNearMasksFound = false;
    // What the walks read as buffer textures (shaders/per_set.glsl): the grid's entries (as
    // floats, and as words for the indices), cell offsets, the culling's spheres and directions.
    gl::BufferView mEntryTexels, mEntryWordTexels, mCellTexels, mCullSphereTexels, mDirectionTexels;
    std::optional<Marks> mMarks;  // the marks in the buffers, for the current set's answers
    bool mMarksReused = false;
    std::optional<std::vector<LevelBox>> mLevelBoxes;  // read by afterFrame()
    std::map<std::string, double> mTimings;            // since the last takeTimings()
    std::optional<StageClock> mStageClock;
    std::vector<std::pair<const char*, gl::TimerQuery>> mQueries;  // not yet read
};

}  // namespace twinrender::realtime
