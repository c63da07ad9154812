// The atmosphere model of core/atmosphere.cpp, line for line (see core/atmosphere.h): a shell
// between radii uShell.x and uShell.y about the origin, density exp(-max(h, 0) / uShell.z) at
// height h above the inner sphere, Henyey-Greenstein phase g = uShell.w; `steps` midpoint
// steps along the view ray and along each sun path, the view transmittance integrated exactly
// over each step at its midpoint's density. The sun is the frame's light (common.glsl).

uniform vec4 uShell;       // inner radius, outer radius, scale height (scene units), phase g
uniform vec3 uScattering;  // sigma_s at the inner sphere, per scene unit
uniform vec3 uAbsorption;  // sigma_a at the inner sphere, per scene unit
uniform int uSteps;

// No end point: the ray meets no surface (core's INFINITY).
const float ATMOSPHERE_NO_END = 3.0e38;

// The ray's entry t0 and exit t1 of the sphere of `radius` about the origin; false when it
// misses. The discriminant from the distance of the closest point, which keeps its precision
// for a far camera.
bool raySphere(vec3 origin, vec3 direction, float radius, out float t0, out float t1) {
    float b = dot(origin, direction);
    vec3 closest = origin - b * direction;
    float disc = radius * radius - dot(closest, closest);
    t0 = 0.0;
    t1 = 0.0;
    if (disc < 0.0) return false;
    float s = sqrt(disc);
    t0 = -b - s;
    t1 = -b + s;
    return true;
}

float atmosphereDensity(vec3 x) {
    return exp(-max(length(x) - uShell.x, 0.0) / uShell.z);
}

float henyeyGreenstein(float g, float cosTheta) {
    float d = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * 3.14159265358979 * d * sqrt(d));
}

// The transmittance from x toward the sun to the shell's exit; 0 in the inner sphere's shadow.
vec3 sunTransmittance(vec3 x, vec3 toSun) {
    float s0, s1;
    if (raySphere(x, toSun, uShell.x, s0, s1) && s1 > 0.0) return vec3(0.0);
    if (!raySphere(x, toSun, uShell.y, s0, s1) || s1 <= 0.0) return vec3(1.0);
    float du = s1 / float(uSteps);
    float depth = 0.0;
    for (int j = 0; j < uSteps; ++j) depth += atmosphereDensity(x + (float(j) + 0.5) * du * toSun);
    vec3 extinction = uScattering + uAbsorption;
    return exp(-extinction * depth * du);
}

// Where the ray first meets the sphere of `radius` at t >= 0; ATMOSPHERE_NO_END when it does
// not (or starts inside it).
float sphereEntry(vec3 origin, vec3 direction, float radius) {
    float t0, t1;
    if (!raySphere(origin, direction, radius, t0, t1) || t0 < 0.0) return ATMOSPHERE_NO_END;
    return t0;
}

// The ray origin + t direction (unit; origin relative to the shell's centre) from t = 0 to
// `end`: its transmittance and in-scatter (linear radiance).
void integrateAtmosphere(vec3 origin, vec3 direction, float end, out vec3 transmittance,
                         out vec3 inscatter) {
    transmittance = vec3(1.0);
    inscatter = vec3(0.0);
    vec3 toSun = -light.xyz;
    vec3 sunIrradiance = lightColor.rgb * light.w;
    float t0, t1;
    if (!raySphere(origin, direction, uShell.y, t0, t1)) return;
    t0 = max(t0, 0.0);
    t1 = min(t1, end);
    if (!(t1 > t0)) return;
    float dt = (t1 - t0) / float(uSteps);
    vec3 extinction = uScattering + uAbsorption;
    float phase = henyeyGreenstein(uShell.w, dot(toSun, direction));
    for (int i = 0; i < uSteps; ++i) {
        vec3 x = origin + (t0 + (float(i) + 0.5) * dt) * direction;
        float rho = atmosphereDensity(x);
        vec3 stepT = exp(-extinction * rho * dt);
        vec3 scattered = uScattering * rho * phase * sunIrradiance * sunTransmittance(x, toSun);
        // The step's in-scatter with its transmittance integrated exactly at constant density:
        // (1 - exp(-sigma_t dt)) / sigma_t, dt where nothing attenuates.
        for (int c = 0; c < 3; ++c) {
            float sigma = extinction[c] * rho;
            float len = sigma > 0.0 ? (1.0 - stepT[c]) / sigma : dt;
            inscatter[c] += transmittance[c] * scattered[c] * len;
        }
        transmittance *= stepT;
    }
}
