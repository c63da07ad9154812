// realtime.particles.halo_pixels (realtime/halo_pass.cpp): one window-aligned quad per sphere
// impostor projected smaller than subpixel.x pixels in radius that emits, carrying its emitted
// flux as a Gaussian halo. The flux is its projected area pi rho^2 (pixels) times its emission
// (the emission map at its uv plus its glow); the Gaussian has the disc's own spread,
// sigma = rho / sqrt(2) (a disc of radius rho has that second moment, so the halo has the
// disc's peak radiance), at least 0.7 px, where a Gaussian sampled at the pixel centres still
// sums to 1 within 0.03 % wherever it lies. Every other particle's quad is dropped, and with
// BODY_MASK (body_mask.glsl) those of the bodies drawn as one sphere.
#include "common.glsl"
#include "convert.glsl"
#include "particles.glsl"
#include "textures.glsl"
#ifdef BODY_MASK
#include "body_mask.glsl"
#endif

flat out vec3 vFlux;         // projected area (pixels^2) times emission (linear RGB)
flat out vec2 vCentre;       // the centre in window coordinates (pixels)
flat out float vSigma;       // pixels
flat out float vFrontDepth;  // eye depth of the sphere's point nearest the eye

// The Gaussian's reach in sigmas: beyond 4 it holds exp(-8) = 3e-4 of the flux.
const float REACH = 4.0;
const float MIN_SIGMA = 0.7;

void main() {
    int particle = gl_VertexID / 6;
    vec2 corner = QUAD_CORNERS[gl_VertexID % 6];
    Particle p = particles[particle];
    vec3 c = mat3(viewFromWorld) * p.positionRadius.xyz;
    float r = p.positionRadius.w;
    float d = length(c);
    float rho = c.z < 0.0 ? r * pixelsPerUnitAt(-c.z) : subpixel.x;
    vec3 emission = c.z < 0.0 && rho < subpixel.x && d > r
                        ? sampleTexture(materials[toIndex(p.glowMaterial.w)].emission,
                                        vec2(p.normalU.w, p.dudxV.w)) + p.glowMaterial.rgb
                        : vec3(0.0);
#ifdef BODY_MASK
    if (bodyReplaced(toIndex(p.dvdxBody.w))) emission = vec3(0.0);
#endif
    if (emission == vec3(0.0)) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: not drawn
        vFlux = vec3(0.0);
        return;
    }
    vec4 clip = clipFromView * vec4(c, 1.0);
    vCentre = (clip.xy / clip.w * 0.5 + 0.5) * viewport.xy;
    vSigma = max(rho / sqrt(2.0), MIN_SIGMA);
    vFlux = 3.14159265 * rho * rho * emission;
    vFrontDepth = -c.z * (1.0 - r / d);
    // The quad reaches every pixel centre within REACH sigmas of the centre.
    vec2 window = vCentre + corner * (REACH * vSigma + 0.5);
    gl_Position = vec4(window * viewport.zw * 2.0 - 1.0, 0.0, 1.0);
}
