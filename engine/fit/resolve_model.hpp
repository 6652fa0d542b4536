#pragma once
// The model a fit identifies, made from its names: a registered model or a published law fixture, optionally
// with parameter laws, and its search box. `fit`, `simulate`, `evaluate`, `compare` and every sweep group resolve
// their models here, so that a model named the same way is the same model wherever it is fitted.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "engine/model/bounds.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

/// A model by name, as a command line or a sweep file gives it.
struct ModelChoice {
  std::string name;     ///< id of a law model built here ("" : the law model's own id); a sweep's label
  std::string model;    ///< registered model id (models/registry.hpp) ...
  std::string fixture;  ///< ... or a law fixture (models/fixtures.hpp)
  std::string laws;     ///< parse_laws text on the model's parameters
  std::string bounds;   ///< "name=lo:hi,..." overrides (SI)
  /// "--" on the command line: messages then name the options --laws and --bounds rather than a file's keys.
  std::string option_prefix;
};

/// A model made ready to identify: the model object (owned when a law model or a fixture built it), a fixture's
/// published coefficients, and its bounds.
struct ResolvedModel {
  std::vector<std::shared_ptr<const Model>> keep;  ///< law models (and a fixture under them) owned here
  const Model* model = nullptr;
  std::vector<double> defaults;  ///< a fixture's published coefficients (empty otherwise)
  Bounds bounds;                 ///< fixed defaults with the overrides (checked when resolved)
  std::string bounds_override;   ///< the choice's `bounds`
  std::string bounds_option;     ///< how messages name the overrides ("bounds" or "--bounds")

  /// The box for fitting these records: the record-scaled defaults (Model::record_bounds_rules) with the
  /// overrides.
  [[nodiscard]] Bounds bounds_for(std::span<const Signals* const> records, RecordBox box = RecordBox::joint) const;
};

/// `laws = "auto"` (`fit --laws auto`, a sweep's `laws = "auto"`): each fit chooses its own laws
/// (engine/fit/law_selection.hpp).
inline bool chooses_laws(const ModelChoice& choice) { return choice.laws == "auto"; }

/// Builds the model of a choice; InputError for unknown names, bad laws or bad bounds ("auto" is not a law here).
ResolvedModel resolve_model(const ModelChoice& choice);

/// The same, where a choice may choose its laws (`fit`, sweeps): such a choice resolves to the registered model the
/// laws will act on (no fixture, no bounds: the coefficients are not known before the laws are).
ResolvedModel resolve_model_or_auto_base(const ModelChoice& choice);

}  // namespace dampbench
