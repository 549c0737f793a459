# Which sources of a target get the precompiled headers (precompiled_headers.h).
#
# Loading the precompiled file (about 650 MB of deal.II, PETSc and Trilinos declarations) costs a
# source about 4 s; parsing deal.II's finite-element, linear-algebra and MPI headers costs a source
# 5-15 s. A source that needs none of them (the case files, the study and calibration drivers, the
# material points, most unit tests) compiles two to five times faster without the precompiled
# file; one that needs them, faster with it. So a source gets it only when it includes, itself or
# through the project's own headers, a deal.II header other than the tensor classes below.
# The scan runs at configure time: a source whose includes change keeps its old choice until
# CMake runs again, which costs build time only, never correctness (every source includes what it
# uses).
set(INDENTSIM_LIGHT_DEAL_II_HEADERS "deal\\.II/base/(tensor|symmetric_tensor|point)\\.h")

# result = ON if `file` includes, directly or through a header of the project (found next to it
# or under src/), a deal.II header outside INDENTSIM_LIGHT_DEAL_II_HEADERS. Memoised per file.
function(indentsim_includes_heavy_headers file result)
  string(MAKE_C_IDENTIFIER "${file}" key)
  get_property(known GLOBAL PROPERTY indentsim_heavy_${key} SET)
  if(known)
    get_property(value GLOBAL PROPERTY indentsim_heavy_${key})
    set(${result} ${value} PARENT_SCOPE)
    return()
  endif()
  set_property(GLOBAL PROPERTY indentsim_heavy_${key} OFF) # ends an include cycle
  set(value OFF)
  get_filename_component(directory ${file} DIRECTORY)
  file(STRINGS ${file} includes REGEX "^[ \t]*#[ \t]*include")
  foreach(line ${includes})
    if(line MATCHES "<(deal\\.II/[^>]+)>")
      set(header ${CMAKE_MATCH_1})
      if(NOT header MATCHES "^${INDENTSIM_LIGHT_DEAL_II_HEADERS}$")
        set(value ON)
        break()
      endif()
    elseif(line MATCHES "\"([^\"]+)\"")
      set(header ${CMAKE_MATCH_1})
      foreach(candidate ${directory}/${header} ${CMAKE_SOURCE_DIR}/src/${header})
        if(EXISTS ${candidate})
          indentsim_includes_heavy_headers(${candidate} heavy)
          if(heavy)
            set(value ON)
          endif()
          break()
        endif()
      endforeach()
      if(value)
        break()
      endif()
    endif()
  endforeach()
  set_property(GLOBAL PROPERTY indentsim_heavy_${key} ${value})
  set(${result} ${value} PARENT_SCOPE)
endfunction()

# target_precompile_headers(target PRIVATE headers...) for the sources of `target` that include
# heavy deal.II headers; the others skip them. Call it in the directory that added the target.
function(indentsim_precompile_headers target)
  target_precompile_headers(${target} PRIVATE ${ARGN})
  get_target_property(sources ${target} SOURCES)
  set(light "")
  foreach(source ${sources})
    get_filename_component(path ${source} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
    set(heavy OFF)
    if(EXISTS ${path})
      indentsim_includes_heavy_headers(${path} heavy)
    endif()
    if(NOT heavy)
      list(APPEND light ${source})
    endif()
  endforeach()
  set_source_files_properties(${light} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
  list(LENGTH sources n_sources)
  list(LENGTH light n_light)
  message(STATUS "${target}: precompiled headers for ${n_sources} sources less ${n_light} "
                 "that need no heavy deal.II header")
endfunction()
