// Textures as linear-RGB float images, sampled the way an OpenGL sampler with GL_LINEAR,
// GL_REPEAT in u and GL_CLAMP_TO_EDGE in v samples them, so both renderers read the same
// values. Constants are 1x1 images; procedurals are baked once at load into images of their
// own resolution; image files are read through OpenImageIO (8-bit files are sRGB-decoded).
//
// Procedurals ("procedural:NAME"):
//   none          black
//   latlong_grid  grey with dark lines every 15 degrees and a red meridian at u = 0
//   checker       16 x 8 checker of two greys
//   continents    fixed-seed value-noise land (green-brown) and sea (blue)
//   city_lights   warm dots on the land of "continents", black elsewhere
//   lava          fixed-seed value-noise dark crust with glowing cracks
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/image.h"
#include "core/scene.h"

namespace twinrender::core {

class Texture {
  public:
    Texture() = default;
    explicit Texture(Image rgb);  // channels R, G, B, linear

    // Builds the texture; throws InputError with source.where for an unknown procedural or an
    // unreadable file.
    static Texture load(const TextureSource& source);

    glm::vec3 sample(glm::vec2 uv) const;
    const Image& image() const { return mImage; }
    bool isConstant() const { return mImage.width() == 1 && mImage.height() == 1; }

  private:
    Image mImage;
};

struct Material {
    std::string name;
    Texture diffuse;
    Texture specular;
    Texture emission;
    Texture cityLights;
    float shininess = 32.0f;
};

// Loads every material of the scene (in Scene::materials order).
std::vector<Material> loadMaterials(const Scene& scene);

}  // namespace twinrender::core
