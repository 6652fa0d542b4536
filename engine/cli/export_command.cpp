#include "engine/cli/export_command.hpp"

#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/text_file.hpp"
#include "engine/export/c_export.hpp"

namespace dampbench::cli {

void add_export_options(CLI::App* c, ExportOptions& o) {
  add_model_by_name_options(c, o.model);
  c->add_option("--lang", o.lang, "c (default; C99, no dependency but libm)");
  c->add_option("--substeps", o.substeps, "fixed RK4 sub-steps per step, as simulate --fixed-step (default 4)");
  c->add_option("-o,--output", o.output, "folder for dampbench_model.h and dampbench_model.c")->required();
}

ExportedModel run_export(const ExportOptions& o) {
  if (o.lang != "c") throw InputError(fmt::format("--lang: expected c, got '{}'", o.lang));
  const LoadedModel loaded = load_named_model(o.model, "export");
  const std::string description =
      o.model.model_file.empty() ? "From the command line's parameters."
                                 : fmt::format("From {} (metric {} {:.6g} on the fitted records).", o.model.model_file,
                                               loaded.file.metric, loaded.file.fitted_value);
  return {exporting::export_c(*loaded.model.model, loaded.params, o.substeps, description),
          std::string(loaded.model.model->id())};
}

int export_command(const ExportOptions& o) {
  if (!std::filesystem::is_directory(o.output))
    throw InputError(fmt::format("-o: '{}' is not a folder (create it first)", o.output));
  // Both files are made before either is written, so a model the exporter refuses leaves no file behind.
  const ExportedModel e = run_export(o);
  const std::filesystem::path dir(o.output);
  write_text_file((dir / "dampbench_model.h").string(), e.c.header);
  write_text_file((dir / "dampbench_model.c").string(), e.c.source);
  std::cout << fmt::format("wrote {} and {} ({}, {} RK4 sub-steps per step)\n", (dir / "dampbench_model.h").string(),
                           (dir / "dampbench_model.c").string(), e.model_id, o.substeps);
  return 0;
}

}  // namespace dampbench::cli
