// libMeshb writer: .mesh / .meshb and .sol / .solb.
#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/meshb_keywords.hpp>
#include <metrica/log.hpp>

#include <fmt/format.h>

#include <cstring>
#include <iterator>
#include <limits>

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
  // After a whole entity: hands a full buffer to the file.
  void maybe_flush() {
    if (file_ == nullptr || out_.size() < kFlushBytes) return;
    file_->write(out_);
    flushed_ += out_.size();
    out_.clear();
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

class TextWriter {
 public:
  explicit TextWriter(int version, AtomicFile* file = nullptr) : version_(version), file_(file) {
    fmt::format_to(it(), "MeshVersionFormatted {}\n\nDimension 3\n", version);
  }
  void begin(int code) { fmt::format_to(it(), "\n{}\n", keyword_name(code)); }
  void count(std::size_t n) { fmt::format_to(it(), "{}\n", n); }
  void integer(std::int64_t v) { fmt::format_to(it(), "{} ", v); }
  void index(std::uint32_t v) { integer(std::int64_t(v) + 1); }
  void real(double x) {
    // Shortest representation that reads back to the same value.
    if (version_ == 1)
      fmt::format_to(it(), "{} ", static_cast<float>(x));
    else
      fmt::format_to(it(), "{} ", x);
  }
  void end_line() {
    if (buf_.size() > 0 && buf_[buf_.size() - 1] == ' ') buf_.resize(buf_.size() - 1);
    buf_.push_back('\n');
  }
  void maybe_flush() {
    if (file_ == nullptr || buf_.size() < kFlushBytes) return;
    file_->write(buf_.data(), buf_.size());
    buf_.clear();
  }
  std::string finish() {
    fmt::format_to(it(), "\nEnd\n");
    if (file_ == nullptr) return fmt::to_string(buf_);
    file_->write(buf_.data(), buf_.size());
    return {};
  }

 private:
  std::back_insert_iterator<fmt::memory_buffer> it() { return std::back_inserter(buf_); }
  int version_;
  AtomicFile* file_;
  fmt::memory_buffer buf_;
};

// Ends an entity: its line (text), and a flush when the buffer is full.
template <class Writer>
void end_line(Writer& w) {
  if constexpr (requires { w.end_line(); }) w.end_line();
  w.maybe_flush();
}

template <class Writer, class Entities>
void write_elements(Writer& w, int code, const Entities& entities, const std::vector<int>& refs) {
  if (entities.empty()) return;
  w.begin(code);
  w.count(entities.size());
  for (std::size_t i = 0; i < entities.size(); ++i) {
    for (auto v : entities[i]) w.index(v);
    w.integer(i < refs.size() ? refs[i] : 0);
    end_line(w);
  }
}

template <class Writer, class List>
void write_list(Writer& w, int code, const List& list) {
  if (list.empty()) return;
  w.begin(code);
  w.count(list.size());
  for (auto v : list) {
    w.index(v);
    end_line(w);
  }
}

template <class Writer>
std::string write_mesh_to(Writer w, const MeshData& m) {
  if (!m.vertices.empty()) {
    w.begin(kVertices);
    w.count(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
      const auto& p = m.vertices[i];
      w.real(p.x());
      w.real(p.y());
      w.real(p.z());
      w.integer(i < m.vertex_refs.size() ? m.vertex_refs[i] : 0);
      end_line(w);
    }
  }
  write_elements(w, kEdges, m.edges, m.edge_refs);
  write_elements(w, kTriangles, m.triangles, m.triangle_refs);
  write_elements(w, kTetrahedra, m.tets, m.tet_refs);
  for (int dim = 0; dim < 3; ++dim) {
    const auto& list = m.on_geometry[static_cast<std::size_t>(dim)];
    if (list.empty()) continue;
    w.begin(kVerticesOnGeometricVertices + dim);
    w.count(list.size());
    for (const auto& r : list) {
      w.index(r.vertex);
      w.integer(r.entity);
      if (dim >= 1) w.real(r.u);
      if (dim == 2) w.real(r.v);
      if (dim >= 1) w.real(r.dist);
      end_line(w);
    }
  }
  write_list(w, kCorners, m.corners);
  write_list(w, kRidges, m.ridges);
  write_list(w, kRequiredVertices, m.required_vertices);
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
    end_line(w);
  }
  const auto stride = static_cast<std::size_t>(s.stride());
  for (std::size_t i = 0; i < s.count; ++i) {
    for (std::size_t k = 0; k < stride; ++k) w.real(s.values[i * stride + k]);
    end_line(w);
  }
  return w.finish();
}

// Bytes a binary file would take with 32-bit offsets; past 2 GB the
// offsets overflow and version 3 is needed.
std::uint64_t binary_size_estimate(const MeshData& m, int version) {
  const Widths w(version);
  return 64 + m.vertices.size() * (3ull * w.real + w.integer) + m.edges.size() * 3ull * w.integer +
         m.triangles.size() * 4ull * w.integer + m.tets.size() * 5ull * w.integer +
         (m.corners.size() + m.ridges.size() + m.required_vertices.size()) * std::uint64_t(w.integer);
}

// `v2_size`: the binary size with version-2 widths (at least version 1's).
int choose_version(int requested, int data_version, Encoding enc, std::uint64_t v2_size) {
  int version = requested != 0 ? requested : data_version;
  if (version < 1 || version > 4) throw IoError(fmt::format("unsupported libMeshb version {} for writing", version));
  if (enc == Encoding::binary && version <= 2 && v2_size > std::uint64_t(std::numeric_limits<std::int32_t>::max())) {
    log::warn("output exceeds 2 GB: writing libMeshb version 3 (64-bit offsets) instead of {}", version);
    version = 3;
  }
  return version;
}

// The whole output as a string (file null), or streamed to the file.
std::string mesh_output(const MeshData& data, Encoding encoding, int version, AtomicFile* file) {
  version = choose_version(version, data.version, encoding, binary_size_estimate(data, 2));
  if (encoding == Encoding::binary) {
    BinaryWriter w(version, file);
    w.reserve(binary_size_estimate(data, version));
    return write_mesh_to(std::move(w), data);
  }
  return write_mesh_to(TextWriter(version, file), data);
}

std::string sol_output(const SolData& data, Encoding encoding, int version, AtomicFile* file) {
  if (data.values.size() != data.count * std::size_t(data.stride()))
    throw IoError(
        fmt::format("solution holds {} values, expected {} x {}", data.values.size(), data.count, data.stride()));
  version = choose_version(version, data.version, encoding, 64 + data.values.size() * std::uint64_t{8});
  if (encoding == Encoding::binary) return write_sol_to(BinaryWriter(version, file), data);
  return write_sol_to(TextWriter(version, file), data);
}

}  // namespace

std::string format_mesh(const MeshData& data, Encoding encoding, int version) {
  return mesh_output(data, encoding, version, nullptr);
}

std::string format_sol(const SolData& data, Encoding encoding, int version) {
  return sol_output(data, encoding, version, nullptr);
}

void write_meshb(const std::string& path, const MeshData& data, int version) {
  const auto enc = encoding_of(path, ".mesh", ".meshb");
  check_finite(data, path);
  AtomicFile out(path);
  mesh_output(data, enc, version, &out);
  out.commit();
}

void write_sol(const std::string& path, const SolData& data, int version) {
  const auto enc = encoding_of(path, ".sol", ".solb");
  check_finite(data, path);
  AtomicFile out(path);
  sol_output(data, enc, version, &out);
  out.commit();
}

}  // namespace metrica::io
