// simulate, evaluate, models and optimizers (filled in next).
#include "python/src/bindings.hpp"

namespace dampbench::python {

void bind_simulate(py::module_&) {}

}  // namespace dampbench::python
