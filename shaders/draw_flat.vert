// Geometry from CPU positions for flat passes: lines (springs, wireframe), and the cloth's
// shadow, which is the cloth squashed onto the ground along the light (with draw_ground.frag).
layout(location = 0) in vec3 position;  // m
uniform mat4 view_projection;
uniform bool project_onto_ground;
uniform float ground_height;   // m
uniform vec3 light_direction;  // unit, towards the light
out vec3 world_position;        // m, where the ground shader draws the cloth's shadow

void main() {
  vec3 p = position;
  if (project_onto_ground) p -= light_direction * (p.z - ground_height) / light_direction.z;
  world_position = p;
  gl_Position = view_projection * vec4(p, 1.0);
}
