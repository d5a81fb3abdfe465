// Instanced spheres (masses, fixed point, pins): one unit sphere scaled and moved per instance.
layout(location = 0) in vec3 unit_position;  // on the unit sphere: also the outward normal
layout(location = 1) in vec4 centre_radius;  // per instance: centre (m), radius (m)
layout(location = 2) in vec3 instance_colour;
uniform mat4 view_projection;
uniform vec3 eye_position;
// m: the depth written is that of a point this much further from the eye (0 for the masses).
// The obstacle sphere is pushed back so that the cloth resting on it, whose flat triangles cut
// under its surface between the particles, is drawn in front of it; its outline is unchanged.
uniform float depth_push;
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
  if (depth_push > 0.0) {
    vec3 away = normalize(world_position - eye_position);
    vec4 pushed = view_projection * vec4(world_position + depth_push * away, 1.0);
    gl_Position.z = pushed.z / pushed.w * gl_Position.w;
  }
}
