#include <metrica/distributed/write_part.hpp>
#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/io/meshb_keywords.hpp>
#include <metrica/io/vtu.hpp>

#include <fmt/core.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string_view>
#include <unistd.h>

namespace metrica::distributed {

namespace {

struct Holder {
  GlobalId id;
  std::int64_t rank;
};

// Rows of a binary file in the making: integers of the version's width,
// reals of 8 bytes (versions 2 to 4).
class Rows {
 public:
  explicit Rows(const io::meshb::Widths& w) : integer_(w.integer), offset_(w.offset) {}
  void integer(std::int64_t v) {
    if (integer_ == 4) {
      const auto x = std::int32_t(v);
      put(&x, 4);
    } else {
      put(&v, 8);
    }
  }
  void offset(std::uint64_t v) {
    if (offset_ == 4) {
      const auto x = std::int32_t(v);
      put(&x, 4);
    } else {
      put(&v, 8);
    }
  }
  void real(double v) { put(&v, 8); }
  void int32(std::int32_t v) { put(&v, 4); }
  std::string& bytes() { return out_; }

 private:
  void put(const void* p, std::size_t n) { out_.append(static_cast<const char*>(p), n); }
  int integer_, offset_;
  std::string out_;
};

// Bytes a rank writes at an offset of the shared file.
struct Piece {
  std::uint64_t at;
  std::string_view bytes;
};

// Writes every rank's pieces together: piece i of every rank in one
// MPI_File_write_at_all (MPI-IO may gather the ranks' slices into large
// requests), a rank with fewer pieces or an empty one taking part with no
// bytes; a piece in parts of at most 1 GiB (an int of bytes), as many on
// every rank. Throws on every rank when a write failed on one.
void write_together(const Comm& comm, MPI_File file, const std::vector<Piece>& pieces) {
  constexpr std::size_t kPart = Comm::kIoPart;
  std::vector<std::size_t> sizes;
  for (const auto& piece : pieces) sizes.push_back(piece.bytes.size());
  const std::vector<std::int64_t> parts = comm.io_parts(sizes);
  const std::size_t n = parts.size();
  std::string failed;
  for (std::size_t i = 0; i < n; ++i) {
    const Piece piece = i < pieces.size() ? pieces[i] : Piece{0, {}};
    for (std::size_t k = 0; k < std::size_t(parts[i]); ++k) {
      const std::size_t off = std::min(piece.bytes.size(), k * kPart);
      const int bytes = int(std::min(kPart, piece.bytes.size() - off));
      if (MPI_File_write_at_all(file, MPI_Offset(piece.at + off), piece.bytes.data() + off, bytes, MPI_BYTE,
                                MPI_STATUS_IGNORE) != MPI_SUCCESS &&
          failed.empty())
        failed = fmt::format("cannot write {} bytes at {}", bytes, piece.at + off);
    }
  }
  comm.step([&] {
    if (!failed.empty()) throw IoError(failed);
  });
}

// Pieces whose bytes they hold: made inside a step (where a rank may
// throw), written together after it.
class OwnedPieces {
 public:
  void add(std::uint64_t at, std::string bytes) { pieces_.emplace_back(at, std::move(bytes)); }
  void write(const Comm& comm, MPI_File file) const {
    std::vector<Piece> views;
    for (const auto& [at, bytes] : pieces_) views.push_back({at, bytes});
    write_together(comm, file, views);
  }

 private:
  std::vector<std::pair<std::uint64_t, std::string>> pieces_;
};

}  // namespace

SharedFile::SharedFile(const Comm& comm, const std::string& path) : comm_(comm) {
  staged_.path = path;
  if (comm.rank() == 0) staged_.temporary = fmt::format("{}.part-{}.tmp", path, ::getpid());
  std::uint64_t size = staged_.temporary.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, comm.get());
  staged_.temporary.resize(size);
  MPI_Bcast(staged_.temporary.data(), int(size), MPI_CHAR, 0, comm.get());
  const int opened =
      MPI_File_open(comm.get(), staged_.temporary.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &file_);
  comm.step([&] {
    if (opened != MPI_SUCCESS && comm.rank() == 0)
      throw IoError(fmt::format("{}: cannot create the output next to it ({})", path, staged_.temporary));
  });
  open_ = true;
}

SharedFile::~SharedFile() {
  if (open_) MPI_File_close(&file_);
  if (!closed_ && comm_.rank() == 0) std::remove(staged_.temporary.c_str());
}

StagedFile SharedFile::close() {
  MPI_File_close(&file_);
  open_ = false;
  closed_ = true;
  return staged_;
}

StagedOutputs::~StagedOutputs() {
  if (comm_.rank() == 0)
    for (std::size_t i = renamed_; i < files_.size(); ++i) std::remove(files_[i].temporary.c_str());
}

void StagedOutputs::commit() {
  comm_.step([&] {
    if (comm_.rank() != 0) return;
    for (; renamed_ < files_.size(); ++renamed_) {
      const StagedFile& f = files_[renamed_];
      if (std::rename(f.temporary.c_str(), f.path.c_str()) != 0)
        throw IoError(fmt::format("{}: cannot rename {} to it ({})", f.path, f.temporary, std::strerror(errno)));
    }
  });
}

VertexNumbering number_vertices(const Comm& comm, const Part& part) {
  VertexNumbering out;
  const auto n = std::size_t(comm.size());
  const int me = comm.rank();
  const VertexIndex index(part.vertex_ids);
  // Which vertices other ranks hold too, and the lowest holder of each.
  std::vector<bool> on_shared(part.vertex_ids.size(), false);
  std::vector<std::vector<Holder>> ask(n);
  for (const auto& f : part.shared_faces)
    for (GlobalId g : f) {
      const auto v = std::size_t(index.find(g));
      if (on_shared[v]) continue;
      on_shared[v] = true;
      ask[std::size_t(owner_of(std::uint64_t(g), comm.size()))].push_back({g, me});
    }
  std::vector<std::int64_t> from;
  auto holders = comm.exchange(ask, &from);
  {
    std::vector<Holder> lowest = holders;
    std::sort(lowest.begin(), lowest.end(),
              [](const Holder& a, const Holder& b) { return a.id != b.id ? a.id < b.id : a.rank < b.rank; });
    lowest.erase(std::unique(lowest.begin(), lowest.end(), [](auto& a, auto& b) { return a.id == b.id; }),
                 lowest.end());
    std::vector<std::vector<Holder>> reply(n);
    std::size_t at = 0;
    for (std::size_t q = 0; q < n; ++q)
      for (std::int64_t i = 0; i < from[q]; ++i, ++at) {
        auto it = std::lower_bound(lowest.begin(), lowest.end(), holders[at],
                                   [](const Holder& a, const Holder& b) { return a.id < b.id; });
        reply[q].push_back({holders[at].id, it->rank});
      }
    holders = comm.exchange(reply);
  }
  // The owner of each local vertex (this rank unless a lower one holds it).
  std::vector<int>& owner = out.owner;
  owner.assign(part.vertex_ids.size(), me);
  for (const auto& h : holders) owner[std::size_t(index.find(h.id))] = int(h.rank);
  for (int o : owner) out.owned += o == me;
  out.first = comm.exclusive_scan(out.owned);
  out.total = comm.sum(out.owned);
  std::vector<std::int64_t>& number = out.number;
  number.assign(part.vertex_ids.size(), 0);
  {
    std::int64_t at = out.first;
    for (std::size_t v = 0; v < owner.size(); ++v)
      if (owner[v] == me) number[v] = ++at;
    // The numbers of the vertices a lower rank writes, from that rank.
    std::vector<std::vector<GlobalId>> want(n);
    for (std::size_t v = 0; v < owner.size(); ++v)
      if (owner[v] != me) want[std::size_t(owner[v])].push_back(part.vertex_ids[v]);
    std::vector<std::int64_t> asked_from;
    const auto asked = comm.exchange(want, &asked_from);
    std::vector<std::vector<std::int64_t>> answer(n);
    std::size_t k = 0;
    for (std::size_t q = 0; q < n; ++q)
      for (std::int64_t i = 0; i < asked_from[q]; ++i, ++k)
        answer[q].push_back(number[std::size_t(index.find(asked[k]))]);
    const auto got = comm.exchange(answer);
    k = 0;
    for (std::size_t q = 0; q < n; ++q)
      for (GlobalId g : want[q]) number[std::size_t(index.find(g))] = got[k++];
  }
  return out;
}

namespace {

// The part's triangles this rank writes: one on a face between parts is
// written by the lower rank.
std::vector<std::uint32_t> triangles_written(const Part& part, int me) {
  std::vector<std::pair<FaceKey, int>> across;
  for (std::size_t i = 0; i < part.shared_faces.size(); ++i)
    across.emplace_back(part.shared_faces[i], part.shared_with[i]);
  std::sort(across.begin(), across.end());
  std::vector<std::uint32_t> triangles;
  for (std::size_t i = 0; i < part.triangles.size(); ++i) {
    const auto key = face_key(part.triangles[i]);
    auto it = std::lower_bound(across.begin(), across.end(), std::pair<FaceKey, int>{key, -1});
    if (it != across.end() && it->first == key && it->second < me) continue;
    triangles.push_back(std::uint32_t(i));
  }
  return triangles;
}

// The CAD association of the vertices this rank writes, numbered among
// them, with what refine and Feflo.a also read (complete_geometry_records).
io::MeshData geometry_records(const Part& part, const VertexNumbering& numbering, int me, const CadModel* model) {
  io::MeshData records;
  if (model == nullptr || part.geo.empty()) return records;
  VertexId k = 0;
  for (std::size_t v = 0; v < numbering.owner.size(); ++v) {
    if (numbering.owner[v] != me) continue;
    const GeoParam& g = part.geo[v];
    if (g.valid()) records.on_geometry[std::size_t(g.dim)].push_back({k, g.tag, g.u, g.v, 0.0});
    ++k;
  }
  complete_geometry_records(records, *model);
  return records;
}

// What this rank writes besides its vertices and tets, and the counts of
// the whole file.
struct Written {
  std::vector<std::uint32_t> triangles;
  io::MeshData records;
  WrittenCounts total;
};
Written written_by(const Comm& comm, const Part& part, const VertexNumbering& numbering, const CadModel* model) {
  Written w;
  w.triangles = triangles_written(part, comm.rank());
  w.records = geometry_records(part, numbering, comm.rank(), model);
  w.total.vertices = numbering.total;
  w.total.triangles = comm.sum(std::int64_t(w.triangles.size()));
  w.total.tets = comm.sum(std::int64_t(part.tets.size()));
  return w;
}

}  // namespace

StagedFile write_part(const Comm& comm, const Part& part, const VertexNumbering& numbering, const std::string& path,
                      int version, const CadModel* model, WrittenCounts* counts) {
  const int me = comm.rank();
  const VertexIndex index(part.vertex_ids);
  const auto& owner = numbering.owner;
  const auto& number = numbering.number;
  const std::int64_t first_vertex = numbering.first;
  auto [triangles, records, total] = written_by(comm, part, numbering, model);
  const std::int64_t first_triangle = comm.exclusive_scan(std::int64_t(triangles.size()));
  const std::int64_t first_tet = comm.exclusive_scan(std::int64_t(part.tets.size()));
  std::array<std::int64_t, 3> on_total{}, on_first{};
  for (std::size_t d = 0; d < 3; ++d) {
    on_total[d] = comm.sum(std::int64_t(records.on_geometry[d].size()));
    on_first[d] = comm.exclusive_scan(std::int64_t(records.on_geometry[d].size()));
  }
  using namespace io::meshb;
  if (version == 0) {
    // The smallest version that holds the counts and the file's size.
    const auto rows_max = std::uint64_t(std::max({total.vertices, total.triangles, total.tets}));
    const Widths v2(2);
    const std::uint64_t v2_bytes =
        std::uint64_t(total.vertices) * v2.vertex_row() + std::uint64_t(total.triangles) * v2.triangle_row() +
        std::uint64_t(total.tets) * v2.tet_row() + std::uint64_t(on_total[0]) * v2.on_geometry_row(0) +
        std::uint64_t(on_total[1]) * v2.on_geometry_row(1) + std::uint64_t(on_total[2]) * v2.on_geometry_row(2);
    version = rows_max > kMaxRowsOfShortIntegers ? 4 : v2_bytes > kMaxBytesOfShortOffsets ? 3 : 2;
  }
  total.version = version;
  const Widths w(version);
  const std::uint64_t head = w.keyword_head();
  // Byte layout: header, Dimension, then each keyword with rows (Vertices,
  // Triangles, Tetrahedra, VerticesOnGeometric*), End.
  struct Block {
    int code;
    std::int64_t rows;
    std::uint64_t row_bytes, at = 0;
  };
  std::vector<Block> blocks{{kVertices, total.vertices, w.vertex_row()},
                            {kTriangles, total.triangles, w.triangle_row()},
                            {kTetrahedra, total.tets, w.tet_row()}};
  for (int d = 0; d < 3; ++d)
    blocks.push_back({kVerticesOnGeometricVertices + d, on_total[std::size_t(d)], w.on_geometry_row(d)});
  std::erase_if(blocks, [](const Block& b) { return b.rows == 0 && b.code != kVertices && b.code != kTetrahedra; });
  const std::uint64_t dimension_at = 8;
  std::uint64_t end_at = dimension_at + 4 + std::uint64_t(w.offset) + 4;
  for (auto& b : blocks) {
    b.at = end_at;
    end_at += head + std::uint64_t(b.rows) * b.row_bytes;
  }
  const auto block = [&](int code) -> const Block* {
    for (const auto& b : blocks)
      if (b.code == code) return &b;
    return nullptr;
  };

  // An error on any rank: every rank throws, and `out` removes the temporary.
  SharedFile out(comm, path);
  OwnedPieces pieces;  // rank 0's heads, then every rank's rows
  comm.step([&] {
    if (me == 0) {
      Rows h(w);
      h.int32(1), h.int32(version);
      h.int32(kDimension), h.offset(blocks[0].at), h.int32(3);
      pieces.add(0, std::move(h.bytes()));
      for (std::size_t i = 0; i < blocks.size(); ++i) {
        Rows k(w);
        k.int32(blocks[i].code), k.offset(i + 1 < blocks.size() ? blocks[i + 1].at : end_at);
        k.integer(blocks[i].rows);
        pieces.add(blocks[i].at, std::move(k.bytes()));
      }
      Rows end(w);
      end.int32(kEnd), end.offset(0);
      pieces.add(end_at, std::move(end.bytes()));
    }
    const auto rows_at = [&](int code, std::int64_t first) {
      const Block* b = block(code);
      return b->at + head + std::uint64_t(first) * b->row_bytes;
    };
    Rows v(w);
    for (std::size_t i = 0; i < owner.size(); ++i) {
      if (owner[i] != me) continue;
      const auto& p = part.points[i];
      v.real(p.x()), v.real(p.y()), v.real(p.z()), v.integer(0);
    }
    pieces.add(rows_at(kVertices, first_vertex), std::move(v.bytes()));
    if (total.triangles) {
      Rows f(w);
      for (auto i : triangles) {
        for (GlobalId g : part.triangles[i]) f.integer(number[std::size_t(index.find(g))]);
        f.integer(part.triangle_refs[i]);
      }
      pieces.add(rows_at(kTriangles, first_triangle), std::move(f.bytes()));
    }
    Rows t(w);
    for (std::size_t i = 0; i < part.tets.size(); ++i) {
      for (auto l : part.tets[i]) t.integer(number[l]);
      t.integer(part.tet_refs[i]);
    }
    pieces.add(rows_at(kTetrahedra, first_tet), std::move(t.bytes()));
    for (int d = 0; d < 3; ++d) {
      const auto& list = records.on_geometry[std::size_t(d)];
      if (on_total[std::size_t(d)] == 0) continue;
      Rows g(w);
      for (const auto& r : list) {
        g.integer(first_vertex + std::int64_t(r.vertex) + 1), g.integer(r.entity);
        if (d >= 1) g.real(r.u);
        if (d == 2) g.real(r.v);
        if (d >= 1) g.real(r.dist);
      }
      pieces.add(rows_at(kVerticesOnGeometricVertices + d, on_first[std::size_t(d)]), std::move(g.bytes()));
    }
  });
  pieces.write(comm, out.file());
  if (counts != nullptr) *counts = total;
  return out.close();
}

namespace {

// Text placed in one shared file by all ranks in turn: rank 0's keyword
// lines, then each keyword's rows, each rank's after those of the ranks
// before it (an exclusive scan of their byte counts). Every rank knows
// where the next text goes.
class TextPlacer {
 public:
  TextPlacer(const Comm& comm, MPI_File file) : comm_(comm), file_(file) {}
  void head(const std::string& text) {
    write_together(comm_, file_, {{at_, comm_.rank() == 0 ? std::string_view(text) : std::string_view()}});
    at_ += text.size();
  }
  void rows(const fmt::memory_buffer& text) {
    const auto mine = std::int64_t(text.size());
    const auto before = std::uint64_t(comm_.exclusive_scan(mine));
    const auto all = std::uint64_t(comm_.sum(mine));
    write_together(comm_, file_, {{at_ + before, std::string_view(text.data(), text.size())}});
    at_ += all;
  }

 private:
  const Comm& comm_;
  MPI_File file_;
  std::uint64_t at_ = 0;
};

}  // namespace

StagedFile write_part_text(const Comm& comm, const Part& part, const VertexNumbering& numbering,
                           const std::string& path, int version, const CadModel* model, WrittenCounts* counts) {
  const int me = comm.rank();
  const VertexIndex index(part.vertex_ids);
  auto [triangles, records, total] = written_by(comm, part, numbering, model);
  total.version = version == 0 ? 2 : version;
  using namespace io::meshb;
  SharedFile out(comm, path);
  TextPlacer place(comm, out.file());
  const auto keyword = [](int code, std::int64_t rows) {
    return fmt::format("\n{}\n{}\n", io::meshb::keyword_name(code), rows);
  };
  fmt::memory_buffer text;
  const auto to = [&] { return std::back_inserter(text); };
  place.head(fmt::format("MeshVersionFormatted {}\n\nDimension 3\n", total.version));
  if (total.vertices > 0) {
    place.head(keyword(kVertices, total.vertices));
    comm.step([&] {
      for (std::size_t v = 0; v < numbering.owner.size(); ++v) {
        if (numbering.owner[v] != me) continue;
        const auto& p = part.points[v];
        if (!p.allFinite()) throw IoError(fmt::format("{}: a vertex is not finite; nothing written", path));
        fmt::format_to(to(), "{} {} {} 0\n", p.x(), p.y(), p.z());
      }
    });
    place.rows(text);
    text.clear();
  }
  if (total.triangles > 0) {
    place.head(keyword(kTriangles, total.triangles));
    for (auto i : triangles) {
      const auto& f = part.triangles[i];
      const auto n = [&](int c) { return numbering.number[std::size_t(index.find(f[std::size_t(c)]))]; };
      fmt::format_to(to(), "{} {} {} {}\n", n(0), n(1), n(2), part.triangle_refs[i]);
    }
    place.rows(text);
    text.clear();
  }
  if (total.tets > 0) {
    place.head(keyword(kTetrahedra, total.tets));
    for (std::size_t t = 0; t < part.tets.size(); ++t) {
      const auto& l = part.tets[t];
      const auto& n = numbering.number;
      fmt::format_to(to(), "{} {} {} {} {}\n", n[l[0]], n[l[1]], n[l[2]], n[l[3]], part.tet_refs[t]);
    }
    place.rows(text);
    text.clear();
  }
  for (int d = 0; d < 3; ++d) {
    const auto& list = records.on_geometry[std::size_t(d)];
    const std::int64_t rows = comm.sum(std::int64_t(list.size()));
    if (rows == 0) continue;
    place.head(keyword(kVerticesOnGeometricVertices + d, rows));
    for (const auto& r : list) {
      fmt::format_to(to(), "{} {}", numbering.first + std::int64_t(r.vertex) + 1, r.entity);
      if (d == 1) fmt::format_to(to(), " {} {}", r.u, r.dist);
      if (d == 2) fmt::format_to(to(), " {} {} {}", r.u, r.v, r.dist);
      text.push_back('\n');
    }
    place.rows(text);
    text.clear();
  }
  place.head("\nEnd\n");
  if (counts != nullptr) *counts = total;
  return out.close();
}

StagedFile write_part_metric(const Comm& comm, const VertexNumbering& numbering,
                             const std::function<Sym6(std::size_t)>& metric_of, const std::string& path, int version) {
  const int me = comm.rank();
  // Version 1 stores single-precision reals: the mesh's version from 2 on.
  using namespace io::meshb;
  const Widths w(version);
  const std::uint64_t head = w.one_field_sol_head(), row = w.sym_matrix_row();
  const std::uint64_t dimension_at = 8, sol_at = dimension_at + 4 + std::uint64_t(w.offset) + 4;
  const std::uint64_t end_at = sol_at + head + std::uint64_t(numbering.total) * row;
  SharedFile out(comm, path);
  OwnedPieces pieces;
  comm.step([&] {
    if (me == 0) {
      Rows h(w);
      h.int32(1), h.int32(version);
      h.int32(kDimension), h.offset(sol_at), h.int32(3);
      h.int32(kSolAtVertices), h.offset(end_at), h.integer(numbering.total);
      h.int32(1), h.int32(std::int32_t(io::SolType::sym_matrix));
      pieces.add(0, std::move(h.bytes()));
      Rows end(w);
      end.int32(kEnd), end.offset(0);
      pieces.add(end_at, std::move(end.bytes()));
    }
    Rows rows(w);
    for (std::size_t v = 0; v < numbering.owner.size(); ++v) {
      if (numbering.owner[v] != me) continue;
      const Sym6 m = metric_of(v);
      for (double x : m) {
        if (!std::isfinite(x)) throw IoError(fmt::format("{}: a non-finite metric entry; nothing written", path));
        rows.real(x);
      }
    }
    pieces.add(sol_at + head + std::uint64_t(numbering.first) * row, std::move(rows.bytes()));
  });
  pieces.write(comm, out.file());
  return out.close();
}

StagedFile write_part_metric_text(const Comm& comm, const VertexNumbering& numbering,
                                  const std::function<Sym6(std::size_t)>& metric_of, const std::string& path,
                                  int version) {
  const int me = comm.rank();
  SharedFile out(comm, path);
  TextPlacer place(comm, out.file());
  place.head(fmt::format("MeshVersionFormatted {}\n\nDimension 3\n\n{}\n{}\n1 {}\n", version,
                         io::meshb::keyword_name(io::meshb::kSolAtVertices), numbering.total,
                         int(io::SolType::sym_matrix)));
  fmt::memory_buffer text;
  comm.step([&] {
    for (std::size_t v = 0; v < numbering.owner.size(); ++v) {
      if (numbering.owner[v] != me) continue;
      const Sym6 m = metric_of(v);
      for (double x : m)
        if (!std::isfinite(x)) throw IoError(fmt::format("{}: a non-finite metric entry; nothing written", path));
      fmt::format_to(std::back_inserter(text), "{} {} {} {} {} {}\n", m[0], m[1], m[2], m[3], m[4], m[5]);
    }
  });
  place.rows(text);
  place.head("\nEnd\n");
  return out.close();
}

StagedFile write_part_vtu(const Comm& comm, const Part& part, const VertexNumbering& numbering,
                          const std::string& path) {
  const int me = comm.rank();
  const VertexIndex index(part.vertex_ids);
  const auto tets = std::int64_t(part.tets.size());
  const std::int64_t total_tets = comm.sum(tets), first_tet = comm.exclusive_scan(tets);
  // The surface triangles after every tet, in the .meshb's order (each
  // rank's written triangles, rank after rank).
  const std::vector<std::uint32_t> triangles = triangles_written(part, me);
  const auto own_triangles = std::int64_t(triangles.size());
  const std::int64_t total_triangles = comm.sum(own_triangles), first_triangle = comm.exclusive_scan(own_triangles);
  // The single process's layout (io/vtu.hpp): rank 0 writes the head, the
  // arrays' counts and the tail; each rank its slice of every array.
  const io::VtuLayout layout(std::uint64_t(numbering.total), std::uint64_t(total_tets), {}, {},
                             std::uint64_t(total_triangles));
  SharedFile out(comm, path);
  OwnedPieces pieces;
  const auto put = [](std::string& bytes, const auto& value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof(value));
  };
  comm.step([&] {
    if (me == 0) {
      pieces.add(0, layout.head());
      for (std::size_t k = 0; k < layout.arrays().size(); ++k) pieces.add(layout.count_at(k), layout.count_bytes(k));
      pieces.add(layout.tail_at(), std::string(io::VtuLayout::tail()));
    }
    std::string points;
    for (std::size_t v = 0; v < numbering.owner.size(); ++v) {
      if (numbering.owner[v] != me) continue;
      for (int c = 0; c < 3; ++c) {
        const double x = part.points[v][c];
        if (!std::isfinite(x)) throw IoError(fmt::format("{}: a vertex is not finite; nothing written", path));
        put(points, x);
      }
    }
    pieces.add(layout.values_at(io::VtuLayout::kPoints) + 24 * std::uint64_t(numbering.first), std::move(points));
    std::string connectivity, offsets, types(part.tets.size(), char(10)), refs;  // 10: VTK_TETRA
    for (std::size_t t = 0; t < part.tets.size(); ++t) {
      for (auto v : part.tets[t]) put(connectivity, std::int64_t(numbering.number[v] - 1));
      put(offsets, std::int64_t(4 * (first_tet + std::int64_t(t) + 1)));
      put(refs, std::int32_t(part.tet_refs[t]));
    }
    const auto first = std::uint64_t(first_tet);
    pieces.add(layout.values_at(io::VtuLayout::kConnectivity) + 32 * first, std::move(connectivity));
    pieces.add(layout.values_at(io::VtuLayout::kOffsets) + 8 * first, std::move(offsets));
    pieces.add(layout.values_at(io::VtuLayout::kTypes) + first, std::move(types));
    pieces.add(layout.values_at(layout.refs()) + 4 * first, std::move(refs));
    std::string f_connectivity, f_offsets, f_types(triangles.size(), char(5)), f_refs;  // 5: VTK_TRIANGLE
    for (std::size_t j = 0; j < triangles.size(); ++j) {
      for (GlobalId g : part.triangles[triangles[j]])
        put(f_connectivity, std::int64_t(numbering.number[std::size_t(index.find(g))] - 1));
      put(f_offsets, std::int64_t(4 * total_tets + 3 * (first_triangle + std::int64_t(j) + 1)));
      put(f_refs, std::int32_t(part.triangle_refs[triangles[j]]));
    }
    const auto cell = std::uint64_t(total_tets + first_triangle);  // the first triangle's cell
    pieces.add(layout.values_at(io::VtuLayout::kConnectivity) + 32 * std::uint64_t(total_tets) +
                   24 * std::uint64_t(first_triangle),
               std::move(f_connectivity));
    pieces.add(layout.values_at(io::VtuLayout::kOffsets) + 8 * cell, std::move(f_offsets));
    pieces.add(layout.values_at(io::VtuLayout::kTypes) + cell, std::move(f_types));
    pieces.add(layout.values_at(layout.refs()) + 4 * cell, std::move(f_refs));
  });
  pieces.write(comm, out.file());
  return out.close();
}

}  // namespace metrica::distributed
