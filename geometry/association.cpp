#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/log.hpp>
#include <metrica/numbering.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace metrica {
namespace {

struct Candidate {
  GeoParam param;
  double distance = std::numeric_limits<double>::infinity();
};

// The nearest point of entity (dim, tag) to p; none (infinitely far) on
// an entity gmsh cannot project on (a degenerate curve: a cone's apex).
Candidate project(const CadModel& model, int dim, int tag, const Point& p) {
  Candidate c;
  try {
    c.param = model.parametrize(dim, tag, p);
    c.distance = (model.value(c.param) - p).norm();
  } catch (const InputError&) {
    c = Candidate{};
  }
  return c;
}

}  // namespace

VertexAssociation associate_vertex(const CadModel& model, const Point& p, std::span<const int> around, VertexClass cls,
                                   const VertexRecords& file, double tolerance) {
  // A vertex at a model vertex is associated with it, not with one of its
  // curves: new vertices between it and a neighbour on any of those curves
  // then find the curve they share (CadGeometry::boundary_vertex).
  const double at_model_vertex = 1e-9 * model.size();
  const double trusted = kTrustedRecord * model.size();
  Candidate best;
  bool from_file = false;
  double refused = -1.0;
  if (cls == VertexClass::surface && around.size() == 1) {
    const int s = around[0];
    for (const auto* r : file.on_surface)
      if (r->entity == s) {
        const GeoParam g{s, 2, r->u, r->v};
        const double d = (model.value(g) - p).norm();
        if (d <= trusted) {
          best = {g, d};
          from_file = true;
        } else {
          refused = std::max(refused, d);
        }
      }
    if (!best.param.valid()) best = project(model, 2, s, p);
  } else {
    // Curves of the vertex's surfaces (shared by two when it can).
    std::vector<int> curves;
    for (int s : around)
      for (int c : model.curves_of_surface(s))
        if (std::find(curves.begin(), curves.end(), c) == curves.end()) curves.push_back(c);
    if (file.model_vertex != 0 && model.has(0, file.model_vertex)) {
      const GeoParam g{file.model_vertex, 0, 0.0, 0.0};
      const double d = (model.value(g) - p).norm();
      if (d <= trusted) {
        best = {g, d};
        from_file = true;
      } else {
        refused = d;
      }
    }
    if (!best.param.valid()) {
      std::vector<int> corners;
      for (int c : curves)
        for (int m : model.vertices_of_curve(c))
          if (std::find(corners.begin(), corners.end(), m) == corners.end()) corners.push_back(m);
      Candidate nearest;
      for (int m : corners) {
        const GeoParam g{m, 0, 0.0, 0.0};
        const double d = (model.value(g) - p).norm();
        if (d < nearest.distance) nearest = {g, d};
      }
      if (cls == VertexClass::corner || nearest.distance <= at_model_vertex) best = nearest;
    }
    if (best.distance > tolerance)
      for (int c : curves) {
        const Candidate k = project(model, 1, c, p);
        // Between two curves equally near (a model vertex), the first found.
        if (k.distance < best.distance - 1e-12 * model.size()) best = k;
      }
    if (best.distance > tolerance && around.size() == 1) best = project(model, 2, around[0], p);
  }
  return {best.param, best.distance, from_file && best.param.valid(), from_file ? -1.0 : refused};
}

void AssociationReport::add(const VertexAssociation& a) {
  ++vertices;
  from_file += a.from_file;
  max_distance = std::max(max_distance, a.distance);
  off_model += a.distance > kOnModel;
  if (a.refused_record >= 0.0) {
    ++records_refused;
    refused_distance = std::max(refused_distance, a.refused_record);
  }
}

std::string off_model_message(VertexId v, const Point& p, const VertexAssociation& a, const CadModel& model,
                              double tolerance) {
  return fmt::format(
      "vertex {} at ({:.6g}, {:.6g}, {:.6g}) is {:.3g} from every entity of {} it may lie on (tolerance {:.3g}): "
      "the model does not match the mesh",
      numbered(v), p.x(), p.y(), p.z(), a.distance, model.source(), tolerance);
}

std::string unknown_surfaces_message(const std::set<int>& missing, const CadModel& model) {
  std::string ids;
  for (int s : missing) ids += fmt::format("{}{}", ids.empty() ? "" : ", ", s);
  const auto& all = model.entities(2);
  return fmt::format(
      "the mesh's surface ids {} are not surfaces of {} (its surfaces are {}..{}): the model does not match the mesh",
      ids, model.source(), *std::min_element(all.begin(), all.end()), *std::max_element(all.begin(), all.end()));
}

AssociationReport associate(Mesh& mesh, const CadModel& model, const io::MeshData* input, double tolerance) {
  if (tolerance <= 0.0) tolerance = 1e-3 * model.size();
  // The surface ids around each surface vertex (boundary and internal
  // surfaces); each id must be a model surface.
  std::vector<std::vector<int>> surfaces(mesh.vertex_capacity());
  std::set<int> missing;
  for_each_surface_face(mesh, [&](TetId t, int f) {
    const SurfaceId s = mesh.face_surface_id(t, f);
    if (!model.has(2, s)) missing.insert(s);
    for (VertexId v : face_vertices(mesh.tet(t), f)) {
      auto& list = surfaces[v];
      if (std::find(list.begin(), list.end(), s) == list.end()) list.push_back(s);
    }
  });
  if (!missing.empty()) throw InputError(unknown_surfaces_message(missing, model));
  // The input's (u, v) per vertex and surface, and its model vertices.
  std::vector<std::vector<const io::GeoRecord*>> on_surface(input != nullptr ? mesh.vertex_capacity() : 0);
  std::vector<int> on_model_vertex(input != nullptr ? mesh.vertex_capacity() : 0, 0);
  if (input != nullptr) {
    for (const auto& r : input->on_geometry[2])
      if (r.vertex < on_surface.size()) on_surface[r.vertex].push_back(&r);
    for (const auto& r : input->on_geometry[0])
      if (r.vertex < on_model_vertex.size()) on_model_vertex[r.vertex] = r.entity;
  }

  mesh.enable_geo_params();
  AssociationReport report;
  bool reclassify = false;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v) || surfaces[v].empty()) continue;
    const Point p = mesh.point(v);
    VertexRecords file;
    if (input != nullptr) file = {on_surface[v], on_model_vertex[v]};
    const VertexAssociation a = associate_vertex(model, p, surfaces[v], mesh.vertex_class(v), file, tolerance);
    if (!(a.distance <= tolerance)) throw InputError(off_model_message(v, p, a, model, tolerance));
    report.add(a);
    mesh.set_geo_param(v, a.param);
    reclassify |= a.param.dim == 0 && mesh.vertex_class(v) != VertexClass::corner;
  }
  if (reclassify) mesh.classify();
  return report;
}

namespace {
// Per vertex, whether it is on a surface face (not of surface `skip`).
std::vector<std::uint8_t> boundary_vertices(const Mesh& mesh, SurfaceId skip) {
  std::vector<std::uint8_t> boundary(mesh.vertex_capacity(), 0);
  for_each_surface_face(mesh, [&](TetId t, int f) {
    if (skip != 0 && mesh.face_surface_id(t, f) == skip) return;
    for (VertexId v : face_vertices(mesh.tet(t), f)) boundary[v] = 1;
  });
  return boundary;
}
}  // namespace

std::vector<VertexId> vertices_off_model(const Mesh& mesh, const CadModel& model, double tolerance, SurfaceId skip) {
  const auto boundary = boundary_vertices(mesh, skip);
  std::vector<VertexId> off;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!boundary[v] || !mesh.vertex_alive(v)) continue;
    if (!mesh.has_geo_params() || !mesh.geo_param(v).valid() ||
        !((model.value(mesh.geo_param(v)) - mesh.point(v)).norm() <= tolerance))
      off.push_back(v);
  }
  return off;
}

ModelDistance model_distance(const Mesh& mesh, const CadModel& model, double tolerance, SurfaceId skip) {
  ModelDistance d;
  const auto boundary = boundary_vertices(mesh, skip);
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!boundary[v] || !mesh.vertex_alive(v)) continue;
    if (!mesh.has_geo_params() || !mesh.geo_param(v).valid()) {
      ++d.unassociated;
      continue;
    }
    ++d.vertices;
    const double x = (model.value(mesh.geo_param(v)) - mesh.point(v)).norm();
    if (x > tolerance) ++d.beyond;
    if (x > d.max || d.worst == kNoId) {
      d.max = std::max(d.max, x);
      d.worst = v;
    }
  }
  return d;
}

void complete_geometry_records(io::MeshData& data, const CadModel& model) {
  std::vector<io::GeoRecord> on_curves, on_surfaces;
  auto add_surfaces_of = [&](const io::GeoRecord& r, int dim, const std::vector<int>& surfaces) {
    for (int s : surfaces) {
      const GeoParam g{r.entity, static_cast<std::int8_t>(dim), r.u, 0.0};
      const auto uv = model.on_surface(g, s);
      on_surfaces.push_back({r.vertex, s, uv[0], uv[1], 0.0});
    }
  };
  for (const auto& r : data.on_geometry[0])
    for (int c : model.curves_of_vertex(r.entity)) {
      const GeoParam g{r.entity, 0, 0.0, 0.0};
      const io::GeoRecord e{r.vertex, c, model.on_curve(g, c), 0.0, 0.0};
      on_curves.push_back(e);
      add_surfaces_of(e, 1, model.surfaces_of_curve(c));
    }
  for (const auto& r : data.on_geometry[1]) add_surfaces_of(r, 1, model.surfaces_of_curve(r.entity));
  auto& curves = data.on_geometry[1];
  auto& surfaces = data.on_geometry[2];
  curves.insert(curves.end(), on_curves.begin(), on_curves.end());
  surfaces.insert(surfaces.end(), on_surfaces.begin(), on_surfaces.end());
  auto by_vertex = [](const io::GeoRecord& a, const io::GeoRecord& b) {
    return a.vertex < b.vertex || (a.vertex == b.vertex && a.entity < b.entity);
  };
  std::sort(curves.begin(), curves.end(), by_vertex);
  std::sort(surfaces.begin(), surfaces.end(), by_vertex);
  // A corner's surface may come from two of its curves: once is enough.
  auto same = [](const io::GeoRecord& a, const io::GeoRecord& b) {
    return a.vertex == b.vertex && a.entity == b.entity;
  };
  surfaces.erase(std::unique(surfaces.begin(), surfaces.end(), same), surfaces.end());
  curves.erase(std::unique(curves.begin(), curves.end(), same), curves.end());
}

void require_on_model(const Mesh& mesh, const CadModel& model, const std::string& what, SurfaceId skip) {
  const ModelDistance d = model_distance(mesh, model, kOnModel, skip);
  if (d.unassociated == 0 && d.max <= kOnModel) return;
  throw InputError(
      fmt::format("{}: the boundary is not on {} ({} vertices without an entity, {} farther than {:.0e}, "
                  "largest distance {:.3g}); nothing written",
                  what, model.source(), d.unassociated, d.beyond, kOnModel, d.max));
}

}  // namespace metrica
