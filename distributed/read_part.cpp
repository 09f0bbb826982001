#include <metrica/distributed/read_part.hpp>
#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/meshb_keywords.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/part_runner.hpp>

#include <fmt/core.h>

#include <cstring>
#include <fcntl.h>
#include <map>
#include <unistd.h>

namespace metrica::distributed {

namespace {

namespace mb = io::meshb;
// Of the records, VerticesOnGeometricVertices and ...Triangles: what the
// association reads of the input (a vertex's model vertex, its (u, v));
// VerticesOnGeometricEdges, between them, it does not need.

// Where each keyword of a native-order binary libMeshb file starts: its
// row count and the offset of its first row.
struct Keyword {
  std::int64_t count = 0;
  std::uint64_t rows = 0;  // offset of the first row
  std::vector<int> types;  // SolAtVertices only
};

class BinaryFile {
 public:
  BinaryFile(const std::string& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDONLY);
    if (fd_ < 0) throw IoError(fmt::format("{}: cannot open ({})", path, std::strerror(errno)));
  }
  ~BinaryFile() { ::close(fd_); }
  BinaryFile(const BinaryFile&) = delete;
  BinaryFile& operator=(const BinaryFile&) = delete;

  void read(std::uint64_t at, void* out, std::size_t n) const {
    auto* p = static_cast<char*>(out);
    while (n > 0) {
      const ssize_t got = ::pread(fd_, p, n, off_t(at));
      if (got <= 0) throw IoError(fmt::format("{}: truncated at byte {}", path_, at));
      p += got, at += std::uint64_t(got), n -= std::size_t(got);
    }
  }
  template <class T>
  T get(std::uint64_t at) const {
    T v;
    read(at, &v, sizeof(T));
    return v;
  }

 private:
  std::string path_;
  int fd_ = -1;
};

struct Layout {
  int version = 0;
  bool native = false;
  std::map<int, Keyword> keywords;
  mb::Widths widths() const { return mb::Widths(version); }
  int real() const { return widths().real; }
  int integer() const { return widths().integer; }
  int offset() const { return widths().offset; }
};

Layout scan(const BinaryFile& f, const std::string& path) {
  Layout l;
  const auto magic = f.get<std::int32_t>(0);
  if (magic != 1) return l;  // the other byte order: read by rank 0
  l.native = true;
  l.version = f.get<std::int32_t>(4);
  if (l.version < 1 || l.version > 4) throw IoError(fmt::format("{}: libMeshb version {} unknown", path, l.version));
  std::uint64_t at = 8;
  for (int guard = 0; guard < 10000; ++guard) {
    const int code = f.get<std::int32_t>(at);
    const std::uint64_t next = l.offset() == 4 ? std::uint64_t(std::uint32_t(f.get<std::int32_t>(at + 4)))
                                               : std::uint64_t(f.get<std::int64_t>(at + 4));
    std::uint64_t body = at + 4 + std::uint64_t(l.offset());
    if (code == mb::kVertices || code == mb::kTriangles || code == mb::kTetrahedra || code == mb::kSolAtVertices ||
        code == mb::kVerticesOnGeometricVertices || code == mb::kVerticesOnGeometricTriangles) {
      Keyword k;
      k.count = l.integer() == 4 ? f.get<std::int32_t>(body) : f.get<std::int64_t>(body);
      body += std::uint64_t(l.integer());
      if (k.count < 0) throw IoError(fmt::format("{}: negative count in keyword {}", path, code));
      if (code == mb::kSolAtVertices) {
        const int n = f.get<std::int32_t>(body);
        if (n < 1 || n > 20) throw IoError(fmt::format("{}: SolAtVertices with {} fields", path, n));
        for (int i = 0; i < n; ++i) k.types.push_back(f.get<std::int32_t>(body + 4 + 4 * std::uint64_t(i)));
        body += 4 + 4 * std::uint64_t(n);
      }
      k.rows = body;
      l.keywords[code] = k;
    } else if (code != mb::kDimension && code != mb::kEnd) {
      l.keywords[code] = Keyword{};  // present, not read here
    }
    if (code == mb::kEnd || next == 0 || next <= at) break;
    at = next;
  }
  return l;
}

std::int64_t read_integer(const char* p, int width) {
  if (width == 4) {
    std::int32_t v;
    std::memcpy(&v, p, 4);
    return v;
  }
  std::int64_t v;
  std::memcpy(&v, p, 8);
  return v;
}
double read_real(const char* p, int width) {
  if (width == 4) {
    float v;
    std::memcpy(&v, p, 4);
    return v;
  }
  double v;
  std::memcpy(&v, p, 8);
  return v;
}

// Reads every rank's slices of one file together: slice i of every rank
// in one MPI_File_read_at_all (MPI-IO may gather the ranks' requests into
// large reads), a rank with fewer slices or an empty one taking part with
// no bytes; a slice in parts of at most 1 GiB (an int of bytes), as many
// on every rank. A short read (a truncated file) throws on every rank.
struct SliceRead {
  std::uint64_t at;
  std::vector<char>* into;  // sized by the caller
};

void read_together(const Comm& comm, const std::string& path, const std::vector<SliceRead>& slices) {
  constexpr std::size_t kPart = Comm::kIoPart;
  MPI_File file;
  const int opened = MPI_File_open(comm.get(), path.c_str(), MPI_MODE_RDONLY, MPI_INFO_NULL, &file);
  comm.step([&] {
    if (opened != MPI_SUCCESS) throw IoError(fmt::format("{}: cannot open for the ranks' reads", path));
  });
  std::vector<std::size_t> sizes;
  for (const auto& slice : slices) sizes.push_back(slice.into->size());
  const std::vector<std::int64_t> parts = comm.io_parts(sizes);
  const std::size_t n = parts.size();
  std::string failed;
  for (std::size_t i = 0; i < n; ++i) {
    char* data = i < slices.size() ? slices[i].into->data() : nullptr;
    const std::size_t size = i < slices.size() ? slices[i].into->size() : 0;
    const std::uint64_t at = i < slices.size() ? slices[i].at : 0;
    for (std::size_t k = 0; k < std::size_t(parts[i]); ++k) {
      const std::size_t off = std::min(size, k * kPart);
      const int bytes = int(std::min(kPart, size - off));
      MPI_Status status;
      int got = 0;
      if (MPI_File_read_at_all(file, MPI_Offset(at + off), data ? data + off : nullptr, bytes, MPI_BYTE, &status) !=
              MPI_SUCCESS ||
          MPI_Get_count(&status, MPI_BYTE, &got) != MPI_SUCCESS || got != bytes)
        if (failed.empty()) failed = fmt::format("{}: truncated at byte {}", path, at + off + std::uint64_t(got));
    }
  }
  MPI_File_close(&file);
  comm.step([&] {
    if (!failed.empty()) throw IoError(failed);
  });
}

// A VerticesOnGeometricVertices (dim 0) or VerticesOnGeometricTriangles
// (dim 2) record of the input.
struct FileRecord {
  GlobalId vertex;
  std::int32_t dim, entity;
  double u, v;
};

// The slice of every keyword this rank reads (global ids are 0-based).
struct Slices {
  std::vector<Point> points;
  std::vector<Sym6> metrics;
  GlobalId first_vertex = 0;
  std::vector<std::int64_t> vertex_starts;    // first vertex of every rank's slice, and the count last
  Part part;                                  // tet refs and triangles of the slice
  std::vector<std::array<GlobalId, 4>> tets;  // the slice's tets, by global ids until the part has its vertices
  // The input's association records of the slice (any vertex; with a model).
  std::vector<FileRecord> records;
};

void check_vertex(GlobalId v, std::int64_t n, const std::string& path, const char* what) {
  if (v < 0 || v >= n) throw IoError(fmt::format("{}: a {} names vertex {} (the mesh has {})", path, what, v + 1, n));
}

// Reads this rank's slice of every keyword of a native-order binary mesh
// (and metric): the ranks read their slices together (read_together), then
// each checks and decodes its own in a step. `ml` is the metric's layout
// (unused without a metric).
Slices read_binary_slices(const Comm& comm, const std::string& path, const Layout& l, const std::string& metric_path,
                          const Layout& ml, bool records, ReadCounts& counts) {
  Slices s;
  const auto kw = [](const Layout& layout, int code) -> const Keyword& {
    static const Keyword none;
    auto it = layout.keywords.find(code);
    return it == layout.keywords.end() ? none : it->second;
  };
  const Keyword& kv = kw(l, mb::kVertices);
  const Keyword& kt = kw(l, mb::kTetrahedra);
  const Keyword& kf = kw(l, mb::kTriangles);
  const Keyword& ks = kw(ml, mb::kSolAtVertices);
  counts.vertices = kv.count, counts.tets = kt.count, counts.triangles = kf.count;
  io::SolData sol;
  comm.step([&] {
    if (kv.count == 0 || kt.count == 0) throw IoError(fmt::format("{}: no vertices or no tetrahedra", path));
    if (metric_path.empty()) return;
    if (ml.keywords.find(mb::kSolAtVertices) == ml.keywords.end())
      throw IoError(fmt::format("{}: no SolAtVertices keyword", metric_path));
    if (ks.count != kv.count)
      throw InputError(
          fmt::format("{}: the metric has {} entries but the mesh has {} vertices", metric_path, ks.count, kv.count));
    for (int t : ks.types) {
      if (t < 1 || t > 4) throw IoError(fmt::format("{}: solution type {} unknown", metric_path, t));
      sol.types.push_back(io::SolType(t));
    }
  });
  const auto n = std::size_t(comm.size()), r = std::size_t(comm.rank());
  for (std::size_t q = 0; q <= n; ++q) s.vertex_starts.push_back(std::int64_t(std::size_t(kv.count) * q / n));
  const auto [v0, v1] = part_slice(std::size_t(kv.count), n, r);
  const auto [t0, t1] = part_slice(std::size_t(kt.count), n, r);
  const auto [f0, f1] = part_slice(std::size_t(kf.count), n, r);
  s.first_vertex = GlobalId(v0);
  const int R = l.real(), I = l.integer();
  const mb::Widths w = l.widths();
  // The slices' bytes: each keyword's rows [first, last) of this rank.
  std::vector<char> vertex_rows((v1 - v0) * w.vertex_row()), tet_rows((t1 - t0) * w.tet_row()),
      triangle_rows((f1 - f0) * w.triangle_row());
  std::vector<SliceRead> reads{{kv.rows + v0 * w.vertex_row(), &vertex_rows},
                               {kt.rows + t0 * w.tet_row(), &tet_rows},
                               {kf.rows + f0 * w.triangle_row(), &triangle_rows}};
  constexpr int kRecordCodes[2] = {mb::kVerticesOnGeometricVertices, mb::kVerticesOnGeometricTriangles};
  std::array<std::vector<char>, 2> record_rows;
  std::array<std::size_t, 2> record_first{};
  if (records)
    for (std::size_t c = 0; c < 2; ++c) {
      const Keyword& k = kw(l, kRecordCodes[c]);
      const int dim = kRecordCodes[c] - mb::kVerticesOnGeometricVertices;
      const auto [a, b] = part_slice(std::size_t(k.count), n, r);
      record_first[c] = a;
      record_rows[c].resize((b - a) * w.on_geometry_row(dim));
      reads.push_back({k.rows + a * w.on_geometry_row(dim), &record_rows[c]});
    }
  read_together(comm, path, reads);
  std::vector<char> metric_rows;
  if (!metric_path.empty()) {
    metric_rows.resize((v1 - v0) * std::size_t(sol.stride()) * std::size_t(ml.real()));
    read_together(comm, metric_path,
                  {{ks.rows + v0 * std::size_t(sol.stride()) * std::size_t(ml.real()), &metric_rows}});
  }

  comm.step([&] {
    for (std::size_t i = 0; i < v1 - v0; ++i) {
      const char* p = vertex_rows.data() + i * w.vertex_row();
      s.points.emplace_back(read_real(p, R), read_real(p + R, R), read_real(p + 2 * R, R));
      if (!s.points.back().allFinite())
        throw IoError(fmt::format("{}: vertex {} has a coordinate that is not finite", path, v0 + i + 1));
    }
    vertex_rows = {};
    for (std::size_t i = 0; i < t1 - t0; ++i) {
      const char* p = tet_rows.data() + i * w.tet_row();
      std::array<GlobalId, 4> t;
      for (int c = 0; c < 4; ++c) {
        t[c] = read_integer(p + c * I, I) - 1;
        check_vertex(t[c], kv.count, path, "tetrahedron");
      }
      s.tets.push_back(t);
      s.part.tet_refs.push_back(int(read_integer(p + 4 * I, I)));
    }
    tet_rows = {};
    for (std::size_t i = 0; i < f1 - f0; ++i) {
      const char* p = triangle_rows.data() + i * w.triangle_row();
      GlobalId a = read_integer(p, I) - 1, b = read_integer(p + I, I) - 1, c = read_integer(p + 2 * I, I) - 1;
      for (GlobalId v : {a, b, c}) check_vertex(v, kv.count, path, "triangle");
      s.part.triangles.push_back({a, b, c});
      s.part.triangle_refs.push_back(int(read_integer(p + 3 * I, I)));
    }
    triangle_rows = {};
    if (records)
      for (std::size_t c = 0; c < 2; ++c) {
        const int dim = kRecordCodes[c] - mb::kVerticesOnGeometricVertices;
        const std::size_t row = w.on_geometry_row(dim);
        for (std::size_t i = 0; i < record_rows[c].size() / row; ++i) {
          const char* p = record_rows[c].data() + i * row;
          FileRecord rec{read_integer(p, I) - 1, dim, std::int32_t(read_integer(p + I, I)), 0.0, 0.0};
          check_vertex(rec.vertex, kv.count, path, io::meshb::keyword_name(kRecordCodes[c]).data());
          if (dim == 2) rec.u = read_real(p + 2 * I, R), rec.v = read_real(p + 2 * I + R, R);
          s.records.push_back(rec);
        }
      }
    for (const auto& [code, k] : l.keywords)
      if (code != mb::kVertices && code != mb::kTetrahedra && code != mb::kTriangles &&
          !(records && code >= mb::kVerticesOnGeometricVertices && code <= mb::kVerticesOnGeometricTriangles)) {
        const auto name = io::meshb::keyword_name(code);
        counts.dropped.push_back(name.empty() ? fmt::format("keyword {}", code) : std::string(name));
      }
    if (!metric_path.empty()) {
      sol.count = v1 - v0;
      const std::size_t rr = std::size_t(ml.real());
      sol.values.resize(sol.count * std::size_t(sol.stride()));
      for (std::size_t i = 0; i < sol.values.size(); ++i)
        sol.values[i] = read_real(metric_rows.data() + i * rr, int(rr));
      s.metrics = metric_field_from_sol(sol, sol.count, metric_path);
    }
  });
  return s;
}

// Rank 0 reads the whole input with the single-process readers and sends
// each rank its slices (ASCII .mesh, .msh, the other byte order).
Slices read_on_rank0(const Comm& comm, const std::string& path, const std::string& metric_path, bool records,
                     ReadCounts& counts) {
  struct Row {
    Coords p;
    Sym6 m;
  };
  struct Tet {
    std::array<GlobalId, 4> v;
    int ref;
  };
  struct Tri {
    std::array<GlobalId, 3> v;
    int ref;
  };
  const auto n = std::size_t(comm.size());
  std::vector<std::vector<Row>> rows_out(n);
  std::vector<std::vector<Tet>> tets_out(n);
  std::vector<std::vector<Tri>> tris_out(n);
  std::vector<FileRecord> records_read;  // on rank 0; associate_slice sends each to its vertex's reader
  std::int64_t header[3] = {0, 0, 0};
  if (comm.rank() == 0) {
    comm.step([&] {
      const io::MeshData d = io::read_mesh_file(path);
      std::vector<Sym6> metric;
      if (!metric_path.empty())
        metric = metric_field_from_sol(io::read_sol(metric_path), d.vertices.size(), metric_path);
      for (std::size_t q = 0; q < n; ++q) {
        auto [a, b] = part_slice(d.vertices.size(), n, q);
        for (std::size_t i = a; i < b; ++i)
          rows_out[q].push_back({coords(d.vertices[i]), metric.empty() ? Sym6{} : metric[i]});
        auto [ta, tb] = part_slice(d.tets.size(), n, q);
        for (std::size_t i = ta; i < tb; ++i)
          tets_out[q].push_back({{d.tets[i][0], d.tets[i][1], d.tets[i][2], d.tets[i][3]}, d.tet_refs[i]});
        auto [fa, fb] = part_slice(d.triangles.size(), n, q);
        for (std::size_t i = fa; i < fb; ++i)
          tris_out[q].push_back({{d.triangles[i][0], d.triangles[i][1], d.triangles[i][2]}, d.triangle_refs[i]});
      }
      if (records)
        for (const std::size_t dim : {0, 2})
          for (const auto& g : d.on_geometry[dim])
            records_read.push_back({GlobalId(g.vertex), std::int32_t(dim), g.entity, g.u, g.v});
      header[0] = std::int64_t(d.vertices.size()), header[1] = std::int64_t(d.tets.size()),
      header[2] = std::int64_t(d.triangles.size());
      if (!d.edges.empty()) counts.dropped.push_back("Edges");
      if (!d.required_vertices.empty() || !d.required_edges.empty() || !d.required_triangles.empty())
        counts.dropped.push_back("Required*");
      if (!records && (!d.on_geometry[0].empty() || !d.on_geometry[1].empty() || !d.on_geometry[2].empty()))
        counts.dropped.push_back("VerticesOnGeometric*");
    });
  } else {
    comm.step([] {});
  }
  MPI_Bcast(header, 3, MPI_INT64_T, 0, comm.get());
  counts.vertices = header[0], counts.tets = header[1], counts.triangles = header[2];
  Slices s;
  const auto rows_in = comm.exchange(rows_out);
  const auto tets_in = comm.exchange(tets_out);
  const auto tris_in = comm.exchange(tris_out);
  s.records = std::move(records_read);
  for (std::size_t q = 0; q <= n; ++q) s.vertex_starts.push_back(std::int64_t(std::size_t(header[0]) * q / n));
  s.first_vertex = s.vertex_starts[std::size_t(comm.rank())];
  for (const auto& r : rows_in) {
    s.points.push_back(point(r.p));
    if (!metric_path.empty()) s.metrics.push_back(r.m);
  }
  for (const auto& t : tets_in) s.tets.push_back(t.v), s.part.tet_refs.push_back(t.ref);
  for (const auto& t : tris_in) s.part.triangles.push_back(t.v), s.part.triangle_refs.push_back(t.ref);
  return s;
}

// The rank that read vertex v.
std::size_t reader_of(const Slices& s, GlobalId v) {
  const auto q = std::upper_bound(s.vertex_starts.begin(), s.vertex_starts.end(), v) - s.vertex_starts.begin() - 1;
  return std::min(std::size_t(q), s.vertex_starts.size() - 2);
}

// The CAD parameters of the slice's vertices (invalid inside the domain):
// each triangle's corners go with the triangle's other two corners and
// surface id to the rank that read them.
std::vector<GeoParam> associate_slice(const Comm& comm, const Slices& s, const AssociateVertex& associate) {
  struct Corner {
    GlobalId vertex, a, b;
    std::int32_t surface, pad = 0;
  };
  const auto n = std::size_t(comm.size());
  std::vector<std::vector<Corner>> out(n);
  for (std::size_t i = 0; i < s.part.triangles.size(); ++i) {
    const auto& t = s.part.triangles[i];
    for (int c = 0; c < 3; ++c)
      out[reader_of(s, t[std::size_t(c)])].push_back(
          {t[std::size_t(c)], t[std::size_t((c + 1) % 3)], t[std::size_t((c + 2) % 3)], s.part.triangle_refs[i]});
  }
  auto in = comm.exchange(out);
  out = {};
  std::vector<std::vector<FileRecord>> records_out(n);
  for (const auto& r : s.records) records_out[reader_of(s, r.vertex)].push_back(r);
  auto records = comm.exchange(records_out);
  records_out = {};
  std::vector<GeoParam> geo(s.points.size());
  comm.step([&] {
    std::sort(in.begin(), in.end(), [](const Corner& x, const Corner& y) { return x.vertex < y.vertex; });
    std::stable_sort(records.begin(), records.end(),
                     [](const FileRecord& x, const FileRecord& y) { return x.vertex < y.vertex; });
    std::vector<FanSide> fan;
    std::vector<io::GeoRecord> on_surface;
    std::vector<const io::GeoRecord*> on_surface_of;
    auto next_record = records.begin();
    for (std::size_t i = 0; i < in.size();) {
      const GlobalId vertex = in[i].vertex;
      std::size_t j = i;
      fan.clear();
      for (; j < in.size() && in[j].vertex == vertex; ++j) {
        fan.push_back({in[j].a, in[j].surface});
        fan.push_back({in[j].b, in[j].surface});
      }
      // The input's records of this vertex.
      VertexRecords file;
      on_surface.clear();
      while (next_record != records.end() && next_record->vertex < vertex) ++next_record;
      for (; next_record != records.end() && next_record->vertex == vertex; ++next_record) {
        if (next_record->dim == 0) file.model_vertex = next_record->entity;
        if (next_record->dim == 2) on_surface.push_back({0, next_record->entity, next_record->u, next_record->v, 0.0});
      }
      on_surface_of.clear();
      for (const auto& r : on_surface) on_surface_of.push_back(&r);
      file.on_surface = on_surface_of;
      const auto local = std::size_t(vertex - s.first_vertex);
      geo[local] = associate(vertex, s.points[local], fan, file);
      i = j;
    }
  });
  return geo;
}

}  // namespace

Part read_part(const Comm& comm, const std::string& mesh_path, const std::string& metric_path, ReadCounts& counts,
               const AssociateVertex& associate) {
  Slices s;
  bool binary = false;
  // Rank 0 opens the files first: a missing or malformed file is said once.
  comm.step([&] {
    if (comm.rank() != 0) return;
    const BinaryFile mesh(mesh_path);
    if (io::format_of(mesh_path) == io::FileFormat::meshb) scan(mesh, mesh_path);
    if (metric_path.empty()) return;
    const BinaryFile metric(metric_path);
    if (io::format_of(metric_path) == io::FileFormat::solb) scan(metric, metric_path);
  });
  // Native-order binary files: their keywords found by every rank, the
  // slices read by all together.
  Layout mesh_layout, metric_layout;
  comm.step([&] {
    if (io::format_of(mesh_path) != io::FileFormat::meshb) return;
    mesh_layout = scan(BinaryFile(mesh_path), mesh_path);
    if (!mesh_layout.native) return;
    if (!metric_path.empty()) {
      if (io::encoding_of(metric_path, ".sol", ".solb") != io::Encoding::binary) return;
      metric_layout = scan(BinaryFile(metric_path), metric_path);
      if (!metric_layout.native)
        throw IoError(fmt::format("{}: a metric in the other byte order is not read under mpirun", metric_path));
    }
    binary = true;
  });
  if (binary) s = read_binary_slices(comm, mesh_path, mesh_layout, metric_path, metric_layout, bool(associate), counts);
  // Every rank takes the same path: the file is the same for all.
  if (!binary) s = read_on_rank0(comm, mesh_path, metric_path, bool(associate), counts);

  // The vertices of the slice's tets, from the ranks that read them.
  const auto n = std::size_t(comm.size());
  std::vector<GlobalId> wanted;
  for (const auto& t : s.tets) wanted.insert(wanted.end(), t.begin(), t.end());
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  std::vector<std::vector<GlobalId>> ask(n);
  for (GlobalId v : wanted) ask[reader_of(s, v)].push_back(v);
  std::vector<std::int64_t> from;
  const auto asked = comm.exchange(ask, &from);
  struct Answer {
    Coords p;
    Sym6 m;
  };
  std::vector<std::vector<Answer>> answers(n);
  std::size_t at = 0;
  for (std::size_t q = 0; q < n; ++q)
    for (std::int64_t i = 0; i < from[q]; ++i, ++at) {
      const auto local = std::size_t(asked[at] - s.first_vertex);
      answers[q].push_back({coords(s.points[local]), s.metrics.empty() ? Sym6{} : s.metrics[local]});
    }
  const auto got = comm.exchange(answers);
  answers = {};
  std::vector<GeoParam> geo_got;
  if (associate) {
    const auto geo = associate_slice(comm, s, associate);
    std::vector<std::vector<GeoParam>> geo_answers(n);
    at = 0;
    for (std::size_t q = 0; q < n; ++q)
      for (std::int64_t i = 0; i < from[q]; ++i, ++at)
        geo_answers[q].push_back(geo[std::size_t(asked[at] - s.first_vertex)]);
    geo_got = comm.exchange(geo_answers);
  }
  Part part = std::move(s.part);
  at = 0;
  for (std::size_t q = 0; q < n; ++q)
    for (GlobalId v : ask[q]) {
      part.vertex_ids.push_back(v);
      part.points.push_back(point(got[at].p));
      if (!metric_path.empty()) part.metrics.push_back(got[at].m);
      if (associate) part.geo.push_back(geo_got[at]);
      ++at;
    }
  const VertexIndex index(part.vertex_ids);
  part.tets.reserve(s.tets.size());
  for (const auto& t : s.tets) {
    LocalTet l;
    for (int c = 0; c < 4; ++c) l[std::size_t(c)] = std::uint32_t(index.find(t[std::size_t(c)]));
    part.tets.push_back(l);
  }
  return part;
}

}  // namespace metrica::distributed
