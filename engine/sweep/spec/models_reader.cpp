// Models: ids, law fixtures or [[models]] tables, with the [bounds] table; every model is built once here so
// that a bad law, bound or name is reported before anything runs.
#include <cmath>

#include "engine/sweep/held_fit.hpp"
#include "engine/sweep/spec/reader.hpp"
#include "models/fixtures.hpp"
#include "models/registry.hpp"

namespace dampbench::sweep::spec_file {

namespace {

/// `hold = { from, split, free, first, next, order }` (HoldSpec); the entry's laws then fix the held parameters at
/// placeholders (held_laws), which each group replaces by the fit it holds to.
void read_hold(const Reader& r, const toml::node& n, const std::string& key, ModelSpec& m) {
  if (!n.is_table()) r.fail(&n, key, "expected { from = \"model\", split = \"split\", free = [\"parameter\", ...], first, next, order, mean }");
  const toml::table& t = *n.as_table();
  r.only_keys(t, key, {"from", "split", "free", "first", "next", "order", "mean"});
  HoldSpec h;
  h.laws = m.laws;
  h.from = r.required_string(t, "from", key);
  h.split = r.required_string(t, "split", key);
  h.free = r.strings(t, "free", key);  // may be empty when the entry's laws are what is fitted
  h.first = r.number(t, "first", key).value_or(0.4);
  if (!(h.first > 0 && h.first <= 1)) r.fail(t.get("first"), Reader::join(key, "first"), "expected a fraction in (0, 1]");
  h.next = r.number(t, "next", key).value_or(0.0);
  if (!(h.next >= 0 && h.next <= 1)) r.fail(t.get("next"), Reader::join(key, "next"), "expected a fraction in [0, 1]");
  h.order = r.string(t, "order", key).value_or("");
  h.mean = r.boolean(t, "mean", key, false);
  if (h.mean && (t.contains("first") || t.contains("next") || t.contains("order")))
    r.fail(&n, key, "mean = true holds to the means over the split's fit sets and leaves the free parameters their own "
                    "bounds: drop first, next and order");
  if (!h.mean && (h.next > 0) == h.order.empty())
    r.fail(&n, key, "next (a window around the fit before) and order (the variable the fits follow) go together");
  if (m.model.empty() || chooses_laws(m) || !m.start.empty())
    r.fail(&n, key, "hold needs a registered 'model' whose laws are its own (not \"auto\", no start)");
  if (h.from == m.name) r.fail(t.get("from"), Reader::join(key, "from"), "a model cannot hold to its own fit");
  m.hold = std::move(h);
  r.check(&n, key, [&] {
    m.laws = held_laws(m, find_model(m.model));
    return 0;
  });
}

/// `narrow = { rounds, from }` (NarrowingSpec): a law model of poly(VAR,1) and shared parameters, not with another
/// start or a hold.
void read_narrow(const Reader& r, const toml::node& n, const std::string& key, ModelSpec& m) {
  if (!n.is_table()) r.fail(&n, key, "expected { rounds = 3, from = \"default\" | \"wide\" }");
  const toml::table& t = *n.as_table();
  r.only_keys(t, key, {"rounds", "from"});
  NarrowingSpec s;
  const double rounds = r.number(t, "rounds", key).value_or(s.rounds);
  if (!(rounds >= 1 && rounds <= 20 && rounds == std::floor(rounds)))
    r.fail(t.get("rounds"), Reader::join(key, "rounds"), "expected a whole number of rounds from 1 to 20");
  s.rounds = static_cast<int>(rounds);
  s.from = r.string(t, "from", key).value_or(s.from);
  if (s.from != "default" && s.from != "wide")
    r.fail(t.get("from"), Reader::join(key, "from"),
           fmt::format("expected \"default\" (the model's box for the records) or \"wide\" ([-1e8, 1e8]), got '{}'", s.from));
  if (m.model.empty() || m.laws.empty() || chooses_laws(m) || !m.start.empty() || m.hold || !m.bounds.empty())
    r.fail(&n, key, "narrow needs a registered 'model' with its own 'laws' (not \"auto\"), and no start, hold or bounds: "
                    "it makes the box and the start");
  r.check(&n, key, [&] {
    check_narrowable_laws(m);
    return 0;
  });
  m.narrow = s;
}

ModelSpec read_model(const Reader& r, const toml::node& n, const std::string& key) {
  ModelSpec m;
  if (n.is_string()) {
    const std::string id(*n.value<std::string>());
    // A registered model, else a law fixture; the message lists the models.
    try {
      find_model(id);
      m.model = id;
    } catch (const InputError& e) {
      try {
        find_fixture(id);
        m.fixture = id;
      } catch (const InputError&) {
        r.fail(&n, key, e.what());
      }
    }
    m.name = id;
    return m;
  }
  if (!n.is_table()) r.fail(&n, key, "expected a model id or a table { name, model | fixture, laws, bounds, optimizers, start, hold, narrow }");
  const toml::table& t = *n.as_table();
  r.only_keys(t, key, {"name", "model", "fixture", "laws", "bounds", "optimizers", "start", "hold", "narrow"});
  m.model = r.string(t, "model", key).value_or("");
  m.fixture = r.string(t, "fixture", key).value_or("");
  if (m.model.empty() == m.fixture.empty()) r.fail(&n, key, "expected exactly one of 'model' and 'fixture'");
  if (!m.model.empty()) r.check(t.get("model"), Reader::join(key, "model"), [&] { return &find_model(m.model); });
  if (!m.fixture.empty()) r.check(t.get("fixture"), Reader::join(key, "fixture"), [&] { return &find_fixture(m.fixture); });
  m.laws = r.string(t, "laws", key).value_or("");
  m.bounds = r.string(t, "bounds", key).value_or("");
  m.name = r.string(t, "name", key).value_or(m.model.empty() ? m.fixture : m.model);
  m.optimizers = r.strings(t, "optimizers", key);
  m.start = r.string(t, "start", key).value_or("");
  if (!m.start.empty() && m.start != "per-file")
    r.fail(t.get("start"), Reader::join(key, "start"), fmt::format("expected \"per-file\", got '{}'", m.start));
  if (!m.start.empty() && (m.laws.empty() || m.model.empty()))
    r.fail(t.get("start"), Reader::join(key, "start"),
           "start = \"per-file\" starts a law model from its records' own fits: it needs 'model' and 'laws'");
  if (!m.start.empty() && chooses_laws(m))
    r.fail(t.get("start"), Reader::join(key, "start"),
           "laws = \"auto\" always starts from the records' own fits: drop start");
  if (const toml::node* h = t.get("hold")) read_hold(r, *h, Reader::join(key, "hold"), m);
  if (const toml::node* nw = t.get("narrow")) read_narrow(r, *nw, Reader::join(key, "narrow"), m);
  return m;
}


}  // namespace

void read_models(const Reader& r, const toml::table& root, PartSpec& part) {
  const toml::node* models = root.get("models");
  if (!models || !models->is_array() || models->as_array()->empty())
    r.fail(models, "models", "expected a non-empty array of model ids or model tables");
  const auto& a = *models->as_array();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const toml::node& n = *a.get(i);
    const std::string key = n.is_string() ? "models" : fmt::format("models[{}]", i);
    ModelSpec m = read_model(r, n, key);
    if (part.model_index(m.name) >= 0) r.fail(&n, key, fmt::format("model name '{}' is used twice", m.name));
    part.models.push_back(std::move(m));
  }
  if (const toml::node* b = root.get("bounds")) {
    if (!b->is_table()) r.fail(b, "bounds", "expected a table [bounds] of model = \"name=lo:hi,...\"");
    for (const auto& [k, v] : *b->as_table()) {
      const std::string id(k.str());
      if (!v.is_string()) r.fail(&v, id, "expected a string \"name=lo:hi,...\"");
      const int m = part.model_index(id);
      if (m < 0) r.fail(&v, id, fmt::format("no model named '{}' in 'models'", id));
      auto& bounds = part.models[m].bounds;
      if (!bounds.empty()) bounds += ',';
      bounds += *v.value<std::string>();
    }
  }
  // Build every model once: laws, bounds and names are checked here, before anything runs.
  for (std::size_t i = 0; i < part.models.size(); ++i) {
    const ModelSpec& m = part.models[i];
    const toml::node* n = a.get(i);
    std::string key = n->is_string() ? "models" : fmt::format("models[{}]", i);
    if (const toml::node* b = root.get("bounds"); b && b->as_table()->get(m.name)) {
      n = b->as_table()->get(m.name);
      key = m.name;
    }
    r.check(n, key, [&] { return resolve_model_or_auto_base(m); });
  }
}

void check_holds(const Reader& r, const toml::table& root, const PartSpec& part) {
  for (std::size_t m = 0; m < part.models.size(); ++m) {
    if (!part.models[m].hold) continue;
    const HoldSpec& h = *part.models[m].hold;
    const toml::node* n = root.get("models")->as_array()->get(m);
    const std::string key = fmt::format("models[{}].hold", m);
    const int from = part.model_index(h.from);
    if (from < 0) r.fail(n, key + ".from", fmt::format("no model named '{}' in 'models'", h.from));
    if (part.models[from].hold) r.fail(n, key + ".from", fmt::format("'{}' holds to another fit itself", h.from));
    const int split = part.split_index(h.split);
    if (split < 0) r.fail(n, key + ".split", fmt::format("no split named '{}'", h.split));
    const auto pairs = part.pairs(part.splits[split]);
    if (std::none_of(pairs.begin(), pairs.end(), [&](const auto& p) { return p.first == from; }))
      r.fail(n, key + ".split", fmt::format("split '{}' does not fit model '{}'", h.split, h.from));
  }
}

void check_auto_laws(const Reader& r, const toml::table& root, const PartSpec& part) {
  for (std::size_t m = 0; m < part.models.size(); ++m) {
    const ModelSpec& model = part.models[m];
    if (!chooses_laws(model)) continue;
    const toml::node* n = root.get("models")->as_array()->get(m);
    const std::string key = fmt::format("models[{}]", m);
    for (const SplitSpec& split : part.splits)
      for (const auto& [pm, po] : part.pairs(split)) {
        if (pm != static_cast<int>(m)) continue;
        if (split.by == SplitSpec::By::each)
          r.fail(n, key,
                 fmt::format("laws = \"auto\" chooses laws across the records of a group, and {} fits each dataset "
                             "alone (by = \"each\"): give it by = \"all\" or a list of variables, or leave this model "
                             "out of its models",
                             split.name.empty() ? "the default split (no [[splits]])" : fmt::format("split '{}'", split.name)));
        if (part.optimizers[po].auto_budget)
          r.fail(n, key,
                 fmt::format("laws = \"auto\" fits at a fixed budget, as fit --laws auto does, and optimizer '{}' has "
                             "the automatic budget: give it population and iterations (or budget = \"fixed\"), or "
                             "name this model's optimizers",
                             part.optimizers[po].label));
      }
  }
}

}  // namespace dampbench::sweep::spec_file
