// The `roving` Python module: `roving measure` and `roving batch` as functions. Keyword arguments
// are the command's options (--max-error is max_error) and are parsed by the command line's own
// declarations (roving/cli/command_line.h), so names, defaults, checks and messages are the
// tool's; the measurement runs the tool's code and the result is its JSON report as a dict, the
// same numbers bit for bit, with the per-sample columns of --samples-out as NumPy arrays that own
// the library's buffers (no copy). Models come as paths or as what Python code already holds:
// NumPy vertex and face arrays, objects with `vertices` and `faces` (or `triangles`), Open3D's
// TriangleMesh and PointCloud.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <signal.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <regex>
#include <string>

#include "roving/cli/batch.h"
#include "roving/cli/command_line.h"
#include "roving/cli/measure.h"
#include "roving/cli/provenance.h"
#include "roving/core/colour_statistics.h"
#include "roving/core/error.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/mtl_reader.h"
#include "roving/registry/method_registry.h"
#include "roving/representations/model.h"

namespace py = pybind11;
using namespace roving;

namespace {

// A NumPy array of `shape` over the data of `values`, which it takes over (moved to the heap,
// freed with the array).
template <class Scalar, class T>
py::array adopt(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  std::vector<py::ssize_t> strides(shape.size(), sizeof(Scalar));
  for (std::size_t i = shape.size() - 1; i > 0; --i) strides[i - 1] = strides[i] * shape[i];
  return py::array_t<Scalar>(shape, strides, reinterpret_cast<const Scalar*>(owned->data()), free_when_done);
}

// --option-name for the keyword option_name.
std::string option_of(const std::string& keyword) {
  std::string option = "--" + keyword;
  for (char& c : option) c = c == '_' ? '-' : c;
  return option;
}

// A flag's value as Python code writes it: True or False, NumPy's bool_ (a mask's element), or
// the integers 1 and 0; anything else is an error naming the keyword.
bool flag_value(const std::string& keyword, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  const std::string type = py::str(py::type::of(value).attr("__name__"));
  if (type == "bool_") return value.attr("__bool__")().cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    const long long number = value.cast<long long>();
    if (number == 0 || number == 1) return number == 1;
  }
  throw Error(keyword + ": expected True or False, found " + std::string(py::repr(value)));
}

// A message of the command's in the module's words: each of `subcommand`'s options as its keyword,
// with the value that follows it where it takes one ("--semantics closest" is semantics='closest'),
// a flag as keyword=True.
std::string in_keywords(const std::string& text, const CLI::App& subcommand) {
  static const std::regex mentioned(R"(--([a-z][a-z0-9-]*)( ([A-Za-z0-9%.:/_-]*[A-Za-z0-9%]))?)");
  std::string out;
  std::size_t copied = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), mentioned); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const CLI::Option* option = nullptr;
    for (const CLI::Option* o : subcommand.get_options()) {
      const std::vector<std::string>& names = o->get_lnames();
      if (std::find(names.begin(), names.end(), m[1].str()) != names.end()) option = o;
    }
    if (!option) continue;  // not this command's: left as it is
    std::string keyword = m[1].str();
    for (char& c : keyword) c = c == '-' ? '_' : c;
    out += text.substr(copied, m.position(0) - copied);
    if (option->get_expected_max() == 0) {
      out += keyword + "=True" + m[2].str();
    } else {
      out += m[3].matched ? keyword + "='" + m[3].str() + "'" : keyword;
    }
    copied = m.position(0) + m.length(0);
  }
  return out + text.substr(copied);
}

// The keyword arguments as command-line arguments of `subcommand`: a flag's True the flag (False
// leaves it off), None left out, a list or tuple the option repeated, anything else its str(). A
// keyword that names no option of the command is an error naming the nearest one; a bool given to
// an option that takes a value is an error naming the keyword.
std::vector<std::string> arguments_of(const CLI::App& subcommand, const py::kwargs& options,
                                      const std::string& function) {
  std::vector<std::string> keywords, flags;
  for (const CLI::Option* option : subcommand.get_options()) {
    for (const std::string& name : option->get_lnames()) {
      std::string keyword = name;
      for (char& c : keyword) c = c == '-' ? '_' : c;
      if (keyword == "help") continue;
      keywords.push_back(keyword);
      if (option->get_expected_max() == 0) flags.push_back(keyword);
    }
  }
  std::vector<std::string> arguments;
  for (const auto& [key, value] : options) {
    const std::string keyword = py::str(key);
    if (std::find(keywords.begin(), keywords.end(), keyword) == keywords.end()) {
      const std::string nearest = nearest_name(keyword, keywords);
      throw Error(function + ": unknown argument '" + keyword + "'" +
                  (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)"));
    }
    if (value.is_none()) continue;
    if (std::find(flags.begin(), flags.end(), keyword) != flags.end()) {
      if (flag_value(keyword, value)) arguments.push_back(option_of(keyword));
      continue;
    }
    if (py::isinstance<py::bool_>(value)) {
      throw Error(keyword + ": expected a value (as the command's " + option_of(keyword) + " takes), found " +
                  std::string(py::repr(value)));
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
      for (const py::handle item : value)
        arguments.insert(arguments.end(), {option_of(keyword), py::str(item)});
      continue;
    }
    arguments.insert(arguments.end(), {option_of(keyword), py::str(value)});
  }
  return arguments;
}

// An N x columns array of `what` (float64 or int64 after NumPy's conversion), checked.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> rows_of(const py::handle& array,
                                                                  const std::string& what,
                                                                  py::ssize_t columns = 3) {
  auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(1) != columns) {
    throw Error(what + ": expected an N x " + std::to_string(columns) + " array, found " +
                (a ? std::to_string(a.ndim()) + " dimensions" +
                         (a.ndim() == 2 ? " of " + std::to_string(a.shape(1)) + " columns" : std::string())
                   : std::string("something that is not an array")));
  }
  return a;
}

std::vector<Vec3> vectors_of(const py::handle& array, const std::string& what) {
  const auto a = rows_of<double>(array, what);
  std::vector<Vec3> out(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) out[i] = Vec3(a.at(i, 0), a.at(i, 1), a.at(i, 2));
  return out;
}

// Colours as code values: arrays of floats on [0, 1] (Open3D's) scaled by 255, integers taken as
// they are.
std::vector<Colour> colours_of(const py::handle& array, const std::string& what) {
  const py::array given = py::array::ensure(array);
  const bool unit = given && given.dtype().kind() == 'f';
  const auto a = rows_of<double>(array, what);
  std::vector<Colour> out(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    for (int c = 0; c < 3; ++c) out[i][c] = static_cast<float>(unit ? 255 * a.at(i, c) : a.at(i, c));
  }
  return out;
}

// What keeps a lent array alive while the library reads it: a reference, dropped under the GIL
// (the mesh may go from a thread that released it).
std::shared_ptr<const void> lender(py::array array) {
  return std::shared_ptr<const void>(array.release().ptr(), [](const void* object) {
    py::gil_scoped_acquire gil;
    Py_DECREF(static_cast<PyObject*>(const_cast<void*>(object)));
  });
}

// `given` as the rows the mesh stores, read in place where it already is them (C-contiguous N x 3
// of `Scalar` in native order, aligned): no copy; null otherwise.
template <class Row, class Scalar>
std::optional<SharedArray<Row>> lent_rows(const py::handle& given) {
  static_assert(sizeof(Row) == 3 * sizeof(Scalar), "a row is three scalars with no padding");
  if (!py::isinstance<py::array_t<Scalar, py::array::c_style>>(given)) return std::nullopt;
  auto a = py::reinterpret_borrow<py::array>(given);
  if (a.ndim() != 2 || a.shape(1) != 3 || reinterpret_cast<std::uintptr_t>(a.data()) % alignof(Row) != 0) {
    return std::nullopt;
  }
  const auto* rows = static_cast<const Row*>(a.data());
  const auto count = static_cast<std::size_t>(a.shape(0));
  return SharedArray<Row>(rows, count, lender(std::move(a)));
}

// A mesh from vertex and face arrays: float64 vertices and int32 faces in C order are read in
// place (a NumPy array's memory, or Open3D's behind it); other types and layouts are converted.
// TriangleMesh checks the values (finite coordinates, indices in range) either way.
TriangleMesh mesh_from_arrays(const py::handle& vertices, const py::handle& faces, const std::string& name) {
  std::optional<SharedArray<Vec3>> positions = lent_rows<Vec3, double>(vertices);
  if (!positions) positions = vectors_of(vertices, name + " vertices");
  std::optional<SharedArray<Triangle>> triangles = lent_rows<Triangle, int>(faces);
  if (!triangles) {
    // Indices given as floats must be whole numbers: NumPy's cast would truncate 1.7 to 1 silently.
    if (py::isinstance<py::array>(faces) && py::reinterpret_borrow<py::array>(faces).dtype().kind() == 'f') {
      const auto values = rows_of<double>(faces, name + " faces");
      for (py::ssize_t i = 0; i < values.shape(0); ++i) {
        for (int c = 0; c < 3; ++c) {
          const double v = values.at(i, c);
          if (!(std::floor(v) == v)) {
            throw Error(name + " faces: face " + std::to_string(i) + " refers to vertex " + std::string(py::repr(py::float_(v))) +
                        "; expected whole-number indices");
          }
        }
      }
    }
    const auto f = rows_of<long long>(faces, name + " faces");
    std::vector<Triangle> converted(f.shape(0));
    for (py::ssize_t i = 0; i < f.shape(0); ++i) {
      for (int c = 0; c < 3; ++c) {
        const long long index = f.at(i, c);
        if (index < 0 || index >= static_cast<long long>(positions->size())) {
          throw Error(name + " faces: face " + std::to_string(i) + " refers to vertex " + std::to_string(index) +
                      "; expected an index in [0, " + std::to_string(positions->size()) + ")");
        }
        converted[i][c] = static_cast<int>(index);
      }
    }
    triangles = std::move(converted);
  }
  return TriangleMesh(std::move(*positions), std::move(*triangles), name + " arrays");
}

// The attribute `name` of `object` where it has one that is not empty.
py::object attribute(const py::handle& object, const char* name) {
  if (!py::hasattr(object, name)) return py::none();
  py::object value = object.attr(name);
  if (value.is_none() || py::len(py::module_::import("numpy").attr("asarray")(value)) == 0) return py::none();
  return value;
}

// A model from what Python holds: an N x 3 array of points, a (vertices, faces) pair, an object with vertices
// and faces or triangles (trimesh, Open3D's TriangleMesh, ...) with vertex_colors / vertex_colours where
// given, or one with points (Open3D's PointCloud) with normals and colors where given.
std::unique_ptr<Model> model_of(const py::handle& given, const std::string& name, bool unit_normals = true) {
  if (py::isinstance<py::array>(given)) {  // N x 3 points
    PointCloud cloud;
    cloud.positions = vectors_of(given, name + " points");
    return std::make_unique<Model>(model_from_points(std::move(cloud), name + " points"));
  }
  if (py::isinstance<py::tuple>(given) || py::isinstance<py::list>(given)) {
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(given);
    if (py::len(pair) != 2) {
      throw Error(name +
                  ": expected a path, a (vertices, faces) pair or a mesh object, found a sequence of " +
                  std::to_string(py::len(pair)));
    }
    return std::make_unique<Model>(
        model_from_mesh(mesh_from_arrays(pair[0], pair[1], name), name + " arrays"));
  }
  if (py::hasattr(given, "points") && !py::hasattr(given, "faces") && !py::hasattr(given, "triangles")) {
    PointCloud cloud;
    cloud.positions =
        vectors_of(py::module_::import("numpy").attr("asarray")(given.attr("points")), name + " points");
    if (const py::object normals = attribute(given, "normals"); !normals.is_none())
      cloud.normals = vectors_of(py::module_::import("numpy").attr("asarray")(normals), name + " normals");
    if (const py::object colours = attribute(given, "colors"); !colours.is_none())
      cloud.colours = colours_of(py::module_::import("numpy").attr("asarray")(colours), name + " colors");
    return std::make_unique<Model>(model_from_points(std::move(cloud), name + " points", unit_normals));
  }
  const char* faces_name = py::hasattr(given, "faces") ? "faces" : "triangles";
  if (!py::hasattr(given, "vertices") || !py::hasattr(given, faces_name)) {
    throw Error(name +
                ": expected a path, a (vertices, faces) pair, an object with vertices and faces (or "
                "triangles), or one with points; found " +
                std::string(py::str(py::type::of(given).attr("__name__"))));
  }
  const py::object numpy = py::module_::import("numpy");
  TriangleMesh mesh = mesh_from_arrays(numpy.attr("asarray")(given.attr("vertices")),
                                       numpy.attr("asarray")(given.attr(faces_name)), name);
  for (const char* colours_name : {"vertex_colors", "vertex_colours"}) {
    if (const py::object colours = attribute(given, colours_name); !colours.is_none()) {
      mesh.set_vertex_colours(colours_of(numpy.attr("asarray")(colours), name + " " + colours_name), name);
      break;
    }
  }
  return std::make_unique<Model>(model_from_mesh(std::move(mesh), name + " mesh"));
}

bool is_path(const py::handle& given) {
  return py::isinstance<py::str>(given) || py::hasattr(given, "__fspath__");
}

// The columns of --samples-out for one direction, as arrays taking over the report's buffers.
py::dict per_sample(DirectionReport& d) {
  const auto rows = static_cast<py::ssize_t>(d.samples.size());
  py::dict out;
  if (d.colour_pairs) {
    std::vector<float> delta_e = sample_delta_e(*d.colour_pairs, d.result.hit);
    out["reference_colour"] = adopt<float>(std::move(d.colour_pairs->reference), {rows, 3});
    out["test_colour"] = adopt<float>(std::move(d.colour_pairs->test), {rows, 3});
    out["delta_e"] = adopt<float>(std::move(delta_e), {rows});
  }
  if (d.result.gl) {
    out["resolved_by"] = adopt<std::uint8_t>(std::move(d.result.gl->resolved_by), {rows});
  }
  if (!d.result.hit_face.empty())
    out["hit_face"] = adopt<std::uint32_t>(std::move(d.result.hit_face), {rows});
  if (d.correspondences) {
    out["test_point"] = adopt<double>(std::move(d.correspondences->points), {rows, 3});
    out["barycentric"] = adopt<double>(std::move(d.correspondences->barycentric), {rows, 3});
  }
  out["positions"] = adopt<double>(std::move(d.samples.positions), {rows, 3});
  out["normals"] = adopt<double>(std::move(d.samples.normals), {rows, 3});
  out["d"] = adopt<double>(std::move(d.result.signed_distance), {rows});
  out["hit"] = adopt<std::uint8_t>(std::move(d.result.hit), {rows}).attr("view")("bool");
  if (!d.samples.elements.empty())
    out["element"] = adopt<std::uint32_t>(std::move(d.samples.elements), {rows});
  out["weight"] = adopt<double>(std::move(d.samples.weights), {rows});
  return out;
}

// Ctrl-C during a call: Python's own handler only sets a flag that its interpreter loop reads, and
// that loop waits for the call to return. So for the call's duration (on the main thread, where
// Python handles signals) a handler of our own notes it, and the progress listener, on whichever
// thread next reports progress, stops the measurement with KeyboardInterrupt. Nothing is written.
std::atomic<bool> interrupted{false};
extern "C" void note_interrupt(int) {
  interrupted = true;
}

class InterruptScope {
 public:
  InterruptScope() {
    interrupted = false;
    const py::module_ threading = py::module_::import("threading");
    if (!threading.attr("current_thread")().is(threading.attr("main_thread")())) return;
    struct sigaction action {};
    action.sa_handler = note_interrupt;
    sigemptyset(&action.sa_mask);
    installed_ = ::sigaction(SIGINT, &action, &previous_) == 0;
  }
  ~InterruptScope() {
    if (!installed_) return;
    ::sigaction(SIGINT, &previous_, nullptr);
    if (interrupted) PyErr_SetInterrupt();  // pressed as the call ended: Python raises it next
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  struct sigaction previous_ {};
  bool installed_ = false;
};

// What a call hears of its progress: Ctrl-C, and the caller's progress(stage, what, done, total).
Progress::Listener listener(const py::object& callback) {
  return [callback](const std::string& stage, const char* what, std::size_t done, std::size_t total) {
    if (!interrupted && callback.is_none()) return;
    py::gil_scoped_acquire gil;
    if (interrupted.exchange(false)) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw py::error_already_set();
    }
    callback(stage, what, done, total);  // what it raises stops the measurement, and is raised
  };
}

// The keyword arguments but `progress`, which is the module's own.
py::kwargs without_progress(const py::kwargs& options, py::object& progress) {
  py::kwargs rest;
  for (const auto& [key, value] : options) {
    if (std::string(py::str(key)) == "progress") {
      progress = py::reinterpret_borrow<py::object>(value);
      if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
        throw Error("progress: expected a function (stage, what, done, total) or None");
    } else {
      rest[key] = value;
    }
  }
  return rest;
}

py::object parse_json(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

// roving.Warning, a UserWarning: what the command prints as "roving: warning: ...".
py::handle warning_category() {
  static PyObject* const category = PyErr_NewExceptionWithDoc(
      "roving.Warning", "A warning about the models or the measurement (the command's 'roving: warning:' lines)",
      PyExc_UserWarning, nullptr);
  return category;
}

py::dict measure(const py::object& reference, const py::object& test, const py::kwargs& all_options) {
  py::object callback = py::none();
  const py::kwargs options = without_progress(all_options, callback);
  // per_sample=False: no per-sample arrays, so that a large REF file may be read a block of faces at
  // a time (--chunk) as the command reads it, in the command's memory.
  bool keep_per_sample = true;
  if (options.contains("per_sample")) {
    const py::object value = options["per_sample"];
    if (!py::isinstance<py::bool_>(value)) {
      throw Error("per_sample: expected True or False, found " + std::string(py::repr(value)));
    }
    keep_per_sample = value.cast<bool>();
    PyDict_DelItemString(options.ptr(), "per_sample");
  }
  const std::unique_ptr<CommandLine> line = make_command_line();
  const bool reference_is_path = is_path(reference), test_is_path = is_path(test);
  const std::string reference_path =
      reference_is_path ? std::string(py::str(py::module_::import("os").attr("fspath")(reference)))
                        : "reference";
  const std::string test_path =
      test_is_path ? std::string(py::str(py::module_::import("os").attr("fspath")(test))) : "test";
  std::vector<std::string> arguments = {"measure", reference_path, test_path};
  const std::vector<std::string> given = arguments_of(*line->measure, options, "roving.measure");
  arguments.insert(arguments.end(), given.begin(), given.end());
  std::string error;
  try {
    error = parse_command_line(*line, arguments);
  } catch (const CLI::Success&) {
    error = "help: see help(roving.measure)";
  }
  if (!error.empty()) throw Error(error);
  MeasureArguments& args = line->args;
  args.correspondences = keep_per_sample;  // per_sample's test_point and barycentric
  args.warnings_to_stderr = false;         // through Python's warnings, below
  args.command_line = "roving.measure(" + reference_path + ", " + test_path;
  for (std::size_t i = 3; i < arguments.size(); ++i) args.command_line += " " + arguments[i];
  args.command_line += ")";
  if (!args.shard.empty() && !(reference_is_path && test_is_path)) {  // before converting the arrays
    throw Error("--shard: the models must be files (a shard's part names them by path and hash for the merge)");
  }
  // pcc=True: normals as given, as the command keeps a file's (pc_error's D2 uses them so).
  std::unique_ptr<Model> a = reference_is_path ? nullptr : model_of(reference, "reference", !args.pcc);
  std::unique_ptr<Model> b = test_is_path ? nullptr : model_of(test, "test", !args.pcc);
  references_may_leave_folder(line->trust_references);
  require_materials(line->strict_materials);
  MeasureRun run;
  std::string stage = "starting", json, printed;
  std::vector<std::string> breached;
  {
    const InterruptScope interrupt;
    py::gil_scoped_release release;
    Progress progress(args.quiet, /*log_lines=*/false);
    progress.listen(listener(callback));
    run = measure_run(args, stage, progress, {}, std::move(a), std::move(b));
    write_measure_outputs(args, run, stage);
    json = to_json(run.report).dump();
    if (args.json_path == "-") printed = to_json(run.report).dump(2);
    breached = breached_gates(run.plan.gates, gate_values(run.report), run.plan.gate_on);
  }
  if (!printed.empty()) py::print(printed);
  py::dict result = parse_json(json);
  result["breached_gates"] = breached;
  // Each warning through Python's warnings, where a notebook shows it and filters apply: a
  // roving.Warning at the caller's line (a C function adds no frame: stacklevel 1), naming keywords
  // where the command's names options. quiet=True says nothing, as the command; all are in
  // result["warnings"] either way, as the command's JSON has them.
  if (!args.quiet) {
    const py::object warn = py::module_::import("warnings").attr("warn");
    for (const std::string& warning : run.report.warnings) {
      warn(in_keywords(warning, *line->measure), warning_category(), 1);
    }
  }
  if (!keep_per_sample) return result;
  if (run.report.symmetric()) {
    py::list directions = result["directions"];
    for (std::size_t i = 0; i < run.report.directions.size(); ++i)
      directions[i]["per_sample"] = per_sample(run.report.directions[i]);
  } else if (!run.report.directions.empty()) {  // none with pcc=True: MPEG's figures alone
    result["per_sample"] = per_sample(run.report.directions.front());
  }
  return result;
}

// roving.batch(*paths, **options) and roving.merge likewise: the subcommand with the paths (any
// path-like) and the keyword options as its command line, parsed into `line`.
void parse_call(CommandLine& line, const CLI::App& subcommand, const py::args& paths, const py::kwargs& options) {
  std::vector<std::string> arguments = {subcommand.get_name()};
  for (const py::handle path : paths) arguments.push_back(py::str(py::module_::import("os").attr("fspath")(path)));
  const std::vector<std::string> given = arguments_of(subcommand, options, "roving." + subcommand.get_name());
  arguments.insert(arguments.end(), given.begin(), given.end());
  const std::string error = parse_command_line(line, arguments);
  if (!error.empty()) throw Error(error);
}

py::dict merge(const py::args& parts, const py::kwargs& options) {
  const std::unique_ptr<CommandLine> line = make_command_line();
  parse_call(*line, *line->merge, parts, options);
  const MergeArguments& args = line->merge_args;
  std::string json, printed;
  std::vector<std::string> breached;
  {
    py::gil_scoped_release release;
    const MergedReport merged = merge_parts(args.parts, "roving.merge");
    json = to_json(merged.report).dump();
    if (!args.json_path.empty() && args.json_path != "-") {
      AtomicFile file(args.json_path);
      std::fputs((to_json(merged.report).dump(2) + "\n").c_str(), file.stream());
      file.commit();
    }
    if (args.json_path == "-") printed = to_json(merged.report).dump(2);
    breached = breached_gates(merged.plan.gates, gate_values(merged.report), merged.plan.gate_on);
  }
  if (!printed.empty()) py::print(printed);
  py::dict result = parse_json(json);
  result["breached_gates"] = breached;
  return result;
}

int batch(const py::args& pairs, const py::kwargs& all_options) {
  py::object callback = py::none();
  const py::kwargs options = without_progress(all_options, callback);
  const std::unique_ptr<CommandLine> line = make_command_line();
  parse_call(*line, *line->batch, pairs, options);
  line->batch_args.defaults.command_line = "roving.batch";
  references_may_leave_folder(line->trust_references);
  require_materials(line->strict_materials);
  std::string stage = "starting";
  const InterruptScope interrupt;
  py::gil_scoped_release release;
  return run_batch(line->batch_args, stage, listener(callback));
}

}  // namespace

PYBIND11_MODULE(roving, m) {
  m.doc() =
      "Shape dissimilarity between 3D models: Z-buffer surface roving, Embree and CGAL references, baselines";
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  m.attr("Warning") = warning_category();
  m.attr("RovingWarning") = warning_category();  // the same class, by the name warnings filters often use
  // The version and commit the module was built from: the reports' "tool" says the same.
  m.attr("__version__") = tool_json()["version"].get<std::string>();
  m.attr("commit") = tool_json()["commit"].get<std::string>();
  m.attr("methods") = method_names();
  m.attr("resolved_by") = py::dict(py::arg("no-hit") = static_cast<int>(Resolution::Unresolved),
                                   py::arg("view") = static_cast<int>(Resolution::View),
                                   py::arg("camera") = static_cast<int>(Resolution::Camera));

  m.def("measure", &measure, py::arg("reference"), py::arg("test"),
        R"doc(measure(reference, test, **options) -> dict

`roving measure REF TEST` from Python: every option of the command is a keyword argument, named as the
option with _ for - (max_error='2%', samples='area:100000', symmetric=True, ibsm=True,
fail_above=['usiad=1%'], json='report.json', samples_out='samples.csv', ...), with the command's
defaults, checks and messages (`roving measure --help` lists them). A flag is True to set it; None
leaves an option at its default.

reference, test: a path (any format the tool reads); an N x 3 array of points; a (vertices, faces)
  pair of arrays (N x 3 floats,
  M x 3 vertex indices); an object with `vertices` and `faces` or `triangles` (trimesh, Open3D's
  TriangleMesh; vertex_colors taken where present, floats on [0, 1] or 8-bit integers); or an object
  with `points` (Open3D's PointCloud; its normals and colors where present, otherwise PCA normals).
  A mesh's float64 vertices and int32 faces in C order (Open3D's) are read in place, with no copy (do
  not change them during the call); other types and layouts, and point clouds, are copied once.

Returns the JSON report (`roving measure --json`) as a dict, every number equal to the command's,
plus 'breached_gates' (the --fail-above gates breached: the command's exit status 3) and the
per-sample columns of --samples-out as NumPy arrays owning the library's buffers (no copy): under
'per_sample', or each direction's under --symmetric: positions and normals (K x 3), d (signed; 0 where
hit is False), hit (bool), element (REF's face or vertex), weight (area), test_point (K x 3: the
point on TEST the distance was measured to; NaN for a no-hit, or a closest point whose face the
method does not name), barycentric (K x 3: test_point's weights of hit_face's corners; NaN where
there is no face), and where they apply hit_face (TEST's face at the hit), resolved_by (codes in
roving.resolved_by), reference_colour, test_colour (K x 3, 8-bit code values) and delta_e (CIEDE2000).

per_sample: False leaves the per-sample arrays out; then, as in the command, a binary PLY or STL, or OBJ, REF with
  more faces than `chunk` is read and measured a block of faces at a time (report["samples"]
  ["streamed"]), in the command's memory rather than about 85 bytes a face.

progress: a function progress(stage, what, done, total) called as the measurement goes (each stage,
  then at most ten times a second: e.g. 'measuring', 'cameras', 40960, 69451); what it raises stops
  the measurement and is raised. Ctrl-C stops it too (KeyboardInterrupt) at its next report of
  progress; no output file is written by a stopped call.

Raises roving.Error (a ValueError) with the command's one-line message.

Example:
    >>> r = roving.measure("ref.ply", "test.ply", method="cooperative", max_error="2%")
    >>> r["statistics"]["usiad"], r["per_sample"]["d"][r["per_sample"]["hit"]].max())doc");

  m.def("merge", &merge, R"doc(merge(*parts, json=None, quiet=False) -> dict

`roving merge PART...` from Python: the report one process gives, as a dict (as roving.measure's,
with `breached_gates` for the gates the shards were given, and no per_sample arrays), from the parts
of one pair's shards, each written by roving.measure(..., shard='I/N', shard_out='PART') or the
command. json writes it to a file as the command's --json does.

Example:
    >>> for i in range(4):
    ...     roving.measure("ref.ply", "test.ply", samples="area:1000000", shard=f"{i}/4", shard_out=f"p{i}.part")
    >>> report = roving.merge(*[f"p{i}.part" for i in range(4)])
    >>> report["statistics"]["usiad"]
)doc");
  m.def("batch", &batch, R"doc(batch(*pairs, **options) -> int

`roving batch PAIRS...` from Python: a manifest (.csv or .jsonl) or two folders, with every option of
the command as a keyword argument (out='results', shard='0/4', html=True, merge=True, and the options of
roving.measure). Writes the per-pair reports and out/summary.csv as the command does and returns its
exit status: 0, or 4 when some pair failed (recorded in the summary with its error).

progress: as roving.measure's, with a stage per pair ('pair 2/40: a.ply vs b.ply, about 30 s
  left') before that pair's own. What it raises, and Ctrl-C (KeyboardInterrupt), stops the batch
  at once and is raised: the pairs done keep their reports, the pair under way leaves nothing, and
  running the same batch again measures only what is left.

Example:
    >>> roving.batch("pairs.csv", out="batch-results", method="embree")
    >>> import csv; rows = list(csv.DictReader(open("batch-results/summary.csv"))))doc");
}
