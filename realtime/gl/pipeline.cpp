#include "realtime/gl/pipeline.h"

#include <epoxy/gl.h>

namespace twinrender::realtime::gl {

void setPipelineState(const PipelineState& state) {
    if (state.depthTest == DepthTest::Off) {
        glDisable(GL_DEPTH_TEST);
    } else {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(state.depthTest == DepthTest::Less ? GL_LESS : GL_GREATER);
    }
    glDepthMask(state.depthWrite ? GL_TRUE : GL_FALSE);
    if (state.depthClamp)
        glEnable(GL_DEPTH_CLAMP);
    else
        glDisable(GL_DEPTH_CLAMP);
    glClipControl(GL_LOWER_LEFT, state.clipDepth == ClipDepth::ZeroToOne ? GL_ZERO_TO_ONE
                                                                         : GL_NEGATIVE_ONE_TO_ONE);
    if (state.additiveBlend) {
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
    } else {
        glDisable(GL_BLEND);
    }
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
}

void drawTriangles(int vertexCount, int firstVertex) {
    if (vertexCount > 0) glDrawArrays(GL_TRIANGLES, firstVertex, vertexCount);
}

void drawTrianglesIndirect(unsigned commands, std::size_t offset) {
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commands);
    glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(offset));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

void drawFullscreenTriangle() {
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void memoryBarrierAll() {
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void computeBarrier() {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
}

void finish() {
    glFinish();
}

void waitAndDelete(void* sync) {
    const GLsync fence = static_cast<GLsync>(sync);
    GLbitfield flags = GL_SYNC_FLUSH_COMMANDS_BIT;
    while (glClientWaitSync(fence, flags, 1'000'000'000) == GL_TIMEOUT_EXPIRED) flags = 0;
    glDeleteSync(fence);
}

Limits queryLimits() {
    Limits l;
    GLint64 block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
    l.maxStorageBlockBytes = block;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.maxTextureSize);
    GLint64 texels = 0;
    glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
    l.maxTextureBufferTexels = texels;
    GLint viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    l.maxViewportWidth = viewport[0];
    l.maxViewportHeight = viewport[1];
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &l.maxStorageBindings);
    glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &l.maxComputeStorageBlocks);
    glGetIntegerv(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, &l.maxComputeTextureUnits);
    glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &l.maxComputeInvocations);
    glGetIntegerv(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, &l.maxComputeSharedBytes);
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &l.maxDrawBuffers);
    return l;
}

}  // namespace twinrender::realtime::gl
