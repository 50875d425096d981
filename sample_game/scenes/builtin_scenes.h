#pragma once
// Scenes the project builds in code, so the default run needs no files.
#include <string>
#include <vector>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::sample {

// Room x in [-1,1], y in [0,2], z in [-1,1], open towards +z where the camera stands.
// Red wall at x = -1, green at x = +1, white floor, ceiling and back wall, a short and a tall box,
// a spot light near the ceiling pointing down.
struct CornellLayout {
  static constexpr float kSpotIntensity = 6.0f;  // W/sr (glTF units used directly)
  static constexpr float kSpotHeight = 1.9f;
  static constexpr float kSpotOuterDeg = 40.0f;
  static constexpr float kSpotInnerDeg = 25.0f;
  static constexpr float kWhite = 0.75f;
  // "cornell-emissive": the spot replaced by an emissive quad under the ceiling (two-sided, as every
  // emitter), of about the spot's power downwards: pi x (2 x 0.25)^2 x 11 = 8.6 W against the spot's 8.8.
  static constexpr float kEmitterHalfSize = 0.25f;  // m
  static constexpr float kEmitterHeight = 1.98f;    // m
  static constexpr float kEmitterRadiance = 11.0f;  // W/(m^2 sr)
};

// "showcase" (the main job's scene): the Cornell box of "cornell-dynamic" (a box sliding, a box turning)
// with the spot turned into an uplight at the front, sliding from side to side: it lights the ceiling,
// and the ceiling the room, so most of the light on screen is bounce light.
struct ShowcaseLayout {
  static constexpr glm::vec3 kUplight{-0.5f, 0.05f, 0.5f};  // front left, clear of the sliding box
  static constexpr float kUplightSway = 0.35f;               // m, along x
  static constexpr float kUplightIntensity = 20.0f;  // W/sr
  static constexpr float kUplightOuterDeg = 25.0f;  // the ceiling only
  static constexpr float kUplightInnerDeg = 15.0f;
};

// Two rooms, x in [-2, 0] and [0, 2], y in [0, 2], z in [-1, 1], with a shared wall at x = 0 thinner
// than two voxels at the default resolution; the spot in room A, the camera in room B facing the wall.
// "two-rooms" is closed, "two-rooms-door" has a doorway: the leak test (docs/QUALITY.md).
struct TwoRoomsLayout {
  static constexpr float kWallThickness = 0.05f;  // m; a voxel is 4.4 m / 128 = 0.034 m at 128^3
};

// "street" (sample_game/scenes/street.cpp): a straight street 400 m long, x in [-200, 200], between two
// rows of building blocks, under a sun; the camera at eye height near the west end looking east. A
// world far larger than a room: a voxel volume over all of it has 3 m voxels at 128^3. "street-near" is
// the same view with only the blocks and ground that end within kNearReach of the camera along the
// street. --animate street-flight flies the camera down the street at kFlightSpeed.
struct StreetLayout {
  static constexpr float kHalfLength = 200.0f;  // m, along x
  static constexpr float kHalfWidth = 6.0f;     // m: the facades at z = +-6
  static constexpr float kBlockDepth = 10.0f;   // m, across the street
  static constexpr float kBlockLength = 20.0f;  // m, along it, with an alley of kAlley after each
  static constexpr float kAlley = 4.0f;
  static constexpr glm::vec3 kCamera{-180.0f, 1.7f, 0.0f};
  static constexpr float kCameraYawDeg = 15.0f; // turned from east towards north
  static constexpr float kNearReach = 40.0f;    // m east of the camera that street-near keeps
  static constexpr glm::vec3 kSunDirection{0.35f, -0.75f, 0.55f};  // where the light goes: from over the north row
  static constexpr float kSunIntensity = 1.5f;  // lux as glTF has it, used as W/m^2
  static constexpr float kFlightSpeed = 10.0f;   // m/s
  static constexpr float kFlightLength = 360.0f;  // m east of the camera, then back
};

bool isBuiltinScene(const std::string& name);
const std::vector<std::string>& builtinSceneNames();   // what --scene NAME takes besides a file
const std::vector<std::string>& animatedSceneNames();  // what --animate takes (buildAnimatedScene)
// One mesh entity of a built-in scene: transform, mesh, a diffuse material of `albedo`, a name, and the
// static or dynamic tag.
scene::Entity addSceneMesh(ecs::World& world, scene::AssetStore& assets, scene::MeshData mesh, const glm::vec3& albedo,
                           const scene::Transform& transform, bool dynamic, const char* name);
// Builds `name` (builtinSceneNames()) into the world; adds a camera.
void buildBuiltinScene(const std::string& name, ecs::World& world, scene::AssetStore& assets);

void buildTwoRooms(bool doorway, ecs::World& world, scene::AssetStore& assets);
void buildStreet(bool nearOnly, ecs::World& world, scene::AssetStore& assets);
void addStreetFlight(ecs::World& world);  // --animate street-flight: the camera's scripted flight

// Scripted benchmark scenes (--animate): the Cornell box with
//  static           nothing moving;
//  moving-spot      the spot sliding back and forth over the floor;
//  rotating-object  a two-coloured object (red and blue halves) turning under the spot;
//  walking-fox      the glTF fox walking on the floor (needs `sharedScenesDir`/Fox.glb);
//  fox-and-spot     the walking fox under the moving spot (the soak scene, scripts/soak.sh);
//  fox-spot-light-on  fox-and-spot, and a second spot switched on at kSecondLightOnAt seconds (the GI
//                   budget's load change, scripts/budget_run.sh);
// or, not a Cornell box, street-flight: the street with its camera flying down it and back.
// Returns an empty string on success, else the problem.
constexpr double kSecondLightOnAt = 4.0;  // seconds of scripted time (frame 240 of a headless run)
std::string buildAnimatedScene(const std::string& name, ecs::World& world, scene::AssetStore& assets,
                               const std::string& sharedScenesDir);

// When a loaded scene has neither punctual lights nor emissive surfaces it would render black; add a
// directional "default sun" instead (and say so). Returns true when a light was added.
bool addDefaultLightIfUnlit(ecs::World& world);

}  // namespace dyngi::sample
