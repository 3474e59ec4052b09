// The compiled half of the Python package `grainflow` (python/grainflow/): cases loaded and
// checked by the same code as the command line, run sessions (run/run_session.hpp) and the
// engine's particle arrays as numpy views. The Python half gives them their user-facing shape.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/config/case_writer.hpp"
#include "grainflow/config/case_parser.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/core/version.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/run/check_report.hpp"
#include "grainflow/run/interrupt.hpp"
#include "grainflow/run/run_session.hpp"

namespace py = pybind11;
using namespace grainflow;

namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double), "a Vec3 array is an N x 3 array of doubles");

// A case as loaded: its text, where it came from (relative paths in it are read from there) and
// the assignments made to it, in order; validated by load_case like `grainflow run --set`.
struct CaseCore {
  std::string text, label;
  std::vector<std::string> overrides;
  CaseConfig config;

  CaseCore(std::string case_text, std::string case_label, std::vector<std::string> assignments)
      : text(std::move(case_text)), label(std::move(case_label)), overrides(std::move(assignments)) {
    config = load_case_from_string(text, label, overrides);
  }
  std::string resolved_toml() const { return write_case_toml(config); }
  std::string check_text() const {
    std::ostringstream out;
    run::print_check(config, out);
    return out.str();
  }
};

// A run session and the numpy views of its particles; a view keeps the session alive (its base).
class SessionCore : public std::enable_shared_from_this<SessionCore> {
 public:
  SessionCore(const CaseCore& c, const std::string& output, int threads, std::vector<std::string> command_line) {
    run::RunOptions options;
    options.output_directory = output;
    options.threads = threads;
    options.quiet = true;
    session_ = run::open_session(c.config, options, command_line);
  }
  run::RunSession& session() { return *session_; }

  // Advances with the GIL released; SIGINT raises KeyboardInterrupt at the step it stopped at.
  template <class Advance>
  void advance(Advance&& advance) {
    int signal = 0;
    {
      run::InterruptScope interrupts;
      py::gil_scoped_release unlocked;
      advance(*session_);
      signal = session_->take_interrupt();
    }
    if (signal != 0) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw py::error_already_set();
    }
  }

  py::array vectors(std::vector<Vec3>& values, bool writable, py::handle base) {
    py::array view(py::dtype::of<double>(), {static_cast<py::ssize_t>(values.size()), py::ssize_t{3}},
                   {static_cast<py::ssize_t>(sizeof(Vec3)), static_cast<py::ssize_t>(sizeof(double))},
                   reinterpret_cast<double*>(values.data()), base);
    if (!writable) py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return view;
  }
  template <class T>
  py::array scalars(const T* values, std::size_t n, py::handle base) {
    py::array view(py::dtype::of<T>(), {static_cast<py::ssize_t>(n)}, {static_cast<py::ssize_t>(sizeof(T))}, values,
                   base);
    py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return view;
  }

 private:
  std::unique_ptr<run::RunSession> session_;
};

// grainflow.errors.InputError(message, file, key, reason) and RunError(message), raised from the
// C++ errors of the same names.
void translate_errors(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const InputError& e) {
    py::object type = py::module_::import("grainflow.errors").attr("InputError");
    py::object value = type(e.what(), e.file(), e.key(), e.reason());
    PyErr_SetObject(type.ptr(), value.ptr());
  } catch (const RunError& e) {
    py::object type = py::module_::import("grainflow.errors").attr("RunError");
    PyErr_SetObject(type.ptr(), type(e.what()).ptr());
  }
}

}  // namespace

PYBIND11_MODULE(_grainflow, m) {
  m.doc() = "grainflow's engines and case loader (use the package grainflow, not this module)";
  m.attr("__version__") = kVersion;
  py::register_exception_translator(&translate_errors);

  py::class_<CaseCore>(m, "CaseCore")
      .def(py::init<std::string, std::string, std::vector<std::string>>(), py::arg("text"), py::arg("label"),
           py::arg("overrides"))
      .def_static("read_file", &read_case_file, py::arg("path"))
      .def_readonly("text", &CaseCore::text)
      .def_readonly("label", &CaseCore::label)
      .def_readonly("overrides", &CaseCore::overrides)
      .def_property_readonly("engine", [](const CaseCore& c) { return c.config.engine.kind; })
      .def_property_readonly("dimension", [](const CaseCore& c) { return c.config.engine.dimension; })
      .def("resolved_toml", &CaseCore::resolved_toml)
      .def("check_text", &CaseCore::check_text);

  py::class_<SessionCore, std::shared_ptr<SessionCore>>(m, "SessionCore")
      .def(py::init<const CaseCore&, const std::string&, int, std::vector<std::string>>(), py::arg("case"),
           py::arg("output"), py::arg("threads"), py::arg("command_line"))
      .def_property_readonly("event_driven", [](SessionCore& s) { return s.session().event_driven(); })
      .def_property_readonly("dimension", [](SessionCore& s) { return s.session().dimension(); })
      .def_property_readonly("time", [](SessionCore& s) { return s.session().time(); })
      .def_property_readonly("steps", [](SessionCore& s) { return s.session().steps(); })
      .def_property_readonly("time_step", [](SessionCore& s) { return s.session().time_step(); })
      .def_property_readonly("end_time", [](SessionCore& s) { return s.session().end_time(); })
      .def_property_readonly("last_step", [](SessionCore& s) { return s.session().last_step(); })
      .def_property_readonly("finished", [](SessionCore& s) { return s.session().finished(); })
      .def_property_readonly("output_directory", [](SessionCore& s) { return s.session().output_directory(); })
      .def("advance_steps",
           [](SessionCore& s, long long n) { s.advance([n](run::RunSession& r) { r.advance_steps(n); }); })
      .def("advance_time", [](SessionCore& s, double dt) { s.advance([dt](run::RunSession& r) { r.advance_time(dt); }); })
      .def("run",
           [](SessionCore& s) {
             int status = 0;
             s.advance([&status](run::RunSession& r) { status = r.run(); });
             return status;
           })
      .def("finish", [](SessionCore& s) { return s.session().finish(); })
      .def("particles_written", [](SessionCore& s, bool positions) { s.session().particles_written(positions); })
      .def("particle_count", [](SessionCore& s) { return s.session().particles().size(); })
      .def("add_particles",
           [](SessionCore& s, const std::vector<int>& species, py::array_t<double, py::array::c_style | py::array::forcecast> x,
              py::array_t<double, py::array::c_style | py::array::forcecast> v) {
             const auto vectors = [](const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
               if (a.ndim() != 2 || a.shape(1) != 3) throw py::value_error("positions and velocities are N x 3 arrays");
               std::vector<Vec3> out(static_cast<std::size_t>(a.shape(0)));
               for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec3{a.at(i, 0), a.at(i, 1), a.at(i, 2)};
               return out;
             };
             const std::vector<Vec3> position = vectors(x), velocity = vectors(v);
             if (velocity.size() != position.size() || species.size() != position.size())
               throw py::value_error("as many species and velocities as positions");
             return s.session().add_particles(species, position, velocity);
           })
      .def("remove_particles", [](SessionCore& s, const std::vector<std::uint32_t>& ids) { s.session().remove_particles(ids); })
      // Views of the engine's arrays (lifetime: until the next advance, which may re-sort them).
      .def("array",
           [](std::shared_ptr<SessionCore> s, const std::string& name, bool writable) -> py::array {
             ParticleStore& p = s->session().particles();
             py::object base = py::cast(s);
             if (name == "position") return s->vectors(p.position, writable, base);
             if (name == "velocity") return s->vectors(p.velocity, writable, base);
             if (name == "angular_velocity") return s->vectors(p.angular_velocity, writable, base);
             if (name == "force") return s->vectors(p.force, false, base);
             if (name == "torque") return s->vectors(p.torque, false, base);
             if (name == "radius") return s->scalars(p.radius.data(), p.size(), base);
             if (name == "mass") return s->scalars(p.mass.data(), p.size(), base);
             if (name == "id") return s->scalars(p.id.data(), p.size(), base);
             if (name == "species") return s->scalars(p.species.data(), p.size(), base);
             if (name == "motion") return s->scalars(reinterpret_cast<const std::uint8_t*>(p.motion.data()), p.size(), base);
             throw py::key_error("no particle array '" + name + "'");
           });
}
