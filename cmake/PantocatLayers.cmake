# The library as layers along the data flow (doc/architecture.md). Each layer
# is a static library whose include path holds only its own folders of
# include/pantocat/ (as links in the build tree) plus those of the layers it
# links: a header of a layer it does not link is not found, so a forbidden
# include does not compile.

set(PANTOCAT_LAYER_ROOT ${CMAKE_BINARY_DIR}/layers)

# deal_ii_setup_target() links with the plain signature of
# target_link_libraries(); the layers link PUBLIC/PRIVATE, which CMake does
# not allow to mix. This is the same set-up (Release or Debug flavour of
# deal.II's flags, definitions, includes and libraries) with keywords.
function(pantocat_setup_dealii target)
  if(NOT DEAL_II_TARGET_CONFIG_INCLUDED)
    include(${DEAL_II_TARGET_CONFIG})
    set(DEAL_II_TARGET_CONFIG_INCLUDED TRUE PARENT_SCOPE)
  endif()
  set(build RELEASE)
  if(CMAKE_BUILD_TYPE STREQUAL "Debug" AND DEAL_II_BUILD_TYPE MATCHES "Debug")
    set(build DEBUG)
  endif()
  target_include_directories(${target} SYSTEM PRIVATE ${DEAL_II_INCLUDE_DIRS})
  set_property(TARGET ${target} APPEND_STRING PROPERTY
    LINK_FLAGS " ${DEAL_II_LINKER_FLAGS} ${DEAL_II_LINKER_FLAGS_${build}}")
  set(flags "${DEAL_II_CXX_FLAGS} ${DEAL_II_CXX_FLAGS_${build}}")
  separate_arguments(flags)
  target_compile_options(${target} PUBLIC $<$<COMPILE_LANGUAGE:CXX>:${flags}>)
  target_compile_definitions(${target} PUBLIC ${DEAL_II_USER_DEFINITIONS}
                             ${DEAL_II_USER_DEFINITIONS_${build}})
  target_link_libraries(${target} PUBLIC ${DEAL_II_TARGET_${build}})
endfunction()

# A build from scratch compiles the sources of a target in batches of up to
# eight (one translation unit each, CMake's unity build): the precompiled
# deal.II header is loaded once per batch instead of once per file, which is
# about 3 s of each file's 10 s. -DPANTOCAT_UNITY_BUILD=OFF compiles file by
# file (quicker rebuilds while editing one file).
option(PANTOCAT_UNITY_BUILD "Compile each target's sources in batches" ON)
function(pantocat_batch_sources target)
  set_target_properties(${target} PROPERTIES UNITY_BUILD ${PANTOCAT_UNITY_BUILD}
                        UNITY_BUILD_BATCH_SIZE 8)
endfunction()

# pantocat_layer(NAME FOLDERS f... [PUBLIC dep...] [PRIVATE dep...] [PCH fe|algebra|none])
function(pantocat_layer name)
  cmake_parse_arguments(L "" "PCH" "FOLDERS;PUBLIC;PRIVATE" ${ARGN})
  set(include_dir ${PANTOCAT_LAYER_ROOT}/${name})
  set(sources "")
  foreach(folder ${L_FOLDERS})
    file(MAKE_DIRECTORY ${include_dir}/pantocat)
    if(NOT EXISTS ${include_dir}/pantocat/${folder})
      file(CREATE_LINK ${CMAKE_SOURCE_DIR}/include/pantocat/${folder}
           ${include_dir}/pantocat/${folder} SYMBOLIC)
    endif()
    file(GLOB folder_sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/source/${folder}/*.cc)
    list(APPEND sources ${folder_sources})
  endforeach()
  if(NOT sources) # a header-only layer
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${include_dir})
    target_link_libraries(${name} INTERFACE ${L_PUBLIC})
    return()
  endif()
  add_library(${name} STATIC ${sources})
  pantocat_batch_sources(${name})
  target_include_directories(${name} PUBLIC ${include_dir})
  target_link_libraries(${name} PUBLIC ${L_PUBLIC} PRIVATE ${L_PRIVATE})
  if(L_PCH STREQUAL "none")
    # Plain C++ and POSIX (the base layer): no deal.II flags to pass on, no
    # precompiled header (whose target links this layer).
    target_compile_options(${name} PRIVATE $<$<CONFIG:Release>:-O3>)
    return()
  endif()
  pantocat_setup_dealii(${name})
  target_compile_options(${name} PRIVATE $<$<CONFIG:Release>:-O3>)
  if(NOT L_PCH)
    set(L_PCH algebra)
  endif()
  target_precompile_headers(${name} REUSE_FROM pantocat_pch_${L_PCH})
endfunction()

# Two precompiled headers: the finite-element one only for the layers that
# assemble on grids.
foreach(kind fe algebra)
  add_library(pantocat_pch_${kind} OBJECT ${CMAKE_SOURCE_DIR}/cmake/pch.cc)
  deal_ii_setup_target(pantocat_pch_${kind})
  # The same definitions as every layer (Boost.Serialization's, through
  # pantocat_base): gcc ignores a precompiled header built with others.
  target_link_libraries(pantocat_pch_${kind} PRIVATE pantocat_base)
  target_compile_options(pantocat_pch_${kind} PRIVATE $<$<CONFIG:Release>:-O3>)
  target_precompile_headers(pantocat_pch_${kind} PRIVATE
    ${CMAKE_SOURCE_DIR}/include/pantocat/pch_${kind}.h)
endforeach()
