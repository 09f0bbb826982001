#include <metrica/geometry.hpp>
#include <metrica/mesh.hpp>

#include <fmt/format.h>

#include <functional>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace metrica {

const char* to_string(VertexClass c) {
  switch (c) {
    case VertexClass::interior: return "interior";
    case VertexClass::surface: return "surface";
    case VertexClass::ridge: return "ridge";
    case VertexClass::corner: return "corner";
  }
  return "?";
}

namespace {
// Tet ids and the adjacency words (FaceRef) end at kMaxTets.
[[noreturn]] void throw_too_many_tets(std::size_t n) {
  throw std::length_error(fmt::format("Mesh: {} tets asked for, more than the {} a mesh holds", n, kMaxTets));
}
}  // namespace

Mesh::Attributes::Attributes() {
  tets.add<double>(std::string(attribute_name::mean_ratio_cache), 0, kUnknownQuality);
  bind();
}

Mesh::Attributes::Attributes(const Attributes& o) : vertices(o.vertices), tets(o.tets), quality_space(o.quality_space) {
  bind();
}

Mesh::Attributes& Mesh::Attributes::operator=(const Attributes& o) {
  if (this != &o) {
    vertices = o.vertices;
    tets = o.tets;
    quality_space = o.quality_space;
    bind();
  }
  return *this;
}

Mesh::Attributes::Attributes(Attributes&& o) noexcept
    : vertices(std::move(o.vertices)), tets(std::move(o.tets)), quality_space(o.quality_space) {
  bind();
  o.bind();
}

Mesh::Attributes& Mesh::Attributes::operator=(Attributes&& o) noexcept {
  if (this != &o) {
    vertices = std::move(o.vertices);
    tets = std::move(o.tets);
    quality_space = o.quality_space;
    bind();
    o.bind();
  }
  return *this;
}

void Mesh::Attributes::bind() {
  metric = vertices.find<Sym6>(attribute_name::metric);
  log_metric = vertices.find<Sym6>(attribute_name::log_metric);
  geo = vertices.find<GeoParam>(attribute_name::cad_parameters);
  background = vertices.find<TetId>(attribute_name::background_tet);
  quality = tets.find<double>(attribute_name::mean_ratio_cache);
  user_vertices.clear();
  user_tets.clear();
  vertices.for_each([&](AttributeColumn& c) {
    if (!attribute_name::is_library(c.name())) user_vertices.push_back(&c);
  });
  tets.for_each([&](AttributeColumn& c) {
    if (!attribute_name::is_library(c.name())) user_tets.push_back(&c);
  });
  // A moved-from table has no quality column: an empty one takes its place.
  if (!quality) quality = &tets.add<double>(std::string(attribute_name::mean_ratio_cache), 0, kUnknownQuality);
  refresh();
}

void Mesh::refuse_library_name(std::string_view name) {
  if (attribute_name::is_library(name))
    throw std::invalid_argument(fmt::format("the attribute '{}' is the library's own", name));
}

bool Mesh::remove_vertex_attribute(std::string_view name) {
  refuse_library_name(name);
  const bool removed = attributes_.vertices.remove(name);
  attributes_.bind();
  return removed;
}

bool Mesh::remove_tet_attribute(std::string_view name) {
  refuse_library_name(name);
  const bool removed = attributes_.tets.remove(name);
  attributes_.bind();
  return removed;
}

void Mesh::enable_geo_params() {
  if (attributes_.geo) return;
  attributes_.vertices.add(std::string(attribute_name::cad_parameters), points_.size(), GeoParam{},
                           DeadRoomFill::initial);
  attributes_.bind();
}

void Mesh::enable_background_tets() {
  if (attributes_.background) return;
  attributes_.vertices.add(std::string(attribute_name::background_tet), points_.size(), TetId{kNoId});
  attributes_.bind();
}

void Mesh::reserve(std::size_t vertices, std::size_t tets) {
  points_.reserve(vertices);
  vertex_ref_.reserve(vertices);
  vert2tet_.reserve(vertices);
  vertex_class_.reserve(vertices);
  vertex_flags_.reserve(vertices);
  vertex_stamp_.reserve(vertices);
  attributes_.vertices.reserve(vertices);
  attributes_.tets.reserve(tets);
  attributes_.refresh();
  tets_.reserve(tets);
  tet2tets_.reserve(tets);
  tet_ref_.reserve(tets);
  tet_stamp_.reserve(tets);
  if (has_internal_surfaces()) internal_.reserve(tets);
}

void Mesh::init_vertex(VertexId v, const Point& p, int ref) {
  points_[v] = p;
  vertex_ref_[v] = ref;
  vert2tet_[v] = kNoId;
  vertex_class_[v] = VertexClass::interior;
  vertex_flags_[v] = kAlive;
  vertex_stamp_[v] = epoch_;
  attributes_.init_vertex(v);
}

VertexId Mesh::add_vertex(const Point& p, int ref) {
  if (id_source_) {
    const VertexId v = id_source_->take_vertex();
    init_vertex(v, p, ref);
    return v;
  }
  ++live_vertices_;
  ++vertex_changes_;
  if (!free_vertices_.empty()) {
    const VertexId v = free_vertices_.back();
    free_vertices_.pop_back();
    init_vertex(v, p, ref);
    return v;
  }
  const auto v = static_cast<VertexId>(points_.size());
  points_.push_back(p);
  vertex_ref_.push_back(ref);
  vert2tet_.push_back(kNoId);
  vertex_class_.push_back(VertexClass::interior);
  vertex_flags_.push_back(kAlive);
  vertex_stamp_.push_back(epoch_);
  attributes_.append_vertex();
  return v;
}

void Mesh::remove_vertex(VertexId v) {
  vertex_flags_[v] = 0;
  vert2tet_[v] = kNoId;
  if (id_source_) {
    id_source_->give_vertex(v);
    return;
  }
  free_vertices_.push_back(v);
  --live_vertices_;
  ++vertex_changes_;
}

void Mesh::set_required(VertexId v, bool required) {
  if (required)
    vertex_flags_[v] |= kRequired;
  else
    vertex_flags_[v] &= static_cast<std::uint8_t>(~kRequired);
}

void Mesh::add_required_edge(VertexId a, VertexId b) {
  set_required(a, true);
  set_required(b, true);
  edge_tags_.add_required(a, b);
}

void Mesh::add_required_triangles(std::span<const TriangleVertices> triangles) {
  for (const auto& tri : triangles) {
    TriangleVertices key = tri;
    std::sort(key.begin(), key.end());
    for (int i = 0; i < 3; ++i) add_required_edge(key[i], key[(i + 1) % 3]);
    required_triangles_.push_back(key);
  }
  std::sort(required_triangles_.begin(), required_triangles_.end());
  required_triangles_.erase(std::unique(required_triangles_.begin(), required_triangles_.end()),
                            required_triangles_.end());
}

void Mesh::keep_surface() {
  keep_surface_ = true;
  for_each_surface_face(*this, [&](TetId t, int f) {
    for (VertexId v : face_vertices(tets_[t], f)) vertex_flags_[v] |= kKeptSurface;
  });
}

void Mesh::set_on_internal_surface(VertexId v, bool on) {
  if (on)
    vertex_flags_[v] |= kInternalSurface;
  else
    vertex_flags_[v] &= static_cast<std::uint8_t>(~kInternalSurface);
}

void Mesh::set_internal_surface_id(TetId t, int face, SurfaceId id) {
  if (internal_.empty()) {
    if (id == 0) return;
    internal_.assign(tets_.size(), std::array<SurfaceId, 4>{});
  }
  internal_[t][face] = id;
}

Mesh Mesh::location_copy() const {
  Mesh m;
  m.points_ = points_;
  m.vert2tet_ = vert2tet_;
  m.vertex_flags_ = vertex_flags_;
  m.tets_ = tets_;
  m.tet2tets_ = tet2tets_;
  m.live_vertices_ = live_vertices_;
  m.live_tets_ = live_tets_;
  return m;
}

void Mesh::set_metric(VertexId v, const Sym6& m, const Sym6& log_m) {
  if (!attributes_.metric) {
    attributes_.vertices.add(std::string(attribute_name::metric), points_.size(), Sym6{});
    attributes_.vertices.add(std::string(attribute_name::log_metric), points_.size(), Sym6{});
    attributes_.bind();
  }
  attributes_.metric_at[v] = m;
  attributes_.log_metric_at[v] = log_m;
}

void Mesh::init_tet(TetId t, const TetVertices& vertices, int ref) {
  store_tet(t, vertices);
  tet2tets_[t] = {};
  tet_ref_[t] = ref;
  tet_stamp_[t] = epoch_;
  attributes_.init_tet(t);
  if (has_internal_surfaces()) internal_[t] = {};
}

TetId Mesh::add_tet(const TetVertices& vertices, int ref) {
  if (id_source_) {
    const TetId t = id_source_->take_tet();
    init_tet(t, vertices, ref);
    return t;
  }
  ++live_tets_;
  if (!free_tets_.empty()) {
    const TetId t = free_tets_.back();
    free_tets_.pop_back();
    init_tet(t, vertices, ref);
    return t;
  }
  if (tets_.size() >= kMaxTets) throw_too_many_tets(tets_.size() + 1);
  const auto t = static_cast<TetId>(tets_.size());
  tets_.push_back(vertices);
  tet2tets_.push_back({});
  tet_ref_.push_back(ref);
  tet_stamp_.push_back(epoch_);
  attributes_.append_tet();
  if (has_internal_surfaces()) internal_.push_back({});
  return t;
}

void Mesh::remove_tet(TetId t) {
  store_tet(t, {kNoId, kNoId, kNoId, kNoId});
  tet2tets_[t] = {};
  if (id_source_) {
    id_source_->give_tet(t);
    return;
  }
  free_tets_.push_back(t);
  --live_tets_;
}

// --- ids from a concurrency policy -----------------------------------------

DeadRoom Mesh::add_dead_room(std::size_t vertex_room, std::size_t tet_room, const PartRunner& run) {
  const std::size_t nv = points_.size(), nt = tets_.size();
  // Grow by an eighth more than asked, not by doubling: the room is
  // mostly handed back, and doubling every array would double the peak.
  const std::size_t v_size = nv + vertex_room, t_size = nt + tet_room;
  if (t_size > kMaxTets) throw_too_many_tets(t_size);
  const std::size_t v_cap = v_size + nv / 8, t_cap = t_size + nt / 8;
  // Only what tells a dead entity is written (its vertices, its flags,
  // its hint, the attributes of DeadRoomFill::initial: the model
  // association); add_vertex and add_tet write the rest. Room that no operation takes is then never resident: a split
  // pass reserves 3.5 tets per candidate edge and takes about one.
  extend_array(points_, v_size, v_cap, run);
  extend_array(vertex_ref_, v_size, v_cap, run);
  grow_array(vert2tet_, v_size, kNoId, v_cap, run);
  extend_array(vertex_class_, v_size, v_cap, run);
  grow_array(vertex_flags_, v_size, std::uint8_t{0}, v_cap, run);
  extend_array(vertex_stamp_, v_size, v_cap, run);
  attributes_.vertices.add_room(v_size, v_cap, run);
  grow_array(tets_, t_size, TetVertices{kNoId, kNoId, kNoId, kNoId}, t_cap, run);
  extend_array(tet2tets_, t_size, t_cap, run);
  extend_array(tet_ref_, t_size, t_cap, run);
  extend_array(tet_stamp_, t_size, t_cap, run);
  attributes_.tets.add_room(t_size, t_cap, run);
  attributes_.refresh();
  if (has_internal_surfaces()) extend_array(internal_, t_size, t_cap, run);
  return {nv, nt};
}

IdLedger Mesh::attach_id_source(IdSource& source) {
  if (id_source_) throw std::logic_error("Mesh::attach_id_source: a source is already attached");
  id_source_ = &source;
  IdLedger ledger;
  std::swap(ledger.free_vertices, free_vertices_);
  std::swap(ledger.free_tets, free_tets_);
  return ledger;
}

void Mesh::detach_id_source(IdLedger returned) {
  id_source_ = nullptr;
  free_vertices_.insert(free_vertices_.end(), returned.free_vertices.begin(), returned.free_vertices.end());
  free_tets_.insert(free_tets_.end(), returned.free_tets.begin(), returned.free_tets.end());
  live_vertices_ = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(live_vertices_) + returned.vertex_delta);
  live_tets_ = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(live_tets_) + returned.tet_delta);
  vertex_changes_ += returned.vertex_changes;
}

void Mesh::split_ridge(VertexId a, VertexId b, VertexId m) {
  // Ridge edges join ridge or corner vertices (classification): without
  // input feature edges (which may lie inside), most splits need not reach
  // the shared sets.
  if (!edge_tags_.has_features() && (vertex_class_[a] < VertexClass::ridge || vertex_class_[b] < VertexClass::ridge))
    return;
  edge_tags_.split(a, b, m);
}

void Mesh::merge_edge_tags(VertexId from, VertexId to, std::span<const VertexId> neighbours) {
  if (!edge_tags_.has_features() && vertex_class_[from] < VertexClass::ridge) return;  // on no tagged edge
  edge_tags_.merge(from, to, neighbours);
}

BoundingBox bounding_box(const Mesh& mesh) {
  BoundingBox b{Point::Constant(std::numeric_limits<double>::max()),
                Point::Constant(-std::numeric_limits<double>::max())};
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    b.lo = b.lo.cwiseMin(mesh.point(v));
    b.hi = b.hi.cwiseMax(mesh.point(v));
  }
  return b;
}

double Mesh::volume() const {
  double sum = 0.0;
  for (TetId t = 0; t < tet_capacity(); ++t) {
    if (!tet_alive(t)) continue;
    const auto& v = tets_[t];
    sum += tet_volume(points_[v[0]], points_[v[1]], points_[v[2]], points_[v[3]]);
  }
  return sum;
}

}  // namespace metrica
