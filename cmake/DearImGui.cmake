# Dear ImGui (docking branch) with its GLFW and OpenGL 3 backends and ImPlot, from their
# published crates on crates.io (the dear-imgui-rs family bundles the C++ sources), fetched by
# cargo at configure time, pinned to one version and checked against a SHA-256 here
# (CargoCrates.cmake). Only their C++ files are compiled, as static libraries. docs/DESIGN.md
# §2.2 says why these crates.
set(IMGUI_CRATES_VERSION 0.22.0)
set(IMGUI_CRATES dear-imgui-sys dear-implot-sys)
set(dear-imgui-sys_SHA256 7b82f66d6c4165fb1e40888e48765d7175ecf96b7c411d351304c8fa8ca6f365)
set(dear-implot-sys_SHA256 510b1a02e89cf686b508c72df1d47ccf223b158f3efd862b5bae8536dcb63eac)

include(${CMAKE_CURRENT_LIST_DIR}/CargoCrates.cmake)
set(_imgui_deps "${CMAKE_BINARY_DIR}/_deps")
set(_imgui_done "${_imgui_deps}/imgui-crates-${IMGUI_CRATES_VERSION}.checked")

if(NOT EXISTS "${_imgui_done}")
  glint_cargo_fetch("the Dear ImGui crates ${IMGUI_CRATES_VERSION}" "${CMAKE_SOURCE_DIR}/cmake/imgui-crates"
                    "${_imgui_deps}/imgui-fetch")
  foreach(_name ${IMGUI_CRATES})
    glint_extract_crate(${_name} ${IMGUI_CRATES_VERSION} ${${_name}_SHA256} "${_imgui_deps}")
  endforeach()
  file(WRITE "${_imgui_done}" "checked\n")
endif()

set(_imgui "${_imgui_deps}/dear-imgui-sys-${IMGUI_CRATES_VERSION}/third-party/cimgui/imgui")
set(_implot "${_imgui_deps}/dear-implot-sys-${IMGUI_CRATES_VERSION}/third-party/cimplot/implot")

pkg_check_modules(GLFW REQUIRED IMPORTED_TARGET glfw3)
# One library: the core, the two backends and ImPlot (built against the same imgui.h, so one
# version of the ABI).
add_library(imgui STATIC
  ${_imgui}/imgui.cpp ${_imgui}/imgui_draw.cpp ${_imgui}/imgui_tables.cpp ${_imgui}/imgui_widgets.cpp
  ${_imgui}/imgui_demo.cpp
  ${_imgui}/backends/imgui_impl_glfw.cpp ${_imgui}/backends/imgui_impl_opengl3.cpp
  ${_implot}/implot.cpp ${_implot}/implot_items.cpp)
target_include_directories(imgui SYSTEM PUBLIC ${_imgui} ${_imgui}/backends ${_implot})
target_link_libraries(imgui PUBLIC PkgConfig::GLFW ${CMAKE_DL_LIBS})
set_target_properties(imgui PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_compile_options(imgui PRIVATE -w)
