# Dear ImGui and stb where the system has no package of them (macOS's Homebrew has neither; the
# browser build compiles both for WebAssembly): compiled here from their sources. Two targets, the
# same whichever way they were found: clothlab_imgui (Dear ImGui with its GLFW and OpenGL 3
# backends) and clothlab_stb (stb_image and stb_image_write, included as <stb/stb_image.h>).

# clothlab_stb from a folder of stb's headers (stb_image.h, stb_image_write.h): a checkout of stb,
# or Debian's /usr/include/stb. Its code is compiled once, in web/stb_implementation.cpp.
function(clothlab_stb_from_headers dir)
  if(NOT EXISTS "${dir}/stb_image.h" OR NOT EXISTS "${dir}/stb_image_write.h")
    message(FATAL_ERROR "clothlab: no stb (pkg-config stb), and CLOTHLAB_STB_DIR (${dir}) has no "
                        "stb_image.h and stb_image_write.h: install stb, or set CLOTHLAB_STB_DIR "
                        "to a checkout of https://github.com/nothings/stb (docs/platforms.md)")
  endif()
  # <stb/stb_image.h> and <stb_image.h> both, through a link in the build folder: the folder
  # above the headers may hold other libraries' headers (/usr/include).
  set(links "${CMAKE_BINARY_DIR}/stb-include")
  file(MAKE_DIRECTORY "${links}")
  if(NOT EXISTS "${links}/stb")
    file(CREATE_LINK "${dir}" "${links}/stb" SYMBOLIC)
  endif()
  add_library(clothlab_stb STATIC "${PROJECT_SOURCE_DIR}/web/stb_implementation.cpp")
  target_include_directories(clothlab_stb SYSTEM PUBLIC "${links}" "${links}/stb")
endfunction()

# clothlab_imgui from Dear ImGui's sources (imgui.cpp, backends/): Debian's source package
# (scripts/setup-web.sh fetches it) or a checkout of https://github.com/ocornut/imgui. ES3: the
# OpenGL ES 3 backend (WebGL2) in place of the desktop's OpenGL 3.
function(clothlab_imgui_from_sources dir)
  cmake_parse_arguments(PARSE_ARGV 1 arg "ES3" "" "")
  if(NOT EXISTS "${dir}/imgui.cpp" OR NOT EXISTS "${dir}/backends/imgui_impl_glfw.cpp")
    message(FATAL_ERROR "clothlab: no Dear ImGui (pkg-config imgui), and CLOTHLAB_IMGUI_DIR "
                        "(${dir}) has no imgui.cpp and backends/: set it to a checkout of "
                        "https://github.com/ocornut/imgui (docs/platforms.md)")
  endif()
  add_library(clothlab_imgui STATIC
    "${dir}/imgui.cpp"
    "${dir}/imgui_draw.cpp"
    "${dir}/imgui_tables.cpp"
    "${dir}/imgui_widgets.cpp"
    "${dir}/backends/imgui_impl_glfw.cpp"
    "${dir}/backends/imgui_impl_opengl3.cpp"
  )
  target_include_directories(clothlab_imgui SYSTEM PUBLIC "${dir}")
  if(arg_ES3)
    target_compile_definitions(clothlab_imgui PUBLIC IMGUI_IMPL_OPENGL_ES3)
  else()
    target_link_libraries(clothlab_imgui PUBLIC glfw OpenGL::GL ${CMAKE_DL_LIBS})
  endif()
endfunction()
