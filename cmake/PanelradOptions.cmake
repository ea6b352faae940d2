# Warnings and sanitizer flags shared by every panelrad target.
add_library(panelrad_options INTERFACE)
target_compile_options(panelrad_options INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic>)
if(PANELRAD_SANITIZE)
  target_compile_options(panelrad_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                         -fno-sanitize-recover=undefined)
  target_link_options(panelrad_options INTERFACE -fsanitize=address,undefined)
endif()

# panelrad_layer_includes(TARGET DIR): public headers in DIR/include; C++20 required of the target
# and of everything that links it (the headers use <span> and defaulted comparisons), so
# that an installed package's consumer gets it through panelrad::panelrad without setting a
# standard itself; warnings (build tree only).
function(panelrad_layer_includes target dir)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${dir}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:panelrad_options>)
endfunction()
