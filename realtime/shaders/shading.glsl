// The shading model of core/shading.cpp, line for line: ambient x albedo x its occlusion (the
// open fraction), the light of emitting surfaces (albedo x irradiance / pi), Lambert diffuse and
// Blinn-Phong specular times the light's visibility, the emission buffer, city lights on the
// night side. Needs common.glsl and textures.glsl.

float nightFactor(vec3 normal, vec3 towardLight) {
    return clamp(0.5 - 5.0 * dot(normal, towardLight), 0.0, 1.0);
}

vec3 shadeSurface(int material, vec3 normal, vec3 toEye, vec2 uv, vec3 emission,
                  float visibility, float ambientOcclusion, vec3 irradiance) {
    MaterialRecord m = materials[material];
    vec3 l = -light.xyz;
    vec3 radiance = lightColor.rgb * light.w;
    vec3 albedo = sampleTexture(m.diffuse, uv);
    float nl = dot(normal, l);
    vec3 color = albedo * lightColor.rgb * lightColor.w * ambientOcclusion;
    color += albedo * irradiance * (1.0 / 3.14159265358979);
    if (nl > 0.0) {
        vec3 halfway = normalize(l + toEye);
        float nh = max(dot(normal, halfway), 0.0);
        vec3 specular = sampleTexture(m.specular, uv) * pow(nh, m.params.x);
        color += (albedo * nl + specular) * radiance * visibility;
    }
    color += emission;
    color += sampleTexture(m.cityLights, uv) * nightFactor(normal, l);
    return color;
}
