#version 330 core
// Instanced spheres (masses, fixed point, pins): one unit sphere scaled and moved per instance.
layout(location = 0) in vec3 unit_position;  // on the unit sphere: also the outward normal
layout(location = 1) in vec4 centre_radius;  // per instance: centre (m), radius (m)
layout(location = 2) in vec3 instance_colour;
uniform mat4 view_projection;
out vec3 world_position;
out vec3 normal;
out vec2 texture_coordinates;
out vec3 surface_colour;

void main() {
  world_position = centre_radius.xyz + centre_radius.w * unit_position;
  normal = unit_position;
  texture_coordinates = vec2(0.0);
  surface_colour = instance_colour;
  gl_Position = view_projection * vec4(world_position, 1.0);
}
