// Fixed-function state and draw calls, as typed values: the passes in realtime/ set state
// and draw through these and never touch GL enums.
#pragma once

#include <cstddef>

namespace twinrender::realtime::gl {

enum class DepthTest {
    Off,
    Less,     // standard and logarithmic depth: smaller is nearer
    Greater,  // reversed-Z: larger is nearer
};

// The clip-space depth range (glClipControl): reversed-Z wants [0, 1] so that float depth
// keeps its precision near 0.
enum class ClipDepth { MinusOneToOne, ZeroToOne };

struct PipelineState {
    DepthTest depthTest = DepthTest::Off;
    bool depthWrite = false;
    // Disables near/far clipping: impostors write their own depth and test near/far
    // themselves, so a huge far/near ratio cannot clip a quad by rounding.
    bool depthClamp = false;
    ClipDepth clipDepth = ClipDepth::MinusOneToOne;
    bool additiveBlend = false;  // dst = src + dst
};

void setPipelineState(const PipelineState& state);

// Attribute-less draws: vertex shaders fetch their data from storage buffers by gl_VertexID
// (from firstVertex up).
void drawTriangles(int vertexCount, int firstVertex = 0);
// The same with the vertex count in a buffer a compute shader wrote: `commands` holds
// glDrawArraysIndirect's {count, 1, 0, 0} at byte `offset` (4-byte aligned).
void drawTrianglesIndirect(unsigned commands, std::size_t offset);
// One triangle covering the viewport (vertex shader fullscreen.vert).
void drawFullscreenTriangle();

// Makes later texture reads see the writes of earlier draws to storage images or buffers
// (not needed between a draw into a framebuffer and sampling its textures).
void memoryBarrierAll();
// Makes later shaders (their texel fetches too), indirect draws and read-backs see a compute
// shader's storage writes.
void computeBarrier();
void finish();
// Waits until the fence `sync` (a GLsync) has signalled, flushing it first, then deletes it.
void waitAndDelete(void* sync);

struct Limits {
    long long maxStorageBlockBytes = 0;    // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
    int maxTextureSize = 0;                // GL_MAX_TEXTURE_SIZE
    long long maxTextureBufferTexels = 0;  // GL_MAX_TEXTURE_BUFFER_SIZE
    int maxViewportWidth = 0, maxViewportHeight = 0;
    // What the per-set compute passes and the passes' targets need (`twinrender doctor` lists
    // them against what the renderer uses).
    int maxStorageBindings = 0;       // GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS
    int maxComputeStorageBlocks = 0;  // GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS
    int maxComputeTextureUnits = 0;   // GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS
    int maxComputeInvocations = 0;    // GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS
    int maxComputeSharedBytes = 0;    // GL_MAX_COMPUTE_SHARED_MEMORY_SIZE
    int maxDrawBuffers = 0;           // GL_MAX_DRAW_BUFFERS
};
Limits queryLimits();

}  // namespace twinrender::realtime::gl
