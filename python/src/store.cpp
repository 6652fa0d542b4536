// A sweep store's runs, groups and tables, and its report (filled in next).
#include "python/src/bindings.hpp"

namespace dampbench::python {

void bind_store(py::module_&) {}

}  // namespace dampbench::python
