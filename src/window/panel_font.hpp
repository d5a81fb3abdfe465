// The panel's font: DejaVu Sans (Debian's fonts-dejavu-core), which has the accents of French and
// the handout's symbols (μ, ω, √, ², ≤, « ») that Dear ImGui's own font lacks. Where it is missing,
// Dear ImGui's font, with a warning: the panel works, its accents show as "?".
#pragma once

namespace clothlab {

// Adds the panel's font at `size_pixels` to Dear ImGui's atlas (a context must exist). False, with
// the warning printed on standard error, when no font file was found and the default was added.
bool add_panel_font(float size_pixels);

}  // namespace clothlab
