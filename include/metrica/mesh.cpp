#include <metrica/geometry.hpp>
#include <metrica/mesh.hpp>

#include <limits>

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

void Mesh::reserve(std::size_t vertices, std::size_t tets) {
  points_.reserve(vertices);
  vertex_ref_.reserve(vertices);
  vert2tet_.reserve(vertices);
  vertex_class_.reserve(vertices);
  vertex_flags_.reserve(vertices);
  if (has_metric()) {
    metric_.reserve(vertices);
    log_metric_.reserve(vertices);
  }
  tets_.reserve(tets);
  tet2tets_.reserve(tets);
  face_surface_.reserve(tets);
  tet_ref_.reserve(tets);
  tet_stamp_.reserve(tets);
  tet_quality_.reserve(tets);
}

VertexId Mesh::add_vertex(const Point& p, int ref) {
  ++live_vertices_;
  if (!free_vertices_.empty()) {
    const VertexId v = free_vertices_.back();
    free_vertices_.pop_back();
    points_[v] = p;
    vertex_ref_[v] = ref;
    vert2tet_[v] = kNoId;
    vertex_class_[v] = VertexClass::interior;
    vertex_flags_[v] = kAlive;
    return v;
  }
  const auto v = static_cast<VertexId>(points_.size());
  points_.push_back(p);
  vertex_ref_.push_back(ref);
  vert2tet_.push_back(kNoId);
  vertex_class_.push_back(VertexClass::interior);
  vertex_flags_.push_back(kAlive);
  if (has_metric()) {
    metric_.push_back(Sym6{});
    log_metric_.push_back(Sym6{});
  }
  return v;
}

void Mesh::remove_vertex(VertexId v) {
  vertex_flags_[v] = 0;
  vert2tet_[v] = kNoId;
  free_vertices_.push_back(v);
  --live_vertices_;
}

void Mesh::set_required(VertexId v, bool required) {
  if (required)
    vertex_flags_[v] |= kRequired;
  else
    vertex_flags_[v] &= static_cast<std::uint8_t>(~kRequired);
}

void Mesh::set_metric(VertexId v, const Sym6& m, const Sym6& log_m) {
  if (metric_.empty()) {
    metric_.assign(points_.size(), Sym6{});
    log_metric_.assign(points_.size(), Sym6{});
  }
  metric_[v] = m;
  log_metric_[v] = log_m;
}

TetId Mesh::add_tet(const TetVertices& vertices, int ref) {
  ++live_tets_;
  constexpr std::array<FaceRef, 4> kNoNeighbours{};
  constexpr std::array<SurfaceId, 4> kInterior{0, 0, 0, 0};
  if (!free_tets_.empty()) {
    const TetId t = free_tets_.back();
    free_tets_.pop_back();
    tets_[t] = vertices;
    tet2tets_[t] = kNoNeighbours;
    face_surface_[t] = kInterior;
    tet_ref_[t] = ref;
    tet_stamp_[t] = epoch_;
    tet_quality_[t] = kUnknownQuality;
    return t;
  }
  const auto t = static_cast<TetId>(tets_.size());
  tets_.push_back(vertices);
  tet2tets_.push_back(kNoNeighbours);
  face_surface_.push_back(kInterior);
  tet_ref_.push_back(ref);
  tet_stamp_.push_back(epoch_);
  tet_quality_.push_back(kUnknownQuality);
  return t;
}

void Mesh::remove_tet(TetId t) {
  tets_[t] = {kNoId, kNoId, kNoId, kNoId};
  tet2tets_[t] = {};
  free_tets_.push_back(t);
  --live_tets_;
}

void Mesh::split_ridge(VertexId a, VertexId b, VertexId m) {
  if (ridges_.erase(edge_key(a, b))) {
    ridges_.insert(edge_key(a, m));
    ridges_.insert(edge_key(m, b));
  }
  if (feature_edges_.erase(edge_key(a, b))) {
    feature_edges_.insert(edge_key(a, m));
    feature_edges_.insert(edge_key(m, b));
  }
}

void Mesh::merge_edge_tags(VertexId from, VertexId to, std::span<const VertexId> neighbours) {
  for (auto* tags : {&ridges_, &feature_edges_}) {
    for (VertexId x : neighbours)
      if (tags->erase(edge_key(from, x)) && x != to) tags->insert(edge_key(to, x));
  }
}

BoundingBox bounding_box(const Mesh& mesh) {
  BoundingBox b{Point::Constant(std::numeric_limits<double>::max()), Point::Constant(-std::numeric_limits<double>::max())};
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
