uniform vec4 flat_colour;  // rgba; alpha blends it over what is behind
out vec4 colour;

void main() { colour = flat_colour; }
