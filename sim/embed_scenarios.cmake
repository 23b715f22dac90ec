# Build-time script: writes OUTPUT, a C++ file holding every SCENARIO_DIR/*.yaml as a raw
# string literal, so the binary never reads the source tree at run time.
file(GLOB files ${SCENARIO_DIR}/*.yaml)
list(SORT files)
set(body "")
foreach(file ${files})
  get_filename_component(name ${file} NAME_WE)
  file(READ ${file} text)
  string(FIND "${text}" ")slambox_yaml\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw-string delimiter )slambox_yaml\"")
  endif()
  string(APPEND body "      {\"${name}\", R\"slambox_yaml(${text})slambox_yaml\"},\n")
endforeach()
set(content "// Generated from scenarios/*.yaml by sim/embed_scenarios.cmake. Do not edit.
#include \"sim/scenario_yaml.hpp\"

namespace slambox {
const std::vector<EmbeddedScenario>& EmbeddedScenarios() {
  static const std::vector<EmbeddedScenario> scenarios = {
${body}  };
  return scenarios;
}
}  // namespace slambox
")
file(WRITE ${OUTPUT}.tmp "${content}")
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
