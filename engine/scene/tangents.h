#pragma once
// Vertex attributes that glTF files may leave out, derived from the triangles.
#include <cstdint>
#include <span>

#include <facet/scene/scene.h>

namespace facet {

// Smooth per-vertex normals: the sum of the unnormalised face normals of the
// triangles using each vertex (so larger faces weigh more), normalised. Vertices
// that no non-degenerate triangle touches get +Z. `indices` is a triangle list
// indexing `vertices`; triangles with an index out of range are skipped.
void generate_normals(std::span<Vertex> vertices, std::span<const uint32_t> indices);

// Per-vertex tangents from the uv derivatives of each triangle, summed per vertex,
// made orthogonal to the vertex normal (Gram-Schmidt) and normalised. w is the glTF
// handedness: bitangent = cross(normal, tangent.xyz) * w. Expects unit normals.
void generate_tangents(std::span<Vertex> vertices, std::span<const uint32_t> indices);

// The same from uv set `uv_set` (0: Vertex::uv, 1: Vertex::uv1), the one the normal
// texture is sampled with.
void generate_tangents_for(std::span<Vertex> vertices, std::span<const uint32_t> indices, uint32_t uv_set);

// Primitive bounds from its vertices' positions.
void set_bounds(Primitive& primitive, std::span<const Vertex> vertices);

}  // namespace facet
