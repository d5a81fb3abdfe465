// The PNG capture of the current framebuffer, for --png, the window's screenshot (P) and the
// web build's download.
#pragma once

#include <string>
#include <vector>

namespace clothlab {

// Reads the current framebuffer (width x height, RGBA8) as a PNG image, top row first, into
// `png` (the file's bytes, e.g. for the web build to hand to the browser as a download). False
// with error on a size below 1 x 1 or a failed encoding.
bool framebuffer_png(int width, int height, std::vector<unsigned char>& png, std::string& error);
// The same PNG written to the file `path`; false with error naming the path when it cannot be
// written whole (a truncated file is removed).
bool save_framebuffer_png(const std::string& path, int width, int height, std::string& error);

}  // namespace clothlab
