// Paths that only the build knows: the clothlab executable under test and the reference images.
// They are compiled into one small file (build_paths.cpp), so that the test files themselves
// compile to the same objects in every checkout, and ccache can share them between the teacher's
// build and the student copy's (tests/student_copy).
#pragma once

namespace clothlab_test {

extern const char* const executable_path;             // build/clothlab
extern const char* const render_reference_directory;  // tests/render/reference

}  // namespace clothlab_test
