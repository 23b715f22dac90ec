#include "bindings.hpp"

namespace slambox::python {

py::object ToPython(const nlohmann::json& j) {
  using T = nlohmann::json::value_t;
  switch (j.type()) {
    case T::null:
    case T::discarded:
      return py::none();
    case T::boolean:
      return py::bool_(j.get<bool>());
    case T::number_integer:
      return py::int_(j.get<std::int64_t>());
    case T::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case T::number_float:
      return py::float_(j.get<double>());
    case T::string:
      return py::str(j.get_ref<const std::string&>());
    case T::array: {
      py::list out;
      for (const auto& v : j) out.append(ToPython(v));
      return out;
    }
    case T::object: {
      py::dict out;
      for (const auto& [k, v] : j.items()) out[py::str(k)] = ToPython(v);
      return out;
    }
    case T::binary:
      break;
  }
  throw py::value_error("slambox: a JSON value without a Python equivalent");
}

std::vector<std::string> SetArguments(const py::dict& overrides) {
  std::vector<std::string> out;
  for (const auto& [key, value] : overrides) {
    std::string text;
    if (py::isinstance<py::bool_>(value)) text = value.cast<bool>() ? "true" : "false";
    else if (py::isinstance<py::str>(value)) text = value.cast<std::string>();
    else text = py::repr(value).cast<std::string>();  // numbers: the shortest text that reads back exactly
    out.push_back(py::str(key).cast<std::string>() + "=" + text);
  }
  return out;
}

/// "ValueError: message": the last line Python prints for the exception.
std::string LastTracebackLine(const py::error_already_set& e) {
  const py::list lines = py::module_::import("traceback").attr("format_exception_only")(e.type(), e.value());
  std::string last = lines.empty() ? std::string("unknown Python error") : py::str(lines[lines.size() - 1]).cast<std::string>();
  while (!last.empty() && (last.back() == '\n' || last.back() == ' ')) last.pop_back();
  return last;
}

}  // namespace slambox::python
