// The extension module dampbench._core; python/dampbench/__init__.py is its public face.
#include "python/src/bindings.hpp"

PYBIND11_MODULE(_core, m) {
  using namespace dampbench::python;
  m.doc() = "dampbench's engine (the public API is the dampbench package)";
  m.attr("version") = DAMPBENCH_VERSION;
  m.attr("build_flags") = DAMPBENCH_BUILD_FLAGS;
  bind_errors(m);
  bind_records(m);
  bind_fit(m);
  bind_simulate(m);
  bind_store(m);
  bind_control(m);
}
