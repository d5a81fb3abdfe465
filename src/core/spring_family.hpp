// The three kinds of springs of the handout's figure 6, each with its own stiffness.
#pragma once

#include <array>

namespace clothlab {

enum class spring_family { structural, shear, bending };
inline constexpr std::array<spring_family, 3> all_spring_families = {
    spring_family::structural, spring_family::shear, spring_family::bending};

}  // namespace clothlab
