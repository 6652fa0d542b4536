// [reproduction] of a sweep file: which published numbers the part's tables stand beside, and what its records are.
#include <filesystem>

#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep::spec_file {

void read_reproduction(const Reader& r, const toml::table& root, PartSpec& part, bool check_files) {
  const toml::node* node = root.get("reproduction");
  if (!node) return;
  const toml::table* t = node->as_table();
  if (!t) r.fail(node, "reproduction", "expected a table: [reproduction] with published, data and truth");
  r.only_keys(*t, "reproduction", {"published", "data", "truth", "truth_is_compared_model", "numbers_not_comparable", "rows"});
  ReproductionSpec spec;
  const std::string folder = std::filesystem::path(r.path()).parent_path().string();
  spec.published = resolve_path(r.required_string(*t, "published", "reproduction"), folder);
  if (check_files && !std::filesystem::exists(spec.published))
    r.fail(t->get("published"), "reproduction.published", fmt::format("no file '{}'", spec.published));
  spec.data = r.required_string(*t, "data", "reproduction");
  if (spec.data != "real" && spec.data != "synthetic")
    r.fail(t->get("data"), "reproduction.data", fmt::format("expected real or synthetic, got '{}'", spec.data));
  spec.truth = r.string(*t, "truth", "reproduction").value_or("");
  if (spec.data == "synthetic" && spec.truth.empty())
    r.fail(node, "reproduction.truth", "synthetic records need their truth named (what made them)");
  spec.truth_is_compared_model = r.boolean(*t, "truth_is_compared_model", "reproduction", false);
  spec.numbers_not_comparable = r.string(*t, "numbers_not_comparable", "reproduction").value_or("");
  const std::string rows = r.string(*t, "rows", "reproduction").value_or("paper");
  if (rows != "paper" && rows != "ours")
    r.fail(t->get("rows"), "reproduction.rows", fmt::format("expected paper or ours, got '{}'", rows));
  spec.claims_on_our_rows = rows == "ours";
  if (spec.claims_on_our_rows && spec.numbers_not_comparable.empty())
    r.fail(node, "reproduction.numbers_not_comparable", "rows = \"ours\" needs the reason the numbers are not comparable");
  part.reproduction = std::move(spec);
}

}  // namespace dampbench::sweep::spec_file
