// GpuDeformation: a played primitive's rest data on the GPU (penumbra::Deformation): its
// unposed positions, normals and tangents, joints and weights as vertex attributes, and its
// morph targets' displacements in a float texture. passes/deform_pass.cpp reads them once per
// pose and writes the posed vertices into the primitive's own buffers (transform feedback), so
// every pass draws the pose without a skinned variant of its own. Also keeps, on the CPU, what
// bounds a pose cheaply (per-joint boxes, per-target displacement ranges).
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "gl/texture.h"
#include "penumbra/scene.h"

namespace penumbra {

// deform.vert's attribute locations and its morph weights' room (uMorphWeights: vec4s).
inline constexpr int kDeformJointsLocation = 3, kDeformWeightsLocation = 4;
inline constexpr int kMaxMorphTargets = 64;

struct GpuDeformation {
  gl::VertexArray rest;  // locations 0..4: position, normal, tangent, joints, weights
  std::vector<gl::Buffer> buffers;
  gl::Texture2D morphs;  // RGBA32F: texel (target * 3 + attribute) * vertexCount + vertex
  int morphWidth = 0;    // its rows' width
  int targets = 0;       // at most kMaxMorphTargets
  bool skinned = false;
  bool tangents = false;
  int vertexCount = 0;
  int mesh = -1;  // the Scene mesh: its skin and morph weights in a Pose
  // Bounds of a pose: the rest box, each target's displacement range, and the box of the
  // vertices each joint moves (in bind space, the rest box grown by the morph range).
  Bounds restBounds;
  std::vector<Bounds> targetRange;
  std::vector<Bounds> jointBoxes;

  static Result<std::unique_ptr<GpuDeformation>> create(const Deformation& d, int mesh);
  // The primitive's box at a pose: morph weights, and its skin's joint matrices (null: none).
  Bounds posedBounds(const std::vector<float>& weights,
                     const std::vector<glm::mat4>* joints) const;
};

}  // namespace penumbra
