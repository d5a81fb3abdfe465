// Blinn-Phong shading of every lit surface (cloth, masses, pins): one directional light plus a
// sky/ground ambient term. Two-sided: a back face uses the flipped normal and a tinted colour.
in vec3 world_position;
in vec3 normal;
in vec2 texture_coordinates;
in vec3 surface_colour;
uniform bool use_texture;
uniform sampler2D cloth_texture;
uniform vec3 light_direction;  // unit, from the surface towards the light
uniform vec3 eye_position;
uniform vec3 back_tint;        // multiplies the colour of back faces
uniform float shininess;
uniform float specular_strength;
out vec4 colour;

void main() {
  vec3 n = normalize(normal);
  vec3 albedo = surface_colour;
  if (use_texture) albedo *= texture(cloth_texture, texture_coordinates).rgb;
  if (!gl_FrontFacing) {
    n = -n;
    albedo *= back_tint;
  }
  vec3 to_eye = normalize(eye_position - world_position);
  vec3 halfway = normalize(light_direction + to_eye);
  float diffuse = max(dot(n, light_direction), 0.0);
  float specular = diffuse > 0.0 ? pow(max(dot(n, halfway), 0.0), shininess) : 0.0;
  float ambient = mix(0.30, 0.42, 0.5 + 0.5 * n.z);  // brighter when facing the sky
  vec3 lit = albedo * (ambient + 0.75 * diffuse) + specular_strength * specular * vec3(1.0);
  colour = vec4(lit, 1.0);
}
