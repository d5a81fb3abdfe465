// A checkered floor of tile_size tiles that fades into the horizon colour far away. Also draws
// the cloth's shadow: the same floor, darker. (The round shadows under the masses are drawn over
// it by draw_blob_shadow: a loop over them here made every ground pixel cost twice as much on
// a software rasteriser, even with no mass.)
in vec3 world_position;
uniform float light_fraction;  // 1 for the ground in the light, less in the cloth's shadow
uniform float tile_size;  // m
uniform vec3 light_tile_colour;
uniform vec3 dark_tile_colour;
uniform vec3 horizon_colour;
uniform vec2 fade_centre;  // m, where the floor is fully visible
uniform float fade_start;  // m, distance from fade_centre where fading begins
uniform float fade_end;    // m, distance where only the horizon colour is left
out vec4 colour;

// Square wave of period 2 (0 on [0, 1), 1 on [1, 2)), smoothed over one pixel to avoid aliasing.
float smooth_square(float x, float pixel) {
  float triangle = abs(fract(x * 0.5) * 2.0 - 1.0);
  return smoothstep(0.5 - pixel, 0.5 + pixel, triangle);
}

void main() {
  vec2 cell = world_position.xy / tile_size;
  vec2 pixel = fwidth(cell);
  float sx = smooth_square(cell.x, pixel.x);
  float sy = smooth_square(cell.y, pixel.y);
  float checker = sx * sy + (1.0 - sx) * (1.0 - sy);
  // Far away a pixel covers many tiles: show their average instead of moire.
  checker = mix(checker, 0.5, smoothstep(0.3, 1.0, max(pixel.x, pixel.y)));
  vec3 ground = mix(dark_tile_colour, light_tile_colour, checker);
  ground *= light_fraction;

  float distance_from_centre = length(world_position.xy - fade_centre);
  float fade = smoothstep(fade_start, fade_end, distance_from_centre);
  colour = vec4(mix(ground, horizon_colour, fade), 1.0);
}
