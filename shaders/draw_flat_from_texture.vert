// The GPU cloth's flat passes (lines; the shadow with draw_ground.frag): each vertex fetches its
// position from the N x N position texture, texel (ku, kv) holding particle k = ku + N kv. The
// lines come with their texels; the shadow's triangles, like the surface's
// (draw_cloth_from_textures.vert), from the vertex number, those that lost a spring left out.
layout(location = 0) in ivec2 texel;  // (ku, kv), for the lines
uniform sampler2D position_texture;   // xyz: position, m
uniform usampler2D spring_mask_texture;  // bit i: the spring to neighbour i is there
uniform bool use_spring_mask;            // false: every triangle is drawn
uniform bool triangles_from_vertex_id;   // true for the shadow's triangles
uniform int grid_size;                   // N
uniform mat4 view_projection;
uniform bool project_onto_ground;
uniform float ground_height;   // m
uniform vec3 light_direction;  // unit, towards the light
out vec3 world_position;        // m, where the ground shader draws the cloth's shadow

// As in draw_cloth_from_textures.vert: the two triangles of a cell, and the mask's bits 0, 2, 4.
const ivec2 corners[6] =
    ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

bool joined(ivec2 k, int bit) {
  return (texelFetch(spring_mask_texture, k, 0).r & (1u << bit)) != 0u;
}

bool triangle_intact(ivec2 cell, bool upper) {
  if (!use_spring_mask) return true;
  bool diagonal = joined(cell, 4);
  if (upper) return diagonal && joined(cell, 2) && joined(cell + ivec2(0, 1), 0);
  return diagonal && joined(cell, 0) && joined(cell + ivec2(1, 0), 2);
}

void main() {
  ivec2 k = texel;
  bool drawn = true;
  if (triangles_from_vertex_id) {
    int cells_per_row = grid_size - 1;
    int corner = gl_VertexID % 6;
    int cell_number = gl_VertexID / 6;
    ivec2 cell = ivec2(cell_number % cells_per_row, cell_number / cells_per_row);
    k = cell + corners[corner];
    drawn = triangle_intact(cell, corner >= 3);
  }
  vec3 p = texelFetch(position_texture, k, 0).xyz;
  if (project_onto_ground) p -= light_direction * (p.z - ground_height) / light_direction.z;
  world_position = p;
  // A torn triangle: its three corners outside the view volume, so it is clipped away.
  gl_Position = drawn ? view_projection * vec4(p, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
