// The pipeline object: Adapter<Space, Precision, Concurrency, Geometry>
// binds the policies once and owns what passes share: the mesh, the metric
// source (an analytic metric, or interpolation), the epochs of the
// incremental passes (each pass sees only what changed since it last ran),
// the quality cache, and the reports, keyed by operator name.
//
// A pipeline is a list of stages (named functions of the adapter); a
// researcher reorders, replaces or adds stages, or runs any operation over
// a work list with run(). adapt.hpp builds the standard pipeline from it.
#pragma once

#include <metrica/allocator.hpp>
#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/operators/boundary_swap.hpp>
#include <metrica/operators/clear_way.hpp>
#include <metrica/operators/collapse.hpp>
#include <metrica/operators/interface_flip.hpp>
#include <metrica/operators/interface_swap.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/project.hpp>
#include <metrica/operators/reconnect.hpp>
#include <metrica/operators/refine_centroids.hpp>
#include <metrica/operators/refine_edges.hpp>
#include <metrica/operators/smooth.hpp>

#include <functional>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace metrica {

// Operator statistics keyed by name, in the order the names first came.
class OperatorReport {
 public:
  OperatorStats& operator[](std::string_view name) {
    for (auto& [n, s] : entries_)
      if (n == name) return s;
    entries_.emplace_back(std::string(name), OperatorStats{});
    return entries_.back().second;
  }
  // The stats of `name`, or zeros when no such operator ran.
  OperatorStats get(std::string_view name) const {
    for (const auto& [n, s] : entries_)
      if (n == name) return s;
    return {};
  }
  OperatorReport& operator+=(const OperatorReport& o) {
    for (const auto& [n, s] : o.entries_) (*this)[n] += s;
    return *this;
  }
  // Summed over every operator.
  OperatorStats total() const {
    OperatorStats t;
    for (const auto& [n, s] : entries_) t += s;
    return t;
  }
  auto begin() const { return entries_.begin(); }
  auto end() const { return entries_.end(); }
  bool empty() const { return entries_.empty(); }

 private:
  std::vector<std::pair<std::string, OperatorStats>> entries_;
};

struct CycleReport {
  int cycle = 0;  // 0.. for adaptation cycles; quality passes follow
  bool quality_phase = false;
  bool repair = false;  // a repair round of the quality phase
  std::size_t vertices = 0, tets = 0;
  OperatorReport ops;     // by operator name ("collapse", "split", "flip", "smooth", ...)
  double conformity = 0;  // share of edges in the unit band
  double min_quality = 0;
  // False for a quality pass before the phase's last: the share in range
  // is not measured there (conformity is NaN), as it decides nothing and
  // costs a listing of every edge. The worst tet is: its sweep fills the
  // quality cache the next pass's seeds read.
  bool conformity_measured = true;
  double seconds = 0;  // of this cycle
  // Of those, the cycle's end: compaction, the heap handed back, the
  // conformity and worst tet measured.
  double closing_seconds = 0;
};

struct AdaptReport {
  std::vector<CycleReport> cycles;
  OperatorReport ops;
  double seconds = 0;
  // The cycles' ends (CycleReport::closing_seconds) summed.
  double closing_seconds() const {
    double s = 0;
    for (const auto& c : cycles) s += c.closing_seconds;
    return s;
  }
};

// The smallest mean ratio of the live tets (1 with none), through the
// quality cache when `cached` (as conformity's), in blocks of 64 tets on
// C's threads.
template <MetricSpace S, class C = Serial>
double worst_quality(const Mesh& mesh, bool cached = false) {
  constexpr std::size_t kBlock = 64;
  const std::size_t nt = mesh.tet_capacity();
  const auto mins =
      C::template collect<double>((nt + kBlock - 1) / kBlock, [&](std::size_t b, std::vector<double>& part) {
        double q = 1.0;
        for (auto t = static_cast<TetId>(b * kBlock); t < std::min(nt, (b + 1) * kBlock); ++t)
          if (mesh.tet_alive(t))
            q = std::min(q, cached ? cached_mean_ratio<S>(mesh, t) : S::mean_ratio(mesh, mesh.tet(t)));
        part.push_back(q);
      });
  return mins.empty() ? 1.0 : *std::min_element(mins.begin(), mins.end());
}

// The share of edges in the unit band and, when asked, the smallest mean
// ratio (through the quality cache when `cached`: only while the cache is
// known to hold S's values, as inside an Adapter) and, when asked, the
// edges outside the band (a < b).
template <MetricSpace S, class C = Serial>
double conformity(const Mesh& mesh, double* min_quality = nullptr, bool cached = false,
                  std::vector<std::pair<VertexId, VertexId>>* out_of_band = nullptr) {
  // Edges in range and in all, per part of the edge buckets, on C's threads.
  const std::size_t parts = sweep_parts<C>(mesh.tet_capacity());
  struct alignas(64) Count {
    std::size_t in = 0, all = 0;
  };
  std::vector<Count> counts(parts);
  using Edge = std::pair<VertexId, VertexId>;
  std::vector<std::vector<Edge>> outside(out_of_band != nullptr ? parts : 0);
  for_each_mesh_edge_bucket<C>(mesh, parts, [&](std::size_t p, VertexId a, std::span<const VertexId> kept) {
    std::size_t in = 0;
    for (VertexId b : kept) {
      const bool inside = S::edge_length_in(mesh, a, b, kUnitBand);
      in += inside;
      if (!inside && out_of_band != nullptr) outside[p].emplace_back(a, b);
    }
    counts[p].in += in;
    counts[p].all += kept.size();
  });
  if (out_of_band != nullptr) {
    out_of_band->clear();
    for (const auto& part : outside) out_of_band->insert(out_of_band->end(), part.begin(), part.end());
  }
  std::size_t in = 0, all = 0;
  for (const Count& c : counts) {
    in += c.in;
    all += c.all;
  }
  if (min_quality != nullptr) *min_quality = worst_quality<S, C>(mesh, cached);
  return all == 0 ? 0.0 : static_cast<double>(in) / static_cast<double>(all);
}

template <MetricSpace S, Concurrency C, Geometry G = ModelOrFacets>
class Adapter {
 public:
  using Space = S;
  using Concurrency = C;
  using Geometry = G;

  // `metric`: when set (an analytic metric or a background), new and
  // moved vertices take it (else the Space interpolates); a background is
  // attached to the mesh (each vertex's background tet). `geometry`: where
  // boundary vertices go. The quality cache is cleared: the metric or the
  // Space may have changed since it was filled.
  explicit Adapter(Mesh& mesh, MetricSource metric = {}, const G& geometry = {})
      : mesh_(mesh), metric_(metric), geometry_(geometry) {
    if (metric_.background != nullptr) metric_.background->attach(mesh_);
    mesh_.clear_quality_cache(S::name);
    set_volume_budget(kDefaultVolumeBudget);
  }

  // Off a model, the boundary collapses of this adapter may change the
  // domain's volume by at most `relative` of its volume now, in all
  // (volume_budget.hpp). On a model the volume follows the model.
  void set_volume_budget(double relative) {
    if (!geometry_.on_model()) volume_budget_ = VolumeBudget(relative * std::abs(mesh_.volume()));
  }
  const VolumeBudget& volume_budget() const { return volume_budget_; }

  Mesh& mesh() { return mesh_; }
  const Mesh& mesh() const { return mesh_; }
  const MetricSource& metric() const { return metric_; }
  const G& geometry() const { return geometry_; }

  // Epochs of the incremental passes, by stage name: the epoch at which
  // the stage's pass last started (0: never, so it sees everything; after
  // restart_all, that epoch). Stages of one name share their epoch (the
  // cycle's two collapses; the quality phase's flips go on from the
  // cycles').
  Mesh::Epoch since(std::string_view stage) const {
    const auto it = epochs_.find(stage);
    return it == epochs_.end() ? restarted_ : it->second;
  }
  // The stage's next pass sees everything.
  void forget(std::string_view stage) { epochs_[std::string(stage)] = 0; }
  // Starts a new epoch as `stage`'s: what is touched from now on is what
  // the stage's next pass sees (a pass seeded from chosen tets).
  Mesh::Epoch mark(std::string_view stage) {
    const Mesh::Epoch e = mesh_.next_epoch();
    epochs_[std::string(stage)] = e;
    return e;
  }
  // Every stage's next pass, of a stage that ran or not, sees only what
  // changed since `epoch`.
  void restart_all(Mesh::Epoch epoch) {
    for (auto& [k, e] : epochs_) e = epoch;
    restarted_ = epoch;
  }
  // The stage running now (empty outside run_stages): the default key of
  // the passes it runs.
  const std::string& stage() const { return stage_; }
  // Runs `f(*this)` as stage `name` (no stage after it, thrown or not).
  // The heap's freed blocks go back to the kernel when it ends: a pass
  // reuses its own freed blocks, but those of the last pass, kept
  // resident, stood under the next pass's peak (allocator.hpp).
  template <class F>
  OperatorStats run_stage(const std::string& name, F&& f) {
    struct Leave {
      std::string& stage;
      ~Leave() {
        stage.clear();
        release_freed_memory();
      }
    } leave{stage_};
    stage_ = name;
    if constexpr (requires { C::follow_load(); }) C::follow_load();
    return f(*this);
  }

  // An incremental pass: `pass(mesh, options)` with
  // options.scope.changed_since set to when the pass of stage `key` last
  // started, then recorded.
  template <class Options, class Pass>
  OperatorStats incremental(std::string_view key, Options options, Pass&& pass) {
    options.scope.changed_since = since(key);
    const Mesh::Epoch start = mesh_.next_epoch();
    OperatorStats stats = pass(mesh_, options);
    epochs_[std::string(key)] = start;
    return stats;
  }

  // Any operation over a work list, on the adapter's executor, with the
  // adapter's metric (options.scope.metric, when the operation has one
  // and it is not set) and geometry (the member `geometry`, when it has
  // one).
  template <Operation Op>
  OperatorStats run(Op op, std::span<const typename Op::Item> items) {
    if constexpr (requires { op.options.scope.metric; })
      if (!op.options.scope.metric) op.options.scope.metric = metric_;
    if constexpr (requires { op.geometry; }) {
      static_assert(std::same_as<std::remove_cvref_t<decltype(op.geometry)>, G>,
                    "the operation's Geometry must be the adapter's");
      op.geometry = geometry_;
    }
    return run_pass<C>(mesh_, op, items);
  }
  template <Operation Op, class List>
  OperatorStats run(Op op, const List& items) {
    return run(std::move(op), std::span<const typename Op::Item>(items.data(), items.size()));
  }

  // The standard passes. Collapse, flips and smoothing are incremental
  // under `key`: by default the running stage's name (outside a stage, the
  // operation's); another stage's name shares that stage's epoch. Splits
  // see the whole mesh unless o.scope.changed_since says. The adapter
  // binds each pass's scope: its metric and its cycle's edge counts.
  template <class Criterion = ShapeOnly>
  OperatorStats collapse(CollapseOptions o, std::string_view key = {}) {
    o.scope.metric = metric_;
    if (!geometry_.on_model()) o.volume_budget = &volume_budget_;
    o.scope.known = &out_of_band_;
    return incremental(key_or(key, "collapse"), o, [this](Mesh& m, const CollapseOptions& x) {
      return collapse_edges<S, C, Criterion>(m, x, geometry_);
    });
  }
  template <class Criterion = ShapeOnly>
  OperatorStats split(RefineOptions o) {
    o.scope.metric = metric_;
    o.scope.known = &out_of_band_;
    return refine_edges<S, C, Criterion>(mesh_, o, geometry_);
  }
  template <class Criterion = ShapeOnly>
  OperatorStats insert_centroids(RefineOptions o) {
    o.scope.metric = metric_;
    return refine_centroids<S, C, Criterion>(mesh_, o, geometry_);
  }
  template <class Criterion = MinQuality>
  OperatorStats flips(const ReconnectOptions& o, std::string_view key = {}) {
    return incremental(key_or(key, "flip"), o, [this](Mesh& m, const ReconnectOptions& x) {
      return reconnect<S, C, Criterion>(m, x, geometry_);
    });
  }
  template <class Criterion = MinQuality>
  OperatorStats smooth(SmoothOptions o, std::string_view key = {}) {
    o.scope.metric = metric_;
    if (!geometry_.on_model()) o.volume_budget = &volume_budget_;
    return incremental(key_or(key, "smooth"), o, [this](Mesh& m, const SmoothOptions& x) {
      return smooth_vertices<S, C, Criterion>(m, x, geometry_);
    });
  }
  // Boundary 2-2 flips that bring facets closer to the model (none
  // without a model), and the 2-2 swaps and flips of internal surfaces.
  OperatorStats swap(const BoundarySwapOptions& o = {}, const InterfaceSwapOptions& i = {},
                     const InterfaceFlipOptions& f = {}) {
    OperatorStats stats = swap_toward_model<S, C>(mesh_, o, geometry_);
    stats += swap_interfaces(i, f);
    return stats;
  }
  // The internal surfaces' 2-2 swaps at their folds' slivers
  // (interface_swap.hpp), then their 2-2 flips (interface_flip.hpp).
  OperatorStats swap_interfaces(const InterfaceSwapOptions& i = {}, const InterfaceFlipOptions& f = {}) {
    OperatorStats stats = metrica::swap_interfaces<S, C>(mesh_, i, geometry_);
    stats += flip_interfaces<S, C>(mesh_, f, geometry_);
    return stats;
  }
  // The inner vertices in the way of the internal surfaces' long edges'
  // splits on the model go (clear_way.hpp; nothing without a model).
  OperatorStats clear_way(const RefineOptions& o) { return clear_way_for_splits<S, C>(mesh_, o, geometry_); }
  // Boundary vertices off the model move onto it (none without a model).
  OperatorStats project(ProjectionOptions o = {}) {
    o.scope.metric = metric_;
    return project_to_model<S, C>(mesh_, o, geometry_);
  }

  // Closes a cycle: compaction, counts, conformity and worst tet, the
  // report and the progress callback. Without `measure_conformity`, the
  // worst tet only (CycleReport::conformity_measured).
  void finish(CycleReport& c, const Stopwatch& clock, bool measure_conformity = true) {
    const Stopwatch closing;
    mesh_.compact(part_runner<C>(mesh_.tet_capacity()));
    release_freed_memory();
    c.vertices = mesh_.num_vertices();
    c.tets = mesh_.num_tets();
    c.conformity_measured = measure_conformity;
    if (measure_conformity) {
      c.conformity = conformity<S, C>(mesh_, &c.min_quality, true, &out_of_band_.edges);
      out_of_band_.taken(mesh_);
    } else {
      c.conformity = std::numeric_limits<double>::quiet_NaN();
      c.min_quality = worst_quality<S, C>(mesh_, true);
    }
    c.closing_seconds = closing.seconds();
    c.seconds = clock.seconds();
    report_.ops += c.ops;
    report_.cycles.push_back(c);
    if (on_cycle) on_cycle(c);
  }

  AdaptReport& report() { return report_; }
  const AdaptReport& report() const { return report_; }

  // Called after every cycle (progress output).
  std::function<void(const CycleReport&)> on_cycle;

 private:
  std::string_view key_or(std::string_view key, std::string_view operation) const {
    return !key.empty() ? key : !stage_.empty() ? std::string_view(stage_) : operation;
  }

  Mesh& mesh_;
  MetricSource metric_;
  G geometry_;
  VolumeBudget volume_budget_;
  std::map<std::string, Mesh::Epoch, std::less<>> epochs_;
  std::string stage_;
  Mesh::Epoch restarted_ = 0;
  AdaptReport report_;
  // The edges outside the unit band at the last cycle's end, for the next
  // cycle's work lists (edges_beyond).
  OutOfBandEdges out_of_band_;
};

// A stage of a pipeline: a name (its key in the reports and the key of
// its incremental passes' epoch) and what it does.
template <class A>
struct Stage {
  std::string name;
  std::function<OperatorStats(A&)> run;
};

template <class A>
using Stages = std::vector<Stage<A>>;

// Runs the stages in order, each one's stats added to c.ops[stage name].
template <class A>
void run_stages(A& adapter, const Stages<A>& stages, CycleReport& c) {
  for (const Stage<A>& s : stages) c.ops[s.name] += adapter.run_stage(s.name, s.run);
}

}  // namespace metrica
