// pagmo2 peer of dampbench: the problem written as a pagmo user would — a user-defined problem
// whose fitness() simulates ONE candidate with plain scalar C++ — and pagmo's `de`, `sga`, `pso_gen` and `cmaes`.
//
// Problems (same equations, metric and RK4 sub-step rule as dampbench; bench/peers/README.md):
//   fvd  fvd.gv_linear_elastic  F = m·a + C·sgn(v)|v|^α + K1·x
//   bw   mrd.bouc_wen           ż = −γ|v|·sgn(z)|z|^n − β·v·|z|^n + A·v,  F = c0·v + k0(x − x0) + α·z,
//                               RK4 with ceil(dt·max|v|·600/ΔZ) sub-steps per sample interval
//   metric of_abs: trapezoid ∫|F_m − F|dt / (σ(F_m)·T)
//
// Parallelism on the 2 cores (`--threads`, default 2): pagmo 2.18 gives batch fitness evaluation
// (set_bfe, here thread_bfe) to pso_gen only — de, sga and cmaes evaluate one candidate at a time inside
// evolve(). So pso_gen runs its 50 runs one after the other with thread_bfe over the swarm, and de, sga and
// cmaes run whole runs on `--threads` worker threads at once (what an archipelago of independent islands does),
// each run's initial population evaluated by that worker. `--parallel bfe|runs` overrides this choice.
//
// Output: one JSON object per algorithm on stdout.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <sys/resource.h>

#include <oneapi/tbb/global_control.h>
#include <pagmo/algorithm.hpp>
#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/algorithms/de.hpp>
#include <pagmo/algorithms/pso_gen.hpp>
#include <pagmo/algorithms/sga.hpp>
#include <pagmo/batch_evaluators/thread_bfe.hpp>
#include <pagmo/bfe.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/types.hpp>

namespace {

/// The record as dampbench's kernels see it (engine/record/signals.cpp): SI signals, trapezoid weights,
/// duration, population σ of the measured force, and the ODE sub-steps per interval (engine/kernels/ode_kernel.hpp).
struct Record {
  std::vector<double> t, x, v, a, F, w;
  std::vector<int> substeps;  // substeps[k]: RK4 steps on [t_{k-1}, t_k]
  double duration = 0, sigma = 0, ptp = 0, vmax = 0;
  mutable std::atomic<long long> evaluations{0};
  std::size_t size() const { return t.size(); }
};

Record* load_record(const std::string& path, double substeps_per_stroke) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  auto* r = new Record;
  std::string line;
  bool header = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {  // expects t,x,v,a,F
      if (line.rfind("t,x,v,a,F", 0) != 0) throw std::runtime_error(path + ": expected header t,x,v,a,F");
      header = true;
      continue;
    }
    std::stringstream ss(line);
    std::string cell;
    double vals[5];
    for (double& d : vals) {
      std::getline(ss, cell, ',');
      d = std::stod(cell);
    }
    r->t.push_back(vals[0]);
    r->x.push_back(vals[1]);
    r->v.push_back(vals[2]);
    r->a.push_back(vals[3]);
    r->F.push_back(vals[4]);
  }
  const std::size_t n = r->size();
  if (n < 4) throw std::runtime_error(path + ": too few samples");
  r->w.assign(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double half = 0.5 * (r->t[k + 1] - r->t[k]);
    r->w[k] += half;
    r->w[k + 1] += half;
  }
  r->duration = r->t.back() - r->t.front();
  double mean = 0;
  for (double f : r->F) mean += f;
  mean /= static_cast<double>(n);
  double var = 0;
  for (double f : r->F) var += (f - mean) * (f - mean);
  r->sigma = std::sqrt(var / static_cast<double>(n));
  const auto [lo, hi] = std::minmax_element(r->x.begin(), r->x.end());
  r->ptp = *hi - *lo;
  for (double v : r->v) r->vmax = std::max(r->vmax, std::fabs(v));
  r->substeps.assign(n, 0);
  for (std::size_t k = 1; k < n; ++k) {
    const double dt = r->t[k] - r->t[k - 1];
    if (r->ptp <= 0) {
      r->substeps[k] = 1;
      continue;
    }
    // engine/kernels/ode_kernel.hpp, stroke-driven law: the larger |v| at the interval's ends
    const double v_k = std::max(std::fabs(r->v[k - 1]), std::fabs(r->v[k]));
    const double s = std::ceil(dt * v_k * substeps_per_stroke / r->ptp);
    r->substeps[k] = std::max(1, static_cast<int>(std::min(s, 1e6)));
  }
  return r;
}

inline double sign(double v) { return static_cast<double>(v > 0.0) - static_cast<double>(v < 0.0); }
inline double log_abs_clamped(double v) { return std::log(std::fabs(v) + 1e-300); }

/// fvd.gv_linear_elastic: parameters m, C, alpha, K1.
double fvd_metric(const Record& r, const double* p) {
  const double m = p[0], C = p[1], alpha = p[2], K1 = p[3];
  double acc = 0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const double v = r.v[k];
    const double F = m * r.a[k] + C * sign(v) * std::exp(alpha * log_abs_clamped(v)) + K1 * r.x[k];
    acc += r.w[k] * std::fabs(r.F[k] - F);
  }
  return acc / (r.sigma * r.duration);
}

/// mrd.bouc_wen: parameters c0, k0, x0, alpha, beta, gamma, A, n.
double bouc_wen_metric(const Record& r, const double* p) {
  const double c0 = p[0], k0 = p[1], x0 = p[2], alpha = p[3], beta = p[4], gamma = p[5], A = p[6], n = p[7];
  auto rate = [&](double z, double u) {
    const double zn = std::exp(n * log_abs_clamped(z));
    return -gamma * std::fabs(u) * sign(z) * zn - beta * u * zn + A * u;
  };
  double z = 0, acc = 0;
  bool failed = false;
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (k > 0) {
      const int ns = r.substeps[k];
      const double h = (r.t[k] - r.t[k - 1]) / ns;
      const double v0 = r.v[k - 1], dv = r.v[k] - v0;
      for (int i = 0; i < ns; ++i) {  // v interpolated linearly inside the interval (the rate has no x)
        const double va = v0 + (static_cast<double>(i) / ns) * dv, vm = v0 + ((i + 0.5) / ns) * dv,
                     vb = v0 + (static_cast<double>(i + 1) / ns) * dv;
        const double k1 = rate(z, va);
        const double k2 = rate(z + 0.5 * h * k1, vm);
        const double k3 = rate(z + 0.5 * h * k2, vm);
        const double k4 = rate(z + h * k3, vb);
        z = z + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      }
      if (!(std::fabs(z) < 1e30)) {  // dampbench's masking: failed candidate, state reset, work goes on
        failed = true;
        z = 0;
      }
    }
    const double F = c0 * r.v[k] + k0 * (r.x[k] - x0) + alpha * z;
    acc += r.w[k] * std::fabs(r.F[k] - F);
  }
  return failed ? HUGE_VAL : acc / (r.sigma * r.duration);
}

/// The pagmo user-defined problem.
struct damper_problem {
  std::shared_ptr<const Record> record;
  bool bouc_wen = false;
  pagmo::vector_double lower, upper;

  pagmo::vector_double fitness(const pagmo::vector_double& p) const {
    record->evaluations.fetch_add(1, std::memory_order_relaxed);
    const double value = bouc_wen ? bouc_wen_metric(*record, p.data()) : fvd_metric(*record, p.data());
    return {std::isfinite(value) ? value : HUGE_VAL};
  }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const { return {lower, upper}; }
  std::string get_name() const { return bouc_wen ? "mrd.bouc_wen" : "fvd.gv_linear_elastic"; }
  pagmo::thread_safety get_thread_safety() const { return pagmo::thread_safety::constant; }
};

std::vector<double> parse_list(const std::string& s) {
  std::vector<double> out;
  std::stringstream ss(s);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(std::stod(cell));
  return out;
}

struct Options {
  std::string problem, data, algorithms = "de,sga,pso_gen,cmaes", parallel;
  std::vector<double> lower, upper;
  unsigned pop = 50, gens = 100, runs = 50, seed = 1, threads = 2;
  double F = 0.5, CR = 0.9, substeps_per_stroke = 600;
};

pagmo::algorithm make_algorithm(const std::string& name, const Options& o, unsigned dim, unsigned seed) {
  const unsigned gen = o.gens - 1;  // pagmo's gen counts generations after the initial population
  if (name == "de")  // variant 7 = DE/rand/1/bin; ftol = xtol = 0: never stop early
    return pagmo::algorithm{pagmo::de(gen, o.F, o.CR, 7u, 0.0, 0.0, seed)};
  if (name == "sga")  // dampbench ga defaults: pc 0.9, SBX η_c 15, polynomial mutation 1/d with η_m 20, tournament 2
    return pagmo::algorithm{pagmo::sga(gen, 0.9, 15.0, 1.0 / dim, 20.0, 2u, "sbx", "polynomial", "tournament", seed)};
  if (name == "pso_gen")  // dampbench pso defaults: inertia form w 0.7298, c1 = c2 = 1.49618, vmax 0.5, gbest
    return pagmo::algorithm{pagmo::pso_gen(gen, 0.7298, 1.49618, 1.49618, 0.5, 1u, 1u, 4u, false, seed)};
  // Classic CMA-ES, λ = --pop, without restarts; learning rates automatic (-1). sigma0 0.3 of every range, as
  // dampbench's cmaes (pagmo scales its steps by the box widths). ftol = xtol = 0: its only early stops are
  // "best − worst of the generation < ftol" and "last step's norm < xtol", so it spends the whole budget.
  // force_bounds clips the samples into the box: otherwise fitness() runs, and the champion may lie, outside
  // the bounds dampbench keeps. memory has no effect with one evolve() per run.
  if (name == "cmaes")
    return pagmo::algorithm{pagmo::cmaes(gen, -1.0, -1.0, -1.0, -1.0, 0.3, 0.0, 0.0, false, true, seed)};
  throw std::runtime_error("unknown algorithm " + name);
}

/// CPU time (user + system) of the whole process, all threads.
double process_cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void run_algorithm(const std::string& name, const Options& o, const std::shared_ptr<Record>& record) {
  const damper_problem udp{record, o.problem == "bw", o.lower, o.upper};
  const unsigned dim = static_cast<unsigned>(o.lower.size());
  const bool bfe_mode = o.parallel.empty() ? name == "pso_gen" : o.parallel == "bfe";
  std::vector<double> values(o.runs);
  std::vector<std::vector<double>> champions(o.runs);  // so that dampbench can re-evaluate them on its own function
  record->evaluations = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_s();
  auto one_run = [&](unsigned run, bool use_bfe) {
    const unsigned seed = o.seed * 1000003u + run;
    pagmo::problem prob{udp};
    pagmo::algorithm algo = make_algorithm(name, o, dim, seed);
    if (use_bfe) {
      pagmo::population pop{prob, pagmo::bfe{pagmo::thread_bfe{}}, o.pop, seed};
      if (name == "pso_gen") algo.extract<pagmo::pso_gen>()->set_bfe(pagmo::bfe{pagmo::thread_bfe{}});
      pop = algo.evolve(pop);
      values[run] = pop.champion_f()[0];
      champions[run] = pop.champion_x();
    } else {
      pagmo::population pop{prob, o.pop, seed};
      pop = algo.evolve(pop);
      values[run] = pop.champion_f()[0];
      champions[run] = pop.champion_x();
    }
  };
  if (bfe_mode) {
    for (unsigned run = 0; run < o.runs; ++run) one_run(run, true);
  } else {
    std::atomic<unsigned> next{0};
    std::vector<std::thread> workers;
    for (unsigned i = 0; i < o.threads; ++i)
      workers.emplace_back([&] {
        for (unsigned run; (run = next.fetch_add(1)) < o.runs;) one_run(run, false);
      });
    for (auto& w : workers) w.join();
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = process_cpu_s() - cpu0;
  const long long evals = record->evaluations.load();
  const double rate = static_cast<double>(evals) * static_cast<double>(record->size()) / wall;
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  std::printf("{\"peer\": \"pagmo2\", \"problem\": \"%s\", \"algorithm\": \"%s\", \"parallel\": \"%s\", "
              "\"threads\": %u, \"runs\": %u, \"samples\": %zu, \"evaluations\": %lld, \"wall_time_s\": %.6f, "
              "\"candidate_samples_per_s\": %.6g, \"cpu_time_s\": %.6f, \"candidate_samples_per_cpu_s\": %.6g, \"best\": %.17g, \"median\": %.17g, \"worst\": %.17g, \"values\": [",
              o.problem.c_str(), name.c_str(), bfe_mode ? "thread_bfe" : "runs", o.threads, o.runs, record->size(),
              evals, wall, rate, cpu, static_cast<double>(evals) * static_cast<double>(record->size()) / cpu, sorted.front(), median(values), sorted.back());
  for (unsigned i = 0; i < o.runs; ++i) std::printf("%s%.17g", i ? ", " : "", values[i]);
  std::printf("], \"champions\": [");
  for (unsigned i = 0; i < o.runs; ++i) {
    std::printf("%s[", i ? ", " : "");
    for (std::size_t j = 0; j < champions[i].size(); ++j) std::printf("%s%.17g", j ? ", " : "", champions[i][j]);
    std::printf("]");
  }
  std::printf("]}\n");
  std::fflush(stdout);
  std::fprintf(stderr, "pagmo2 %s %s: %lld evaluations in %.2f s, %.3g candidate-samples/s, median %.6g\n",
               o.problem.c_str(), name.c_str(), evals, wall, rate, median(values));
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
        return argv[++i];
      };
      if (a == "--problem") o.problem = next();
      else if (a == "--data") o.data = next();
      else if (a == "--lower") o.lower = parse_list(next());
      else if (a == "--upper") o.upper = parse_list(next());
      else if (a == "--pop") o.pop = std::stoul(next());
      else if (a == "--gens") o.gens = std::stoul(next());
      else if (a == "--runs") o.runs = std::stoul(next());
      else if (a == "--seed") o.seed = std::stoul(next());
      else if (a == "--threads") o.threads = std::stoul(next());
      else if (a == "--F") o.F = std::stod(next());
      else if (a == "--CR") o.CR = std::stod(next());
      else if (a == "--substeps-per-stroke") o.substeps_per_stroke = std::stod(next());
      else if (a == "--algorithms") o.algorithms = next();
      else if (a == "--parallel") o.parallel = next();
      else throw std::runtime_error("unknown option " + a);
    }
    if (o.problem != "fvd" && o.problem != "bw") throw std::runtime_error("--problem fvd|bw");
    if (o.lower.size() != o.upper.size() || o.lower.size() != (o.problem == "bw" ? 8u : 4u))
      throw std::runtime_error("--lower/--upper: wrong number of bounds");
    if (o.gens < 1 || o.pop < 5 || o.runs < 1 || o.threads < 1) throw std::runtime_error("bad budget");
    if (!o.parallel.empty() && o.parallel != "bfe" && o.parallel != "runs") throw std::runtime_error("--parallel bfe|runs");
    // thread_bfe runs on oneTBB: cap it at --threads, as dampbench's --threads caps its arena.
    oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, o.threads);
    std::shared_ptr<Record> record{load_record(o.data, o.substeps_per_stroke)};
    std::stringstream algos(o.algorithms);
    std::string name;
    while (std::getline(algos, name, ',')) run_algorithm(name, o, record);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pagmo_peer: %s\n", e.what());
    return 1;
  }
  return 0;
}
