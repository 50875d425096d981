#pragma once
// Analytic light evaluation on the CPU: the single definition of dyngi's light units. The GLSL in
// shaders/shared/lighting.glsl implements the same formulas; tests check the renderer against these.
#include <glm/glm.hpp>

#include "dyngi/engine/scene/components.h"

namespace dyngi::scene {

// glTF's recommended spot cone attenuation.
float spotFalloff(float cosAngle, float innerConeAngle, float outerConeAngle);
// glTF's recommended range window (1 when range <= 0).
float rangeWindow(float distance, float range);

// Irradiance (radiometric, same units as Light::intensity x color) that a light at world-space
// `lightPos` pointing along `lightDir` delivers to a surface point `p` with unit normal `n`,
// ignoring shadows.
glm::vec3 directIrradiance(const Light& light, const glm::vec3& lightPos, const glm::vec3& lightDir,
                           const glm::vec3& p, const glm::vec3& n);

}  // namespace dyngi::scene
