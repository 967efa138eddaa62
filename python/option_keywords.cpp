// The non-template parts of the verbs' Python keywords (option_keywords.hpp).
#include "option_keywords.hpp"

#include <pybind11/stl.h>

#include "ccal/io/config_file.hpp"  // nearest_name: the did-you-mean of every mistyped name

namespace ccal::python::keywords {

void unknown_keyword(std::string_view function, std::string_view keyword,
                     std::initializer_list<std::string_view> own, const std::vector<std::string_view>& accepted) {
  std::string list;
  for (std::string_view name : own) list += (list.empty() ? "" : ", ") + std::string(name);
  for (std::string_view name : accepted) list += (list.empty() ? "" : ", ") + std::string(name);
  const std::vector<std::string> names(accepted.begin(), accepted.end());
  const std::optional<std::string> nearest = nearest_name(keyword, names);
  throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" + std::string(keyword) +
                       "'" + (nearest ? "; did you mean '" + *nearest + "'?" : "") + "; accepted: " + list);
}

void wrong_type(std::string_view field, std::string_view expected, py::handle value) {
  throw py::type_error(std::string(field) + ": expected " + std::string(expected) + ", got " +
                       std::string(py::str(py::type::handle_of(value).attr("__name__"))) + " (" +
                       std::string(py::repr(value)) + ")");
}

bool is_calendar_date(py::handle value) {
  const py::module_ datetime = py::module_::import("datetime");
  return py::isinstance(value, datetime.attr("date")) && !py::isinstance(value, datetime.attr("datetime"));
}

bool is_number(py::handle value) {
  if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value))
    return false;
  // NumPy's bool_ has __index__ in old versions: refuse it as a number too.
  if (std::string(py::str(py::type::handle_of(value).attr("__name__"))).starts_with("bool")) return false;
  // A NumPy array, even of one element, is no number (its __index__ and __float__ would refuse or warn).
  if (py::hasattr(value, "ndim") && py::hasattr(value, "shape") && value.attr("ndim").cast<long>() != 0) return false;
  return py::hasattr(value, "__index__") || py::hasattr(value, "__float__");
}

std::string number_text(py::handle value) {
  if (py::hasattr(value, "__index__")) {
    if (PyObject* index = PyNumber_Index(value.ptr())) return py::str(py::reinterpret_steal<py::object>(index));
    PyErr_Clear();  // a float-like value whose __index__ refuses: read as a float below
  }
  // repr of a float is its shortest round-trip text (1e+20, 100000.0, nan, inf).
  return py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
}

std::vector<std::string> strings(std::string_view field, py::handle value) {
  if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value))
    wrong_type(field, "a list of str", value);
  std::vector<std::string> out;
  // A list of the items holds each one while it is read: a NumPy array's items are new objects.
  for (py::handle item : py::list(py::reinterpret_borrow<py::object>(value))) {
    if (!py::isinstance<py::str>(item)) wrong_type(field, "a list of str", item);
    out.push_back(item.cast<std::string>());
  }
  return out;
}

std::vector<double> reals(std::string_view field, py::handle value) {
  if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value))
    wrong_type(field, "a list of numbers", value);
  std::vector<double> out;
  // A list of the items holds each one while it is read: a NumPy array's items (its rows) are new objects.
  for (py::handle item : py::list(py::reinterpret_borrow<py::object>(value)))
    out.push_back(number<double>(field, item));
  return out;
}

bool skipped(std::string_view field, std::initializer_list<std::string_view> skip) {
  return std::find(skip.begin(), skip.end(), field) != skip.end();
}

void record(py::module_& m, std::string_view function, std::string_view name, py::object default_value,
            const std::string& type, const std::string& help) {
  if (!py::hasattr(m, "_option_keywords")) m.attr("_option_keywords") = py::dict();
  py::dict all = m.attr("_option_keywords");
  const py::str key{std::string(function)};
  if (!all.contains(key)) all[key] = py::list();
  py::list(all[key]).append(py::make_tuple(std::string(name), default_value, type, help));
}

}  // namespace ccal::python::keywords
