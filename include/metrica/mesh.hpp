// The tetrahedral mesh: flat arrays indexed by 32-bit ids.
//
// Vertices carry a position, a hint to one incident tet, a classification
// (interior / surface / ridge / corner) and flags. Tets carry 4 vertex ids
// (positively oriented), across each face the neighbour or, on the
// boundary, the surface id (tet2tets, one word a face: FaceRef), and a
// domain reference. What the layers above keep per entity (the metric and
// its logarithm, CAD parameters, a background's tets, the quality cache,
// a distributed part's global ids, a user's own) are attributes
// (attributes.hpp), which follow the entities through every operation.
// Deleted entities are recycled through free lists; compact() renumbers.
//
// The invariants of docs/architecture.md are checked by validate() (validate.hpp).
// Operators change the mesh through the small set of primitives below;
// none of them allocates per call once capacity is reserved.
#pragma once

#include <metrica/attributes.hpp>
#include <metrica/edge_tags.hpp>
#include <metrica/geometry.hpp>
#include <metrica/id_source.hpp>
#include <metrica/ids.hpp>
#include <metrica/mesh_array.hpp>
#include <metrica/tet_topology.hpp>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <unordered_set>
#include <utility>
#include <vector>

namespace metrica {

enum class VertexClass : std::uint8_t { interior = 0, surface = 1, ridge = 2, corner = 3 };

const char* to_string(VertexClass c);

class ValidationReport;
struct ValidateOptions;

// The names of the attributes the library itself keeps (a user's own
// columns take other names).
namespace attribute_name {
inline constexpr std::string_view metric = "metric";
inline constexpr std::string_view log_metric = "log_metric";
inline constexpr std::string_view cad_parameters = "cad_parameters";
inline constexpr std::string_view background_tet = "background_tet";
inline constexpr std::string_view mean_ratio_cache = "mean_ratio_cache";
inline bool is_library(std::string_view name) {
  return name == metric || name == log_metric || name == cad_parameters || name == background_tet ||
         name == mean_ratio_cache;
}
}  // namespace attribute_name

class Mesh {
 public:
  // --- sizes -------------------------------------------------------------
  // Ids run over [0, capacity); some may be dead (on a free list).
  std::size_t vertex_capacity() const { return points_.size(); }
  std::size_t tet_capacity() const { return tets_.size(); }
  std::size_t num_vertices() const { return live_vertices_; }
  // Vertices created plus vertices removed since the mesh was made (a
  // parallel pass's are added at its end): what a cycle changed, whatever
  // its stages are called, is the difference of two readings.
  std::uint64_t vertex_changes() const { return vertex_changes_; }
  std::size_t num_tets() const { return live_tets_; }

  bool vertex_alive(VertexId v) const { return (vertex_flags_[v] & kAlive) != 0; }
  bool tet_alive(TetId t) const { return tets_[t][0] != kNoId; }
  // The vertices of t read without holding any of them (a parallel pass's
  // seed, before it locks them): each id is read atomically, the four
  // together may mix two versions. The caller locks what it read and
  // reads again (tet()) to check that t still holds those vertices.
  TetVertices peek_tet(TetId t) const {
    TetVertices v;
    for (int i = 0; i < 4; ++i)
      v[i] = std::atomic_ref<VertexId>(const_cast<VertexId&>(tets_[t][i])).load(std::memory_order_relaxed);
    return v;
  }

  // --- vertices ----------------------------------------------------------
  const Point& point(VertexId v) const { return points_[v]; }
  Point& point(VertexId v) { return points_[v]; }
  int vertex_ref(VertexId v) const { return vertex_ref_[v]; }
  TetId vert2tet(VertexId v) const { return vert2tet_[v]; }
  void set_vert2tet(VertexId v, TetId t) { vert2tet_[v] = t; }
  VertexClass vertex_class(VertexId v) const { return vertex_class_[v]; }
  // Vertices the input marked as Corners or RequiredVertices: never moved
  // or removed by an operator.
  bool is_required(VertexId v) const { return (vertex_flags_[v] & kRequired) != 0; }
  void set_required(VertexId v, bool required);
  // Vertices on an internal surface (classify() marks them, a split of an
  // internal-surface edge marks its new vertex): they move and go within
  // their surface only.
  bool on_internal_surface(VertexId v) const { return (vertex_flags_[v] & kInternalSurface) != 0; }
  void set_on_internal_surface(VertexId v, bool on);
  // Never moved by an operator: required, or on the surface while the
  // surface is kept (keep_surface).
  bool is_fixed(VertexId v) const { return (vertex_flags_[v] & (kRequired | kKeptSurface)) != 0; }

  // --- required entities and the kept surface -----------------------------
  // Required edges (RequiredEdges, and the edges of RequiredTriangles) are
  // never split, flipped or removed; their ends are required vertices.
  // Safe in a parallel pass for a caller holding a and b (most calls stop
  // at the vertex flags).
  bool is_required_edge(VertexId a, VertexId b) const {
    if (!is_required(a) || !is_required(b)) return false;
    return edge_tags_.is_required(a, b);
  }
  void add_required_edge(VertexId a, VertexId b);
  // Required triangles (RequiredTriangles): their vertices and edges are
  // required, so every operation keeps them; listed (sorted vertex ids)
  // for output and validation.
  void add_required_triangles(std::span<const TriangleVertices> triangles);
  std::span<const TriangleVertices> required_triangles() const { return required_triangles_; }
  const std::unordered_set<std::uint64_t>& required_edges() const { return edge_tags_.required(); }
  // Keeps the whole surface (boundary and internal surfaces) as it is while
  // the volume is adapted: its vertices are fixed, and no operation splits,
  // flips or inserts on it (Mmg's -nosurf).
  void keep_surface();
  bool keeps_surface() const { return keep_surface_; }

  // --- attributes ----------------------------------------------------------
  // Named per-vertex and per-tet columns (attributes.hpp). A new column
  // has a value for every id (dead ones too), each `initial`; made or
  // reused entities take `initial`, compaction carries the values along.
  // Outside parallel passes. The library's own (attribute_name) are read
  // through the accessors below: their names are not a user's to add or
  // remove (std::invalid_argument).
  template <class T>
  Attribute<T>& add_vertex_attribute(std::string name, const T& initial) {
    refuse_library_name(name);
    Attribute<T>& a = attributes_.vertices.add<T>(std::move(name), points_.size(), initial);
    attributes_.bind();
    return a;
  }
  template <class T>
  Attribute<T>& add_tet_attribute(std::string name, const T& initial) {
    refuse_library_name(name);
    Attribute<T>& a = attributes_.tets.add<T>(std::move(name), tets_.size(), initial);
    attributes_.bind();
    return a;
  }
  template <class T>
  Attribute<T>* find_vertex_attribute(std::string_view name) {
    return attributes_.vertices.find<T>(name);
  }
  template <class T>
  const Attribute<T>* find_vertex_attribute(std::string_view name) const {
    return attributes_.vertices.find<T>(name);
  }
  template <class T>
  Attribute<T>* find_tet_attribute(std::string_view name) {
    return attributes_.tets.find<T>(name);
  }
  template <class T>
  const Attribute<T>* find_tet_attribute(std::string_view name) const {
    return attributes_.tets.find<T>(name);
  }
  bool remove_vertex_attribute(std::string_view name);
  bool remove_tet_attribute(std::string_view name);
  const AttributeTable& vertex_attributes() const { return attributes_.vertices; }
  const AttributeTable& tet_attributes() const { return attributes_.tets; }

  // Metric field: absent until set (metrics/ fills it).
  bool has_metric() const { return attributes_.metric != nullptr; }
  const Sym6& metric(VertexId v) const { return attributes_.metric_at[v]; }
  const Sym6& log_metric(VertexId v) const { return attributes_.log_metric_at[v]; }
  // Sets M and log M of a vertex; adds the attributes on first use.
  void set_metric(VertexId v, const Sym6& m, const Sym6& log_m);

  // Geometric parameters of the vertices (GeoParam): empty until a model
  // is attached (geometry/ fills them); interior vertices keep dim -1.
  bool has_geo_params() const { return attributes_.geo != nullptr; }
  const GeoParam& geo_param(VertexId v) const { return attributes_.geo_at[v]; }
  // Adds the attribute (every vertex unassociated); outside parallel passes.
  void enable_geo_params();
  void set_geo_param(VertexId v, const GeoParam& g) { attributes_.geo_at[v] = g; }

  // The tet of a background mesh (the user's metric on the input mesh,
  // metrics/background_metric.hpp) where each vertex's metric was sampled:
  // where the walk for a vertex made from it starts. Empty until enabled;
  // kNoId for a vertex not sampled there.
  bool has_background_tets() const { return attributes_.background != nullptr; }
  TetId background_tet(VertexId v) const { return attributes_.background_at ? attributes_.background_at[v] : kNoId; }
  // Adds the attribute (every vertex kNoId); outside parallel passes.
  void enable_background_tets();
  void set_background_tet(VertexId v, TetId t) {
    if (attributes_.background_at) attributes_.background_at[v] = t;
  }
  // A copy that holds only what point location reads (point_location.hpp):
  // the points, the vertices' flags and tet hints, the tets and their
  // neighbours (a background's, metrics/background_metric.hpp: 32 bytes a
  // tet and 29 a vertex), no attribute. Nothing else may be asked of it.
  Mesh location_copy() const;

  // --- tets --------------------------------------------------------------
  const TetVertices& tet(TetId t) const { return tets_[t]; }
  int tet_ref(TetId t) const { return tet_ref_[t]; }
  // Moves t to another region (the caller holds its vertices and sets the
  // ids of the faces between regions: interface_swap.hpp).
  void set_tet_ref(TetId t, int ref) { tet_ref_[t] = ref; }
  // Neighbour across face `face` of t (with its local face), or none.
  FaceRef neighbour(TetId t, int face) const { return tet2tets_[t][face]; }
  // Asks the cache for t's vertices and neighbours (walks that will read
  // t a little later: each step of a walk is otherwise a dependent miss).
  void prefetch_tet(TetId t) const {
    __builtin_prefetch(&tets_[t]);
    __builtin_prefetch(&tet2tets_[t]);
  }
  FaceRef neighbour(FaceRef f) const { return tet2tets_[f.tet()][f.face()]; }
  // The surface id of a face without a neighbour (0: none given yet), 0
  // for a face with one.
  SurfaceId surface_id(TetId t, int face) const { return tet2tets_[t][face].surface(); }
  Point tet_point(TetId t, int i) const { return points_[tets_[t][i]]; }

  // --- internal surfaces ---------------------------------------------------
  // A face with a neighbour may lie on a surface too: between two regions
  // (tets of different refs), or a surface the input gave inside one
  // region. Both tets' slots hold its surface id (internal_surface_id; 0
  // elsewhere) and the adjacency still says who the neighbour is. Such a
  // face counts as a surface face for classification, validation and
  // output (is_surface_face, face_surface_id); the operations keep it. The
  // ids are stored once the first one is set: a mesh without internal
  // surfaces pays nothing for them.
  bool has_internal_surfaces() const { return !internal_.empty(); }
  SurfaceId internal_surface_id(TetId t, int face) const { return internal_.empty() ? 0 : internal_[t][face]; }
  // Allocates the ids on first use (outside parallel passes); afterwards
  // safe for a caller holding t's vertices.
  void set_internal_surface_id(TetId t, int face, SurfaceId id);
  // A face on a surface: without a neighbour, or on an internal surface.
  bool is_surface_face(TetId t, int face) const {
    return !tet2tets_[t][face].valid() || internal_surface_id(t, face) != 0;
  }
  // The surface id of a surface face (outer or internal), 0 for another.
  SurfaceId face_surface_id(TetId t, int face) const {
    const FaceRef n = tet2tets_[t][face];
    return n.valid() ? internal_surface_id(t, face) : n.surface();
  }

  // --- change stamps -----------------------------------------------------
  // Every tet carries the epoch in which it was last written (created,
  // re-vertexed, or touched because one of its vertices moved). A pass
  // that starts a new epoch can later ask which tets changed since: an
  // operator whose decision depends only on a cavity's tets need not try
  // a cavity again when none of them changed (the same inputs give the
  // same answer), so later cycles work where the mesh still changes.
  using Epoch = std::uint32_t;
  Epoch epoch() const { return epoch_; }
  // Starts a new epoch and returns it: tets written from now on carry it.
  Epoch next_epoch() { return ++epoch_; }
  Epoch tet_stamp(TetId t) const { return tet_stamp_[t]; }
  bool changed_since(TetId t, Epoch e) const { return tet_stamp_[t] >= e; }
  // Marks t as changed now (e.g. a vertex of t moved).
  void touch_tet(TetId t) {
    tet_stamp_[t] = epoch_;
    cache_quality(t, kUnknownQuality);
  }
  // The epoch in which vertex v was created (a pass asks which of its
  // cavity's vertices it made itself: the proximity filter).
  Epoch vertex_stamp(VertexId v) const { return vertex_stamp_[v]; }

  // --- quality cache -------------------------------------------------------
  // One number per tet that a measuring policy may keep (the mean ratio of
  // the Space an adaptation runs in: cached_mean_ratio in space.hpp),
  // forgotten whenever the tet is written or touched. Whoever moves a
  // vertex or changes its metric touches its ball (the operators do);
  // whoever changes the metric of the whole mesh or measures in another
  // Space clears the cache.
  static constexpr double kUnknownQuality = -2.0;  // mean ratios lie in [-1, 1]
  // Atomic (relaxed) so that two threads each holding a different vertex
  // of t may both measure it and store the same number.
  double cached_quality(TetId t) const {
    return std::atomic_ref<double>(attributes_.quality_at[t]).load(std::memory_order_relaxed);
  }
  void cache_quality(TetId t, double q) const {
    std::atomic_ref<double>(attributes_.quality_at[t]).store(q, std::memory_order_relaxed);
  }
  // Forgets every number; `space` names the Space whose mean ratios the
  // cache holds from now on (empty: not said), which cached_mean_ratio
  // checks in debug builds.
  void clear_quality_cache(std::string_view space = {}) {
    attributes_.quality->fill(kUnknownQuality);
    attributes_.quality_space = space;
  }
  // The Space the cache holds mean ratios of (empty: not said).
  std::string_view quality_cache_space() const { return attributes_.quality_space; }

  // --- ridges ------------------------------------------------------------
  // Ridge edges: between faces of two different surface ids, plus the
  // feature edges the input gave (Edges / Ridges keywords).
  // Safe in a parallel pass for a caller holding a and b (both ends of a
  // ridge edge are ridge or corner vertices, so most calls never reach the
  // shared set, edge_tags.hpp).
  bool is_ridge(VertexId a, VertexId b) const {
    if (vertex_class_[a] < VertexClass::ridge || vertex_class_[b] < VertexClass::ridge) return false;
    return edge_tags_.is_ridge(a, b);
  }
  // The sets themselves: only outside parallel passes.
  const std::unordered_set<std::uint64_t>& ridge_edges() const { return edge_tags_.ridges(); }
  const std::unordered_set<std::uint64_t>& feature_edges() const { return edge_tags_.features(); }
  void add_feature_edge(VertexId a, VertexId b) { edge_tags_.add_feature(a, b); }

  // Recomputes ridges and vertex classes from the surface ids, feature
  // edges and required vertices (classification.cpp). The one function
  // operators call after changing the boundary.
  void classify();

  // --- mutation primitives -----------------------------------------------
  void reserve(std::size_t vertices, std::size_t tets);
  VertexId add_vertex(const Point& p, int ref = 0);
  void remove_vertex(VertexId v);
  // Adds a tet with no neighbours and interior faces; the caller links it.
  TetId add_tet(const TetVertices& vertices, int ref = 0);
  void remove_tet(TetId t);
  // Gives t other vertices: a tet made again in its place (its attributes
  // take their initial values).
  void set_tet_vertices(TetId t, const TetVertices& vertices) {
    store_tet(t, vertices);
    tet_stamp_[t] = epoch_;
    attributes_.init_tet(t);
  }
  // Makes a and b neighbours of each other (both slots written).
  void link(FaceRef a, FaceRef b) {
    tet2tets_[a.tet()][a.face()] = b;
    tet2tets_[b.tet()][b.face()] = a;
  }
  void set_neighbour(TetId t, int face, FaceRef n) { tet2tets_[t][face] = n; }
  // Makes face `face` of t a face without a neighbour, of surface `id`
  // (0..kMaxSurfaceId; one slot holds the neighbour or the id).
  void set_surface_id(TetId t, int face, SurfaceId id) { tet2tets_[t][face] = FaceRef::boundary(id); }
  void set_vertex_class(VertexId v, VertexClass c) { vertex_class_[v] = c; }
  void set_ridges(std::unordered_set<std::uint64_t> ridges) { edge_tags_.set_ridges(std::move(ridges)); }
  // Replaces ridge (and feature) edge ab by am and mb when an operator
  // puts vertex m on it, keeping the classification up to date.
  void split_ridge(VertexId a, VertexId b, VertexId m);
  // When an edge collapse merges vertex `from` into `to`: ridge and feature
  // edges (from, x) become (to, x) and (from, to) disappears. `neighbours`
  // are the vertices joined to `from` by an edge.
  void merge_edge_tags(VertexId from, VertexId to, std::span<const VertexId> neighbours);

  // --- ids from a concurrency policy --------------------------------------
  // While a source is attached (a parallel pass), add_vertex, add_tet,
  // remove_vertex and remove_tet take and give ids through it
  // (id_source.hpp), and the free lists and counts wait. Attaching hands
  // the source the free lists; detaching takes back the ids it holds and
  // adds its counts. Neither while threads run; one source at a time.
  IdLedger attach_id_source(IdSource& source);
  void detach_id_source(IdLedger returned);
  // Appends `vertex_room` and `tet_room` dead entities (ids no list holds:
  // the caller hands them out) without moving a live one's data; the
  // arrays grow (copy, fill) in `run`'s parts. Only while no thread runs.
  DeadRoom add_dead_room(std::size_t vertex_room, std::size_t tet_room, const PartRunner& run = {});

  // Removes dead entities and renumbers vertices along a Morton curve and
  // tets by their vertices, so that neighbours in space are neighbours in
  // memory (compact.cpp). Invalidates every id held outside. With a
  // PartRunner (part_runner<C>(n) of a Concurrency policy) its sweeps run
  // on that policy's threads; the result is the same for any runner.
  void compact();
  void compact(const PartRunner& run);
  // How many compactions the mesh went through: ids taken at different
  // counts name different entities.
  std::uint32_t renumberings() const { return renumberings_; }

  // Checks every invariant of docs/architecture.md (validate.cpp).
  ValidationReport validate(const ValidateOptions& options) const;
  ValidationReport validate() const;

  // Sum of the (Euclidean) volumes of the live tets.
  double volume() const;

 private:
  static constexpr std::uint8_t kAlive = 1;
  static constexpr std::uint8_t kRequired = 2;
  static constexpr std::uint8_t kInternalSurface = 4;
  static constexpr std::uint8_t kKeptSurface = 8;

  void store_tet(TetId t, const TetVertices& v) {
    for (int i = 0; i < 4; ++i) std::atomic_ref<VertexId>(tets_[t][i]).store(v[i], std::memory_order_relaxed);
  }
  void init_vertex(VertexId v, const Point& p, int ref);
  static void refuse_library_name(std::string_view name);
  void init_tet(TetId t, const TetVertices& vertices, int ref);

  // The attribute tables, and the library's own columns in them (null:
  // absent), which a copy finds again in its own tables. The accessors
  // read those columns' values through one pointer each, which every
  // change that may move them refreshes; a made or reused entity's
  // library values are written directly, the user's columns' through
  // their virtual set_initial.
  struct Attributes {
    AttributeTable vertices, tets;
    Attribute<Sym6>* metric = nullptr;
    Attribute<Sym6>* log_metric = nullptr;
    Attribute<GeoParam>* geo = nullptr;
    Attribute<TetId>* background = nullptr;
    Attribute<double>* quality = nullptr;
    std::vector<AttributeColumn*> user_vertices, user_tets;
    Sym6* metric_at = nullptr;
    Sym6* log_metric_at = nullptr;
    GeoParam* geo_at = nullptr;
    TetId* background_at = nullptr;
    // Written through const access (a cache), one writer per tet at a
    // time: the holder of the tet's vertices' locks.
    double* quality_at = nullptr;
    std::string_view quality_space;  // a policy's static name

    void refresh() {
      metric_at = metric ? metric->data() : nullptr;
      log_metric_at = log_metric ? log_metric->data() : nullptr;
      geo_at = geo ? geo->data() : nullptr;
      background_at = background ? background->data() : nullptr;
      quality_at = quality->data();
    }
    void init_vertex(VertexId v) {
      if (metric_at) metric_at[v] = log_metric_at[v] = Sym6{};
      if (geo_at) geo_at[v] = GeoParam{};
      if (background_at) background_at[v] = kNoId;
      for (AttributeColumn* c : user_vertices) c->set_initial(v);
    }
    void init_tet(TetId t) {
      std::atomic_ref<double>(quality_at[t]).store(kUnknownQuality, std::memory_order_relaxed);
      for (AttributeColumn* c : user_tets) c->set_initial(t);
    }
    void append_vertex() {
      vertices.append_initial();
      refresh();
    }
    void append_tet() {
      tets.append_initial();
      quality_at = quality->data();
    }

    Attributes();
    Attributes(const Attributes& o);
    Attributes& operator=(const Attributes& o);
    // The moved-from tables hold an empty quality cache, no other column.
    Attributes(Attributes&& o) noexcept;
    Attributes& operator=(Attributes&& o) noexcept;
    void bind();
  };

  MeshArray<Point> points_;
  MeshArray<int> vertex_ref_;
  MeshArray<TetId> vert2tet_;
  MeshArray<VertexClass> vertex_class_;
  MeshArray<std::uint8_t> vertex_flags_;
  MeshArray<Epoch> vertex_stamp_;

  MeshArray<TetVertices> tets_;
  MeshArray<std::array<FaceRef, 4>> tet2tets_;
  MeshArray<int> tet_ref_;
  MeshArray<Epoch> tet_stamp_;
  MeshArray<std::array<SurfaceId, 4>> internal_;  // empty: no internal surface
  Attributes attributes_;
  Epoch epoch_ = 0;
  std::uint32_t renumberings_ = 0;

  MeshArray<VertexId> free_vertices_;
  MeshArray<TetId> free_tets_;
  std::size_t live_vertices_ = 0;
  std::uint64_t vertex_changes_ = 0;
  std::size_t live_tets_ = 0;

  EdgeTags edge_tags_;
  std::vector<TriangleVertices> required_triangles_;  // sorted vertex ids, sorted
  bool keep_surface_ = false;

  IdSource* id_source_ = nullptr;
};

// The axis-aligned bounding box of the live vertices.
struct BoundingBox {
  Point lo, hi;
};
BoundingBox bounding_box(const Mesh& mesh);

inline Eigen::Vector3d face_normal(const Mesh& mesh, VertexId p, VertexId q, VertexId r) {
  return (mesh.point(q) - mesh.point(p)).cross(mesh.point(r) - mesh.point(p));
}

// Calls f(tet, face) for every face of a live tet that has no neighbour.
template <class F>
void for_each_boundary_face(const Mesh& mesh, F&& f) {
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int face = 0; face < 4; ++face)
      if (!mesh.neighbour(t, face).valid()) f(t, face);
  }
}

// Calls f(tet, face) for every surface face once: the boundary faces, and
// each internal-surface face from the side of the smaller tet id (its
// vertices in that tet's outward order). Over the tets [first, last) only:
// a part of a sweep.
template <class F>
void for_each_surface_face_in(const Mesh& mesh, std::size_t first, std::size_t last, F&& f) {
  const bool internal = mesh.has_internal_surfaces();
  for (auto t = static_cast<TetId>(first); t < last; ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int face = 0; face < 4; ++face) {
      const FaceRef n = mesh.neighbour(t, face);
      if (!n.valid() || (internal && mesh.internal_surface_id(t, face) != 0 && t < n.tet())) f(t, face);
    }
  }
}
template <class F>
void for_each_surface_face(const Mesh& mesh, F&& f) {
  for_each_surface_face_in(mesh, 0, mesh.tet_capacity(), f);
}

}  // namespace metrica
