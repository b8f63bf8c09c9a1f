# The browser viewer's script (io/viewer_writer.hpp): three.js and its glTF loader from npm
# (viewer/package.json, versions locked in viewer/package-lock.json), bundled by esbuild into
# one file, build/viewer/sinew_viewer.js, which every written viewer page inlines. npm fetches
# the packages once (the first build needs the npm registry); later builds and the pages work
# offline. Without npm the library still builds, and writing a viewer is a clear error.
find_program(SINEW_NPM npm)
find_program(SINEW_NODE node)
set(SINEW_VIEWER_DIR ${CMAKE_BINARY_DIR}/viewer)
set(SINEW_VIEWER_SCRIPT_FILE ${SINEW_VIEWER_DIR}/sinew_viewer.js)
if(SINEW_NPM AND SINEW_NODE)
  set(stamp ${SINEW_VIEWER_DIR}/node_modules/.package-lock.json)
  add_custom_command(
    OUTPUT ${stamp}
    COMMAND ${CMAKE_COMMAND} -E copy ${CMAKE_SOURCE_DIR}/viewer/package.json ${CMAKE_SOURCE_DIR}/viewer/package-lock.json
            ${SINEW_VIEWER_DIR}/
    COMMAND ${SINEW_NPM} ci --no-audit --no-fund --loglevel=error
    COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
    WORKING_DIRECTORY ${SINEW_VIEWER_DIR}
    DEPENDS ${CMAKE_SOURCE_DIR}/viewer/package.json ${CMAKE_SOURCE_DIR}/viewer/package-lock.json
    COMMENT "npm: three.js and esbuild for the viewer (viewer/package-lock.json)")
  file(GLOB SINEW_VIEWER_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/viewer/src/*.js)
  add_custom_command(
    OUTPUT ${SINEW_VIEWER_SCRIPT_FILE}
    COMMAND ${CMAKE_COMMAND} -E env NODE_PATH=${SINEW_VIEWER_DIR}/node_modules
            ${SINEW_VIEWER_DIR}/node_modules/.bin/esbuild ${CMAKE_SOURCE_DIR}/viewer/src/viewer.js --bundle
            --format=iife --minify --target=es2020 --legal-comments=none --log-level=warning
            --outfile=${SINEW_VIEWER_SCRIPT_FILE}
    DEPENDS ${stamp} ${SINEW_VIEWER_SOURCES}
    COMMENT "esbuild: the viewer script ${SINEW_VIEWER_SCRIPT_FILE}")
  add_custom_target(sinew_viewer_script ALL DEPENDS ${SINEW_VIEWER_SCRIPT_FILE})
  set_source_files_properties(${CMAKE_SOURCE_DIR}/src/io/viewer_writer.cpp PROPERTIES
                              COMPILE_DEFINITIONS SINEW_VIEWER_SCRIPT="${SINEW_VIEWER_SCRIPT_FILE}")
else()
  message(WARNING "npm/node not found: the browser viewer's script is not built (install Debian's nodejs and npm)")
  add_custom_target(sinew_viewer_script)
  set(SINEW_VIEWER_SCRIPT_FILE "")
endif()
