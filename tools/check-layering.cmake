# The layering of src/ (docs/architecture.md, "What may include what"),
# checked on the sources' #include lines:
#
#   cmake -DSRC=path/to/src -P tools/check-layering.cmake
#
# Each rule names a folder and the folders its code must not include: the
# file readers (io/) reach no stage after the model but image/'s checked EXR
# reader and render/'s settings; the renderer's stages never reach the file
# readers or the front ends;
# inside render/, the BSDFs (render/bsdf/) and the lights (render/lights/)
# know nothing of each other, and the media (render/media/) nothing of either; the library API (api/) reads no file; the front ends (app/, python/,
# view/) call the API, and neither Python nor the viewer reaches into the
# command line (app/); the denoiser (denoise/) works on plain arrays and
# includes nothing but core/ and itself; the scene model includes nothing but core/ and itself. Test code is exempt, a file whose
# name contains "test" (foo_test.cpp, test_meshes.h, chi2_test_util.h): a
# test may read a scene file to render it, and its executable links
# sombra_io for that. Fails, listing every offending line, when a rule is
# broken. CTest runs it as the test layering_includes (src/CMakeLists.txt).
cmake_minimum_required(VERSION 3.25)

if(NOT DEFINED SRC)
  message(FATAL_ERROR "usage: cmake -DSRC=<src folder> -P check-layering.cmake")
endif()

set(rules
  "io:accel,explain,api,distributed,view,python,app"
  "accel:io,api,distributed,view,python,app"
  "render:io,api,distributed,view,python,app"
  "render/bsdf:render/lights"
  "render/lights:render/bsdf"
  "render/media:render/bsdf,render/lights"
  "explain:io,api,distributed,view,python,app"
  "image:io,api,distributed,view,python,app"
  "denoise:scene,io,accel,render,explain,image,api,distributed,view,python,app"
  "api:io,distributed,view,python,app"
  "distributed:io,view,python,app"
  "view:io,distributed,python,app"
  "python:app,view,distributed"
  "scene:io,accel,render,explain,image,api,distributed,view,python,app"
  "core:scene,io,accel,render,explain,image,api,distributed,view,python,app")

set(broken "")
set(checked 0)
foreach(rule IN LISTS rules)
  string(REPLACE ":" ";" parts "${rule}")
  list(GET parts 0 folder)
  list(GET parts 1 forbidden)
  string(REPLACE "," "|" forbidden "${forbidden}")
  file(GLOB_RECURSE files RELATIVE "${SRC}" "${SRC}/${folder}/*.h" "${SRC}/${folder}/*.hpp" "${SRC}/${folder}/*.cpp")
  foreach(file IN LISTS files)
    get_filename_component(name "${file}" NAME)
    if(name MATCHES "test")
      continue()
    endif()
    math(EXPR checked "${checked} + 1")
    file(STRINGS "${SRC}/${file}" includes REGEX "^[ \t]*#[ \t]*include")
    foreach(line IN LISTS includes)
      # "io/x.h", <io/x.h>, and relative climbs such as "../io/x.h".
      if(line MATCHES "include[ \t]*[\"<](\\.\\./)*(${forbidden})/")
        string(STRIP "${line}" line)
        string(APPEND broken "  ${file}: ${line} (${folder}/ must not include ${CMAKE_MATCH_2}/)\n")
      endif()
    endforeach()
  endforeach()
endforeach()

if(broken)
  message(FATAL_ERROR "layering broken: see docs/architecture.md, \"What may include what\"\n${broken}")
endif()
message(STATUS "layering holds: ${checked} files of ${SRC} checked")
