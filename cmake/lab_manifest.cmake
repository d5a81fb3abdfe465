# The lab's questions that ask for code, read from grading/lab.json (the one list: every script
# reads it too, scripts/clothlab_lab/manifest.py). Sets, in the caller's scope:
#   CLOTHLAB_LAB_TESTS   each question's test, "q8_compute_force": tests/lab/<test>_test.cpp
#   CLOTHLAB_LAB_LABELS  each question's label, "q8", in the same order
# CMake runs again when the manifest changes.
function(clothlab_read_lab_manifest)
  set(manifest ${PROJECT_SOURCE_DIR}/grading/lab.json)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${manifest})
  file(READ ${manifest} lab)
  string(JSON count LENGTH "${lab}" questions)
  set(tests)
  set(labels)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON id GET "${lab}" questions ${i} id)
    string(JSON test GET "${lab}" questions ${i} test)
    string(TOLOWER ${id} label)
    list(APPEND tests ${test})
    list(APPEND labels ${label})
  endforeach()
  set(CLOTHLAB_LAB_TESTS ${tests} PARENT_SCOPE)
  set(CLOTHLAB_LAB_LABELS ${labels} PARENT_SCOPE)
endfunction()
