// A calm sky: pale at the horizon (the colour the ground fades into far away), soft blue above,
// by the direction each pixel looks in (so the horizon stays level when the camera turns).
in vec2 screen_position;
uniform mat4 inverse_view_projection;
uniform vec3 horizon_colour;
uniform vec3 sky_colour;
out vec4 colour;

void main() {
  vec4 near_point = inverse_view_projection * vec4(screen_position, -1.0, 1.0);
  vec4 far_point = inverse_view_projection * vec4(screen_position, 1.0, 1.0);
  vec3 direction = normalize(far_point.xyz / far_point.w - near_point.xyz / near_point.w);
  colour = vec4(mix(horizon_colour, sky_colour, smoothstep(-0.02, 0.22, direction.z)), 1.0);
}
