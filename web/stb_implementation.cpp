// stb's image reading and PNG writing for the page. Debian's libstb-dev holds their code compiled
// for this machine only (libstb.so, which the desktop links); the page compiles it from the same
// Debian headers, here.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>
