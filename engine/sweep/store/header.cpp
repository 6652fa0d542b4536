// The header of a store: the plan it was written for (parts, models, optimizers, splits, datasets, fit sets),
// written once when the store is created and read back for tables, reports and verify.
#include <map>

#include <nlohmann/json.hpp>

#include "engine/sweep/store.hpp"
#include "engine/sweep/store/schema.hpp"
#include "engine/sweep/store/sqlite_access.hpp"

namespace dampbench::sweep {

using json = nlohmann::json;
using store_db::count;
using store_db::json_column;
using store_db::metric_list;
using store_db::now_utc;
using store_db::Stmt;

int StoreHeader::model(int part, int i) const {
  for (int k = 0, n = 0; k < static_cast<int>(models.size()); ++k)
    if (models[k].part == part && n++ == i) return k;
  return -1;
}
int StoreHeader::optimizer(int part, int i) const {
  for (int k = 0, n = 0; k < static_cast<int>(optimizers.size()); ++k)
    if (optimizers[k].part == part && n++ == i) return k;
  return -1;
}
int StoreHeader::dataset(int part, int i) const {
  // Datasets are stored part by part: find the part's first, then offset.
  for (int k = 0; k < static_cast<int>(datasets.size()); ++k)
    if (datasets[k].part == part) {
      const int j = k + i;
      return j < static_cast<int>(datasets.size()) && datasets[j].part == part ? j : -1;
    }
  return -1;
}
int StoreHeader::fitset(int part, int split, int i) const {
  for (int k = 0; k < static_cast<int>(fitsets.size()); ++k)
    if (fitsets[k].part == part && fitsets[k].split == split) {
      const int j = k + i;
      return j < static_cast<int>(fitsets.size()) && fitsets[j].part == part && fitsets[j].split == split ? j : -1;
    }
  return -1;
}
std::string StoreHeader::split_name(int part, int i) const {
  for (int k = 0, n = 0; k < static_cast<int>(splits.size()); ++k)
    if (splits[k].first == part && n++ == i) return splits[k].second;
  return "";
}

namespace store_db {

void insert_header(sqlite3* db, const StoreHeader& h) {
  {
    Stmt s(db, "INSERT INTO meta(key, value) VALUES(?, ?)");
    for (const auto& [k, v] : std::vector<std::pair<std::string, std::string>>{
             {"format", std::to_string(kStoreFormat)}, {"name", h.name}, {"spec_hash", h.spec_hash},
             {"spec_path", h.spec_path}, {"dampbench_version", h.dampbench_version}, {"build_flags", h.build_flags},
             {"groups", std::to_string(h.groups)}, {"tasks", std::to_string(h.tasks)}, {"metrics", metric_list()},
             {"created", now_utc()}})
      s.bind(1, k).bind(2, v).run();
    if (!h.shard.empty()) s.bind(1, std::string("shard")).bind(2, h.shard).run();
  }
  {
    Stmt s(db, "INSERT INTO parts VALUES(?, ?, ?, ?, ?, ?, ?)");
    for (int p = 0; p < static_cast<int>(h.parts.size()); ++p) {
      const auto& x = h.parts[p];
      s.bind(1, p).bind(2, x.name).bind(3, x.title).bind(4, x.path).bind(5, x.source)
          .bind(6, static_cast<long long>(x.seed)).bind(7, x.runs).run();
    }
  }
  {
    Stmt s(db, "INSERT INTO models VALUES(?, ?, ?, ?, ?, ?, ?, ?)");
    std::map<int, int> n;
    for (const auto& m : h.models)
      s.bind(1, m.part).bind(2, n[m.part]++).bind(3, m.name).bind(4, m.model_id).bind(5, m.fixture).bind(6, m.laws)
          .bind(7, m.bounds).bind(8, json(m.params).dump()).run();
  }
  {
    Stmt s(db, "INSERT INTO optimizers VALUES(?, ?, ?, ?, ?, ?, ?)");
    std::map<int, int> n;
    for (const auto& o : h.optimizers)
      s.bind(1, o.part).bind(2, n[o.part]++).bind(3, o.label).bind(4, o.name).bind(5, o.population)
          .bind(6, o.iterations).bind(7, json(o.settings).dump()).run();
  }
  {
    Stmt s(db, "INSERT INTO splits VALUES(?, ?, ?)");
    std::map<int, int> n;
    for (const auto& [part, name] : h.splits) s.bind(1, part).bind(2, n[part]++).bind(3, name).run();
  }
  {
    Stmt s(db, "INSERT INTO datasets VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    std::map<int, int> n;
    for (const auto& d : h.datasets) {
      json vars = json::object();
      for (const auto& [k, v] : d.variables) vars[k] = v;
      s.bind(1, d.part).bind(2, n[d.part]++).bind(3, d.name).bind(4, d.collection).bind(5, d.label).bind(6, d.path)
          .bind(7, d.samples).bind(8, d.hash).bind(9, vars.dump(-1, ' ', false, json::error_handler_t::replace))
          .bind(10, d.error).run();
    }
  }
  {
    Stmt s(db, "INSERT INTO fitsets VALUES(?, ?, ?, ?, ?, ?)");
    std::map<std::pair<int, int>, int> n;
    for (const auto& f : h.fitsets)
      s.bind(1, f.part).bind(2, f.split).bind(3, n[{f.part, f.split}]++).bind(4, f.label).bind(5, json(f.fit).dump())
          .bind(6, json(f.predict).dump()).run();
  }
}

}  // namespace store_db

StoreHeader Store::header() const {
  StoreHeader h;
  h.name = meta("name");
  h.spec_hash = meta("spec_hash");
  h.spec_path = meta("spec_path");
  h.dampbench_version = meta("dampbench_version");
  h.build_flags = meta("build_flags");
  h.shard = meta("shard");
  h.groups = count(meta("groups"), "meta groups");
  h.tasks = count(meta("tasks"), "meta tasks");
  {
    Stmt s(db_, "SELECT name, title, path, source, seed, runs FROM parts ORDER BY part");
    while (s.step())
      h.parts.push_back({s.text(0), s.text(1), s.text(2), s.text(3), static_cast<std::uint64_t>(s.integer(4)),
                         static_cast<int>(s.integer(5))});
  }
  {
    Stmt s(db_, "SELECT part, name, model_id, fixture, laws, bounds, params FROM models ORDER BY part, model");
    while (s.step())
      h.models.push_back({static_cast<int>(s.integer(0)), s.text(1), s.text(2), s.text(3), s.text(4), s.text(5),
                          json_column<std::vector<std::string>>(s, 6, "models.params")});
  }
  {
    Stmt s(db_, "SELECT part, label, name, population, iterations, settings FROM optimizers ORDER BY part, optimizer");
    while (s.step())
      h.optimizers.push_back({static_cast<int>(s.integer(0)), s.text(1), s.text(2), static_cast<int>(s.integer(3)),
                              static_cast<int>(s.integer(4)),
                              json_column<std::map<std::string, std::string>>(s, 5, "optimizers.settings")});
  }
  {
    Stmt s(db_, "SELECT part, name FROM splits ORDER BY part, split");
    while (s.step()) h.splits.emplace_back(static_cast<int>(s.integer(0)), s.text(1));
  }
  {
    Stmt s(db_, "SELECT part, name, collection, label, path, hash, error, samples, variables FROM datasets "
                "ORDER BY part, dataset");
    while (s.step()) {
      StoreDataset d{static_cast<int>(s.integer(0)), s.text(1), s.text(2), s.text(3), s.text(4), s.text(5), s.text(6),
                     s.integer(7), {}};
      const json vars = json_column<json>(s, 8, "datasets.variables");
      for (const auto& [k, v] : vars.items())
        if (v.is_number()) d.variables[k] = v.get<double>();
      h.datasets.push_back(std::move(d));
    }
  }
  {
    Stmt s(db_, "SELECT part, split, label, fit, predict FROM fitsets ORDER BY part, split, fitset");
    while (s.step())
      h.fitsets.push_back({static_cast<int>(s.integer(0)), static_cast<int>(s.integer(1)), s.text(2),
                           json_column<std::vector<int>>(s, 3, "fitsets.fit"), json_column<std::vector<int>>(s, 4, "fitsets.predict")});
  }
  return h;
}

}  // namespace dampbench::sweep
