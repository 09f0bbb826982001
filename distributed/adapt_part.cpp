#include <metrica/distributed/adapt_part.hpp>

#include <metrica/error.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <cstring>

namespace metrica::distributed {

namespace {

using Bits = std::array<std::uint64_t, 3>;
Bits bits_of(const Point& p) {
  Bits b;
  for (int c = 0; c < 3; ++c) std::memcpy(&b[std::size_t(c)], &p[c], 8);
  return b;
}

}  // namespace

PartAdaptResult adapt_part(const Comm& comm, Part& part, const PartAdaptSettings& settings, GlobalId& next_id) {
  PartAdaptResult result;
  std::int64_t fresh = 0;
  Part adapted;
  comm.step([&] {
    if (part.tets.empty()) return;
    Stopwatch clock;
    const VertexIndex index(part.vertex_ids);
    io::MeshData data;
    data.vertices = part.points;
    for (const auto& t : part.tets) {
      TetVertices l;
      for (int c = 0; c < 4; ++c) l[std::size_t(c)] = VertexId(index.find(t[std::size_t(c)]));
      data.tets.push_back(l);
    }
    data.tet_refs = part.tet_refs;
    auto local_face = [&](const std::array<GlobalId, 3>& k) {
      return TriangleVertices{VertexId(index.find(k[0])), VertexId(index.find(k[1])), VertexId(index.find(k[2]))};
    };
    std::vector<FaceKey> shared = part.shared_faces;
    std::sort(shared.begin(), shared.end());
    for (std::size_t i = 0; i < part.triangles.size(); ++i) {
      data.triangles.push_back(local_face(part.triangles[i]));
      data.triangle_refs.push_back(part.triangle_refs[i]);
      if (std::binary_search(shared.begin(), shared.end(), face_key(part.triangles[i])))
        data.required_triangles.push_back(std::uint32_t(i));
    }
    std::vector<FaceKey> listed;
    for (const auto& t : part.triangles) listed.push_back(face_key(t));
    std::sort(listed.begin(), listed.end());
    for (const auto& k : shared) {
      if (std::binary_search(listed.begin(), listed.end(), k)) continue;
      data.required_triangles.push_back(std::uint32_t(data.triangles.size()));
      data.triangles.push_back(local_face(k));
      data.triangle_refs.push_back(kPartFaceId);
    }
    BuildOptions bo;
    bo.default_surface_id = settings.default_surface_id;
    bo.source = fmt::format("part {}", comm.rank());
    Mesh mesh = build_mesh(data, bo);
    data = io::MeshData{};
    result.volume_before = mesh.volume();
    if (settings.exact)
      assign_metric(mesh, *settings.exact);
    else
      assign_metric(mesh, part.metrics);
    AdaptInputs inputs;
    inputs.metric = settings.exact;
    adapt_by_name(mesh, settings.options, settings.policies, inputs);
    // Valid, with the volume checked over all parts by the caller.
    require_adapted(mesh, nullptr, result.volume_before, 1e300);
    result.volume_after = mesh.volume();
    result.quality = quality_report(mesh, settings.policies.space, {.cached_quality = true});

    // Back to global ids: the shared faces' vertices by their coordinates.
    std::vector<std::pair<Bits, GlobalId>> kept;
    for (const auto& k : shared)
      for (GlobalId g : k) kept.emplace_back(bits_of(part.points[std::size_t(index.find(g))]), g);
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    const io::MeshData out = extract_mesh_data(mesh);
    std::vector<GlobalId> ids(out.vertices.size(), -1);
    for (std::size_t v = 0; v < out.vertices.size(); ++v) {
      const auto b = bits_of(out.vertices[v]);
      auto it = std::lower_bound(kept.begin(), kept.end(), std::pair<Bits, GlobalId>{b, -1});
      if (it != kept.end() && it->first == b) ids[v] = it->second;
      else ++fresh;
    }
    adapted.vertex_ids = std::move(ids);
    adapted.points = out.vertices;
    if (!settings.exact) {
      for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
        if (mesh.vertex_alive(v)) adapted.metrics.push_back(mesh.metric(v));
    }
    for (std::size_t t = 0; t < out.tets.size(); ++t) {
      const auto& l = out.tets[t];
      adapted.tets.push_back({GlobalId(l[0]), GlobalId(l[1]), GlobalId(l[2]), GlobalId(l[3])});  // local for now
      adapted.tet_refs.push_back(out.tet_refs[t]);
    }
    for (std::size_t f = 0; f < out.triangles.size(); ++f) {
      if (out.triangle_refs[f] == kPartFaceId) continue;
      const auto& l = out.triangles[f];
      adapted.triangles.push_back({GlobalId(l[0]), GlobalId(l[1]), GlobalId(l[2])});  // local for now
      adapted.triangle_refs.push_back(out.triangle_refs[f]);
    }
    result.seconds = clock.seconds();
  });
  const std::int64_t base = next_id + comm.exclusive_scan(fresh);
  next_id += comm.sum(fresh);
  GlobalId at = base;
  for (auto& g : adapted.vertex_ids)
    if (g < 0) g = at++;
  for (auto& t : adapted.tets)
    for (auto& v : t) v = adapted.vertex_ids[std::size_t(v)];
  for (auto& f : adapted.triangles)
    for (auto& v : f) v = adapted.vertex_ids[std::size_t(v)];
  // The faces between parts must come out as they went in: the rank
  // across relies on them.
  comm.step([&] {
    std::vector<FaceKey> faces;
    for (const auto& t : adapted.tets)
      for (const auto& f : kTetFaces) faces.push_back(face_key(t[std::size_t(f[0])], t[std::size_t(f[1])], t[std::size_t(f[2])]));
    std::sort(faces.begin(), faces.end());
    std::size_t lost = 0;
    for (const auto& k : part.shared_faces) lost += !std::binary_search(faces.begin(), faces.end(), k);
    if (lost > 0)
      throw std::runtime_error(fmt::format("{} of the {} faces kept between parts changed in the adaptation", lost,
                                           part.shared_faces.size()));
  });
  adapted.shared_faces = std::move(part.shared_faces);
  adapted.shared_with = std::move(part.shared_with);
  part = std::move(adapted);
  return result;
}

}  // namespace metrica::distributed
