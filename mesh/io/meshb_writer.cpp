// libMeshb writer: .mesh / .meshb and .sol / .solb.
#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/meshb_keywords.hpp>
#include <metrica/log.hpp>
#include <metrica/part_runner.hpp>

#include <fmt/format.h>

#include <cstring>
#include <iterator>
#include <limits>
#include <vector>

namespace metrica::io {
namespace {

using namespace meshb;

// Both writers build their output in a buffer; given a file, they hand
// the buffer to it whenever it passes kFlushBytes (after a whole entity),
// so that writing a mesh costs a buffer, not a second copy of the file.
constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

// Appends binary words; keywords are chained by patching each keyword's
// next-offset field when the following keyword begins (in the buffer, or
// in the file once flushed).
class BinaryWriter {
 public:
  explicit BinaryWriter(int version, AtomicFile* file = nullptr) : w_(version), file_(file) {
    put<std::int32_t>(kMagic);
    put<std::int32_t>(version);
    begin(kDimension);
    put<std::int32_t>(3);  // always a 32-bit word
  }

  void begin(int code) {
    patch_previous();
    put<std::int32_t>(code);
    offset_field_ = flushed_ + out_.size();
    if (w_.offset == 4)
      put<std::int32_t>(0);
    else
      put<std::int64_t>(0);
  }
  void count(std::size_t n) { integer(static_cast<std::int64_t>(n)); }
  void integer(std::int64_t v) {
    if (w_.integer == 4)
      put<std::int32_t>(static_cast<std::int32_t>(v));
    else
      put<std::int64_t>(v);
  }
  void index(std::uint32_t v) { integer(std::int64_t(v) + 1); }
  void real(double x) {
    if (w_.real == 4)
      put<float>(static_cast<float>(x));
    else
      put<double>(x);
  }
  template <class T>
  void put(T v) {
    const auto n = out_.size();
    out_.resize(n + sizeof(T));
    std::memcpy(out_.data() + n, &v, sizeof(T));
  }
  // row(i, *this) for i in [0, n), the buffer handed to the file when full.
  template <class Row>
  void rows(std::size_t n, Row&& row) {
    for (std::size_t i = 0; i < n; ++i) {
      row(i, *this);
      maybe_flush();
    }
  }
  // The whole output (no file), or the rest written to the file.
  std::string finish() {
    begin(kEnd);  // End's own next-offset stays 0
    if (file_ == nullptr) return std::move(out_);
    file_->write(out_);
    return {};
  }
  void reserve(std::size_t n) { out_.reserve(file_ == nullptr ? n : std::min(n, 2 * kFlushBytes)); }

 private:
  // After a whole entity: hands a full buffer to the file.
  void maybe_flush() {
    if (file_ == nullptr || out_.size() < kFlushBytes) return;
    file_->write(out_);
    flushed_ += out_.size();
    out_.clear();
  }
  void patch_previous() {
    if (offset_field_ == 0) return;
    const std::uint64_t here = flushed_ + out_.size();
    char bytes[8];
    std::size_t width = 4;
    if (w_.offset == 4) {
      const auto v = static_cast<std::int32_t>(here);
      std::memcpy(bytes, &v, 4);
    } else {
      const auto v = static_cast<std::int64_t>(here);
      std::memcpy(bytes, &v, 8);
      width = 8;
    }
    if (offset_field_ >= flushed_)
      std::memcpy(out_.data() + (offset_field_ - flushed_), bytes, width);
    else
      file_->write_at(offset_field_, bytes, width);
  }

  Widths w_;
  AtomicFile* file_;
  std::string out_;
  std::uint64_t flushed_ = 0;  // bytes already handed to the file
  std::uint64_t offset_field_ = 0;
};

// One row of an ASCII file: numbers separated by spaces, the line ended
// without a trailing space.
class TextRow {
 public:
  TextRow(fmt::memory_buffer& buf, int version) : buf_(buf), version_(version) {}
  void integer(std::int64_t v) { fmt::format_to(std::back_inserter(buf_), "{} ", v); }
  void index(std::uint32_t v) { integer(std::int64_t(v) + 1); }
  void real(double x) {
    // Shortest representation that reads back to the same value.
    if (version_ == 1)
      fmt::format_to(std::back_inserter(buf_), "{} ", static_cast<float>(x));
    else
      fmt::format_to(std::back_inserter(buf_), "{} ", x);
  }
  void end_line() {
    if (buf_.size() > 0 && buf_[buf_.size() - 1] == ' ') buf_.resize(buf_.size() - 1);
    buf_.push_back('\n');
  }

 private:
  fmt::memory_buffer& buf_;
  int version_;
};

// Formatting the numbers is most of an ASCII write: the rows of a long
// keyword are formatted in chunks on run's parts, a batch of chunks at a
// time, and handed to the file in order, so the bytes are those of one
// thread.
class TextWriter {
 public:
  TextWriter(int version, AtomicFile* file = nullptr, const PartRunner& run = {})
      : version_(version), file_(file), run_(run) {
    fmt::format_to(it(), "MeshVersionFormatted {}\n\nDimension 3\n", version);
  }
  void begin(int code) { fmt::format_to(it(), "\n{}\n", keyword_name(code)); }
  void count(std::size_t n) { fmt::format_to(it(), "{}\n", n); }
  void integer(std::int64_t v) { TextRow(buf_, version_).integer(v); }
  void end_line() { TextRow(buf_, version_).end_line(); }
  // row(i, r) writes row i through r (a TextRow) for i in [0, n).
  template <class Row>
  void rows(std::size_t n, Row&& row) {
    constexpr std::size_t kChunkRows = 16384;
    const std::size_t chunks = (n + kChunkRows - 1) / kChunkRows;
    if (run_.parts <= 1 || chunks < 2) {
      TextRow r(buf_, version_);
      for (std::size_t i = 0; i < n; ++i) {
        row(i, r);
        r.end_line();
        maybe_flush();
      }
      return;
    }
    const std::size_t batch = std::min(chunks, 4 * run_.parts);
    std::vector<fmt::memory_buffer> formatted(batch);
    for (std::size_t first = 0; first < chunks; first += batch) {
      const std::size_t k = std::min(batch, chunks - first);
      run_(k, [&](std::size_t j) {
        fmt::memory_buffer& b = formatted[j];
        b.clear();
        TextRow r(b, version_);
        const std::size_t lo = (first + j) * kChunkRows, hi = std::min(n, lo + kChunkRows);
        for (std::size_t i = lo; i < hi; ++i) {
          row(i, r);
          r.end_line();
        }
      });
      for (std::size_t j = 0; j < k; ++j) {
        if (file_ == nullptr) {
          buf_.append(formatted[j].data(), formatted[j].data() + formatted[j].size());
          continue;
        }
        flush();
        file_->write(formatted[j].data(), formatted[j].size());
      }
    }
  }
  std::string finish() {
    fmt::format_to(it(), "\nEnd\n");
    if (file_ == nullptr) return fmt::to_string(buf_);
    flush();
    return {};
  }

 private:
  void maybe_flush() {
    if (file_ != nullptr && buf_.size() >= kFlushBytes) flush();
  }
  void flush() {
    file_->write(buf_.data(), buf_.size());
    buf_.clear();
  }
  std::back_insert_iterator<fmt::memory_buffer> it() { return std::back_inserter(buf_); }
  int version_;
  AtomicFile* file_;
  PartRunner run_;
  fmt::memory_buffer buf_;
};

template <class Writer, class Entities>
void write_elements(Writer& w, int code, const Entities& entities, const std::vector<int>& refs) {
  if (entities.empty()) return;
  w.begin(code);
  w.count(entities.size());
  w.rows(entities.size(), [&](std::size_t i, auto& r) {
    for (auto v : entities[i]) r.index(v);
    r.integer(i < refs.size() ? refs[i] : 0);
  });
}

template <class Writer, class List>
void write_list(Writer& w, int code, const List& list) {
  if (list.empty()) return;
  w.begin(code);
  w.count(list.size());
  w.rows(list.size(), [&](std::size_t i, auto& r) { r.index(list[i]); });
}

template <class Writer>
std::string write_mesh_to(Writer w, const MeshData& m) {
  if (!m.vertices.empty()) {
    w.begin(kVertices);
    w.count(m.vertices.size());
    w.rows(m.vertices.size(), [&](std::size_t i, auto& r) {
      const auto& p = m.vertices[i];
      r.real(p.x());
      r.real(p.y());
      r.real(p.z());
      r.integer(i < m.vertex_refs.size() ? m.vertex_refs[i] : 0);
    });
  }
  write_elements(w, kEdges, m.edges, m.edge_refs);
  write_elements(w, kTriangles, m.triangles, m.triangle_refs);
  write_elements(w, kTetrahedra, m.tets, m.tet_refs);
  for (int dim = 0; dim < 3; ++dim) {
    const auto& list = m.on_geometry[static_cast<std::size_t>(dim)];
    if (list.empty()) continue;
    w.begin(kVerticesOnGeometricVertices + dim);
    w.count(list.size());
    w.rows(list.size(), [&](std::size_t i, auto& r) {
      const auto& g = list[i];
      r.index(g.vertex);
      r.integer(g.entity);
      if (dim >= 1) r.real(g.u);
      if (dim == 2) r.real(g.v);
      if (dim >= 1) r.real(g.dist);
    });
  }
  write_list(w, kCorners, m.corners);
  write_list(w, kRidges, m.ridges);
  write_list(w, kRequiredVertices, m.required_vertices);
  write_list(w, kRequiredEdges, m.required_edges);
  write_list(w, kRequiredTriangles, m.required_triangles);
  return w.finish();
}

template <class Writer>
std::string write_sol_to(Writer w, const SolData& s) {
  w.begin(kSolAtVertices);
  w.count(s.count);
  // The solution header's type count and types are 32-bit in every version.
  if constexpr (std::is_same_v<Writer, BinaryWriter>) {
    w.template put<std::int32_t>(static_cast<std::int32_t>(s.types.size()));
    for (auto t : s.types) w.template put<std::int32_t>(static_cast<std::int32_t>(t));
  } else {
    w.integer(static_cast<std::int64_t>(s.types.size()));
    for (auto t : s.types) w.integer(static_cast<int>(t));
    w.end_line();
  }
  const auto stride = static_cast<std::size_t>(s.stride());
  w.rows(s.count, [&](std::size_t i, auto& r) {
    for (std::size_t k = 0; k < stride; ++k) r.real(s.values[i * stride + k]);
  });
  return w.finish();
}

// Bytes a binary file would take with 32-bit offsets; past 2 GB the
// offsets overflow and version 3 is needed.
std::uint64_t binary_size_estimate(const MeshData& m, int version) {
  const Widths w(version);
  return 64 + m.vertices.size() * w.vertex_row() + m.edges.size() * 3ull * w.integer +
         m.triangles.size() * w.triangle_row() + m.tets.size() * w.tet_row() +
         (m.corners.size() + m.ridges.size() + m.required_vertices.size() + m.required_edges.size() +
          m.required_triangles.size()) *
             std::uint64_t(w.integer);
}

// `v2_size`: the binary size with version-2 widths (at least version 1's).
int choose_version(int requested, int data_version, Encoding enc, std::uint64_t v2_size) {
  int version = requested != 0 ? requested : data_version;
  if (version < 1 || version > 4) throw IoError(fmt::format("unsupported libMeshb version {} for writing", version));
  if (enc == Encoding::binary && version <= 2 && v2_size > kMaxBytesOfShortOffsets) {
    log::warn("output exceeds 2 GB: writing libMeshb version 3 (64-bit offsets) instead of {}", version);
    version = 3;
  }
  return version;
}

// The whole output as a string (file null), or streamed to the file.
std::string mesh_output(const MeshData& data, Encoding encoding, int version, AtomicFile* file, const PartRunner& run) {
  version = choose_version(version, data.version, encoding, binary_size_estimate(data, 2));
  if (encoding == Encoding::binary) {
    BinaryWriter w(version, file);
    w.reserve(binary_size_estimate(data, version));
    return write_mesh_to(std::move(w), data);
  }
  return write_mesh_to(TextWriter(version, file, run), data);
}

std::string sol_output(const SolData& data, Encoding encoding, int version, AtomicFile* file, const PartRunner& run) {
  if (data.values.size() != data.count * std::size_t(data.stride()))
    throw IoError(
        fmt::format("solution holds {} values, expected {} x {}", data.values.size(), data.count, data.stride()));
  version = choose_version(version, data.version, encoding, 64 + data.values.size() * std::uint64_t{8});
  if (encoding == Encoding::binary) return write_sol_to(BinaryWriter(version, file), data);
  return write_sol_to(TextWriter(version, file, run), data);
}

}  // namespace

std::string format_mesh(const MeshData& data, Encoding encoding, int version, const PartRunner& run) {
  return mesh_output(data, encoding, version, nullptr, run);
}

std::string format_sol(const SolData& data, Encoding encoding, int version, const PartRunner& run) {
  return sol_output(data, encoding, version, nullptr, run);
}

void write_meshb(const std::string& path, const MeshData& data, int version, const PartRunner& run) {
  const auto enc = encoding_of(path, ".mesh", ".meshb");
  check_finite(data, path);
  AtomicFile out(path);
  mesh_output(data, enc, version, &out, run);
  out.commit();
}

void write_sol(const std::string& path, const SolData& data, int version, const PartRunner& run) {
  const auto enc = encoding_of(path, ".sol", ".solb");
  check_finite(data, path);
  AtomicFile out(path);
  sol_output(data, enc, version, &out, run);
  out.commit();
}

}  // namespace metrica::io
