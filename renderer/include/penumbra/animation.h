// Animation playback: what a scene loaded with LoadOptions::playback keeps of its glTF
// animations (Rig: the node tree, the channels, the skins), and the pose it stands in at a time
// (Pose: every instance's world matrix, every skin's joint matrices, every mesh's morph weights),
// which Renderer::setPose applies on the GPU. Core code, no GL: the same channel sampling poses
// the CPU loader's still (LoadOptions::animation), so a played pose and a loaded one agree.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "penumbra/error.h"

namespace penumbra {

// One animation channel's sampler (glTF 3.11): key times (seconds, ascending) and values,
// `width` floats a key (4 for rotations, the morph target count for weights; CUBICSPLINE keys
// hold in-tangent, value, out-tangent).
struct AnimationCurve {
  enum class Interpolation { Linear, Step, CubicSpline };
  enum class Path { Translation, Rotation, Scale, Weights };
  int node = -1;
  Path path = Path::Translation;
  Interpolation interpolation = Interpolation::Linear;
  size_t width = 3;
  std::vector<float> times;
  std::vector<float> values;

  // The value at `time`: the ends held before the first key and after the last; rotations
  // along the shortest arc and normalised.
  std::vector<float> sample(float time) const;
};

struct Rig {
  struct Node {
    int parent = -1;
    bool hasMatrix = false;  // animations may not target a matrix node
    glm::mat4 matrix{1.0f};
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
    std::vector<float> weights;  // its mesh's morph weights at rest
  };
  struct Skin {
    std::vector<int> joints;               // nodes
    std::vector<glm::mat4> inverseBind;    // one per joint
  };
  // Per Scene mesh: the skin posing it (-1: none) and the node whose morph weights it takes
  // (-1: no morph targets). A morph-targeted mesh is one node's own (the loader does not share
  // it), since nodes animate their weights apart.
  struct MeshLink {
    int skin = -1;
    int weightsNode = -1;
  };
  std::vector<Node> nodes;
  std::vector<Skin> skins;
  std::vector<MeshLink> meshes;
  // Per Scene instance: the node it stands at and its transform under that node (an
  // EXT_mesh_gpu_instancing copy's own; the identity otherwise). A skinned instance stays at
  // the identity: its joints place it (glTF 3.7.3).
  std::vector<int> instanceNode;
  std::vector<glm::mat4> instanceLocal;
  std::vector<bool> instanceSkinned;
  // Per Scene::animations entry: its channels.
  std::vector<std::vector<AnimationCurve>> clips;
};

struct Pose {
  std::vector<glm::mat4> instanceWorld;        // per Scene instance
  std::vector<std::vector<glm::mat4>> joints;  // per skin: joint world x inverse bind
  std::vector<std::vector<float>> weights;     // per Scene mesh (empty: no morph targets)

  // Mesh `mesh`'s morph weights (empty: none) and skin `skin`'s joints (null: none, or -1).
  const std::vector<float>& weightsOf(int mesh) const;
  const std::vector<glm::mat4>* jointsOf(int skin) const;
};

// A node's local matrix from its translation, rotation and scale (glTF 3.5.3: T * R * S).
glm::mat4 composeTrs(const glm::vec3& translation, const glm::quat& rotation,
                     const glm::vec3& scale);

// The pose at `time` seconds of clip `animation` (-1: the rest pose).
Pose poseRig(const Rig& rig, int animation, float time);

// One clip's share of a blended pose (a crossfade from one animation to another).
struct PoseLayer {
  int animation = -1;  // -1: the rest pose
  float time = 0.0f;
  float weight = 1.0f;
};
// The layers' poses blended by weight, node by node (glTF's parts: translations, scales and
// morph weights linearly, rotations by normalised weighted sums); one layer is that clip's pose.
Pose poseRig(const Rig& rig, std::span<const PoseLayer> layers);

}  // namespace penumbra
