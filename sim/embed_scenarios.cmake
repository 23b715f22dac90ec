# Build-time script: writes OUTPUT, a C++ file holding every scenario in SCENARIO_DIR/*.yaml
# as a raw string literal, so the binary never reads the source tree at run time. A
# scenario file has a top-level `version:` key; other YAML there (e.g. sweep files) is skipped.
# Every file of SCENARIO_DIR/maps/ (map.yaml + image) is embedded as bytes, for built-in
# scenarios that name `occupancy_map: maps/NAME.yaml`.
file(GLOB files ${SCENARIO_DIR}/*.yaml)
list(SORT files)
set(body "")
foreach(file ${files})
  get_filename_component(name ${file} NAME_WLE)
  file(READ ${file} text)
  if(NOT text MATCHES "(^|\n)version:")
    continue()
  endif()
  string(FIND "${text}" ")slambox_yaml\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw-string delimiter )slambox_yaml\"")
  endif()
  string(APPEND body "      {\"${name}\", R\"slambox_yaml(${text})slambox_yaml\"},\n")
endforeach()
file(GLOB map_files ${SCENARIO_DIR}/maps/*)
list(SORT map_files)
set(arrays "")
set(entries "")
set(index 0)
foreach(file ${map_files})
  get_filename_component(name ${file} NAME)
  file(READ ${file} hex HEX)
  string(LENGTH "${hex}" hex_length)
  math(EXPR size "${hex_length} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(APPEND arrays "const unsigned char file${index}[] = {${bytes}};\n")
  string(APPEND entries "      {\"maps/${name}\", file${index}, ${size}},\n")
  math(EXPR index "${index} + 1")
endforeach()
set(content "// Generated from scenarios/*.yaml by sim/embed_scenarios.cmake. Do not edit.
#include \"sim/scenario_yaml.hpp\"

namespace slambox::scenario_detail {
const std::vector<EmbeddedScenario>& EmbeddedScenarios() {
  static const std::vector<EmbeddedScenario> scenarios = {
${body}  };
  return scenarios;
}

namespace {
${arrays}}  // namespace

const std::vector<EmbeddedFile>& EmbeddedFiles() {
  static const std::vector<EmbeddedFile> files = {
${entries}  };
  return files;
}
}  // namespace slambox::scenario_detail
")
file(WRITE ${OUTPUT} "${content}")
