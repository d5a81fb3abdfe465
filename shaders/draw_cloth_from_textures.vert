// The GPU cloth (question 11): each vertex fetches its position and normal from the N x N state
// textures, texel (ku, kv) holding particle k = ku + N kv. No vertex data: the CPU draws
// 6 (N-1)^2 vertices, two triangles per cell, and the vertex number gives the cell and the
// corner. A triangle that lost a spring (tearing, an addition) is moved out of view whole, so
// that it is not drawn, without the state ever being read back.
uniform sampler2D position_texture;      // xyz: position, m
uniform sampler2D normal_texture;        // xyz: unit normal
uniform usampler2D spring_mask_texture;  // bit i: the spring to neighbour i is there
uniform bool use_spring_mask;            // false: every triangle is drawn
uniform int grid_size;                   // N
uniform mat4 view_projection;
out vec3 world_position;
out vec3 normal;
out vec2 texture_coordinates;
out vec3 surface_colour;

// Cell (ku, kv) -> (ku+1, kv+1) is split along its diagonal into the triangles (00, 10, 11) and
// (00, 11, 01), counter-clockwise seen from the front, as the CPU cloth's.
const ivec2 corners[6] =
    ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

// The spring mask's bits (gpu_cloth.hpp): 0 to (ku+1, kv), 2 to (ku, kv+1), 4 to (ku+1, kv+1).
bool joined(ivec2 k, int bit) {
  return (texelFetch(spring_mask_texture, k, 0).r & (1u << bit)) != 0u;
}

// Whether the triangle still has its three springs (spring_mesh::triangle_intact).
bool triangle_intact(ivec2 cell, bool upper) {
  if (!use_spring_mask) return true;
  bool diagonal = joined(cell, 4);
  if (upper) return diagonal && joined(cell, 2) && joined(cell + ivec2(0, 1), 0);
  return diagonal && joined(cell, 0) && joined(cell + ivec2(1, 0), 2);
}

void main() {
  int cells_per_row = grid_size - 1;
  int corner = gl_VertexID % 6;
  int cell_number = gl_VertexID / 6;
  ivec2 cell = ivec2(cell_number % cells_per_row, cell_number / cells_per_row);
  ivec2 texel = cell + corners[corner];
  world_position = texelFetch(position_texture, texel, 0).xyz;
  normal = texelFetch(normal_texture, texel, 0).xyz;
  texture_coordinates = vec2(texel) / float(max(cells_per_row, 1));
  surface_colour = vec3(1.0);
  // A torn triangle: its three corners outside the view volume, so it is clipped away.
  gl_Position = triangle_intact(cell, corner >= 3) ? view_projection * vec4(world_position, 1.0)
                                                   : vec4(2.0, 2.0, 2.0, 1.0);
}
