# Build-time script: writes OUTPUT, a C++ file holding every scenario in SCENARIO_DIR/*.yaml
# as a raw string literal, so the binary never reads the source tree at run time. A
# scenario file has a top-level `version:` key; other YAML there (e.g. sweep files) is skipped.
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
set(content "// Generated from scenarios/*.yaml by sim/embed_scenarios.cmake. Do not edit.
#include \"sim/scenario_yaml.hpp\"

namespace slambox::scenario_detail {
const std::vector<EmbeddedScenario>& EmbeddedScenarios() {
  static const std::vector<EmbeddedScenario> scenarios = {
${body}  };
  return scenarios;
}
}  // namespace slambox::scenario_detail
")
file(WRITE ${OUTPUT} "${content}")
