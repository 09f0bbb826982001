// libMeshb reader: .mesh / .meshb and .sol / .solb, versions 1-4.
//
// Both encodings share the per-keyword record parsing (a Source gives
// integers and reals); they differ only in how keywords are found: binary
// files chain keywords by absolute offsets, ASCII files name them.
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/byte_reader.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/meshb_keywords.hpp>
#include <metrica/log.hpp>

#include <fmt/core.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sys/stat.h>

namespace metrica::io {
namespace {

using namespace meshb;

void log_missing_end(const std::string& file) { log::warn("{}: no End keyword; the file may be truncated", file); }

// Values of one record kind, to bound counts against the file size.
struct BinarySource {
  ByteReader& in;
  Widths w;

  std::int64_t integer() { return in.integer(w.integer); }
  double real() { return in.real(w.real); }
  std::string location() const { return fmt::format("byte offset {}", in.pos()); }
  [[noreturn]] void fail(const std::string& what) const { in.fail(what); }
  // Reads a count and checks that `ints` integers and `reals` reals per
  // entry fit in what is left of the file.
  std::size_t count(int ints, int reals) {
    const std::size_t at = in.pos();
    const std::int64_t n = in.integer(w.integer);
    const std::uint64_t entry = std::uint64_t(ints) * w.integer + std::uint64_t(reals) * w.real;
    if (n < 0) in.fail_at(fmt::format("negative count {}", n), at);
    if (entry > 0 && std::uint64_t(n) > in.left() / entry)
      in.fail_at(fmt::format("count {} exceeds the file ({} bytes needed, {} left): the file is truncated or corrupt",
                             n, std::uint64_t(n) * entry, in.left()),
                 at);
    return static_cast<std::size_t>(n);
  }
  std::size_t check_fits(std::size_t n, int reals) {
    const std::uint64_t entry = std::uint64_t(reals) * w.real;
    if (entry > 0 && n > in.left() / entry)
      in.fail(fmt::format("{} entries of {} values exceed the file ({} bytes left)", n, reals, in.left()));
    return n;
  }
  int small_int() { return in.raw<std::int32_t>(); }
};

struct TextSource {
  TextReader& in;
  int version;

  std::int64_t integer() { return in.integer("an integer"); }
  double real() {
    const double x = in.real("a real number");
    // Version 1 files hold 32-bit reals: keep what a binary v1 would hold.
    return version == 1 ? static_cast<double>(static_cast<float>(x)) : x;
  }
  std::string location() const { return fmt::format("line {}", in.line()); }
  [[noreturn]] void fail(const std::string& what) const { in.fail(what); }
  // Every value takes at least two characters ("0 "), which bounds a count
  // before anything is allocated for it.
  std::size_t count(int ints, int reals) {
    const std::int64_t n = in.integer("a count");
    if (n < 0) in.fail(fmt::format("negative count {}", n));
    return check_fits(static_cast<std::size_t>(n), ints + reals);
  }
  std::size_t check_fits(std::size_t n, int values) {
    if (values > 0 && n > in.left() / (2 * std::size_t(values)))
      in.fail(fmt::format("count {} exceeds what the file holds", n));
    return n;
  }
  int small_int() {
    const auto v = in.integer("an integer");
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      in.fail(fmt::format("value {} out of range", v));
    return static_cast<int>(v);
  }
};

template <class Source>
int read_ref(Source& src) {
  const std::int64_t r = src.integer();
  if (r < std::numeric_limits<int>::min() || r > std::numeric_limits<int>::max())
    src.fail(fmt::format("reference {} does not fit in 32 bits", r));
  return static_cast<int>(r);
}

// 1-based index as read; range-checked once all keywords are known.
template <class Source>
std::uint32_t read_index(Source& src) {
  const std::int64_t i = src.integer();
  if (i < 1 || i > std::int64_t(std::numeric_limits<std::uint32_t>::max()))
    src.fail(fmt::format("index {} out of range (indices start at 1 and must fit in 32 bits)", i));
  return static_cast<std::uint32_t>(i - 1);
}

// Elements of N vertices, each followed by its reference.
template <class Source, std::size_t N>
void read_elements(Source& src, std::vector<std::array<VertexId, N>>& elements, std::vector<int>& refs) {
  const auto n = src.count(int(N) + 1, 0);
  elements.resize(n);
  refs.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (auto& v : elements[i]) v = read_index(src);
    refs[i] = read_ref(src);
  }
}

// Where each keyword was found, for messages about its content.
using Locations = std::map<int, std::string>;

// Returns false for a keyword whose content is skipped (not parsed).
template <class Source>
bool read_mesh_keyword(Source& src, int code, MeshData& m, Locations& where) {
  where[code] = src.location();
  switch (code) {
    case kVertices: {
      const auto n = src.count(1, 3);
      m.vertices.resize(n);
      m.vertex_refs.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const double x = src.real(), y = src.real(), z = src.real();
        m.vertices[i] = Point(x, y, z);
        m.vertex_refs[i] = read_ref(src);
      }
      break;
    }
    case kEdges: read_elements(src, m.edges, m.edge_refs); break;
    case kTriangles: read_elements(src, m.triangles, m.triangle_refs); break;
    case kTetrahedra: read_elements(src, m.tets, m.tet_refs); break;
    case kCorners:
    case kRequiredVertices:
    case kRidges:
    case kRequiredEdges:
    case kRequiredTriangles: {
      auto& list = code == kCorners             ? m.corners
                   : code == kRidges            ? m.ridges
                   : code == kRequiredEdges     ? m.required_edges
                   : code == kRequiredTriangles ? m.required_triangles
                                                : m.required_vertices;
      const auto n = src.count(1, 0);
      list.resize(n);
      for (auto& v : list) v = read_index(src);
      break;
    }
    case kVerticesOnGeometricVertices:
    case kVerticesOnGeometricEdges:
    case kVerticesOnGeometricTriangles: {
      // (vertex, entity) then t, dist on a curve; u, v, dist on a surface.
      const int dim = code - kVerticesOnGeometricVertices;
      const int reals = dim == 0 ? 0 : dim + 1;
      const auto n = src.count(2, reals);
      auto& list = m.on_geometry[static_cast<std::size_t>(dim)];
      list.resize(n);
      for (auto& r : list) {
        r.vertex = read_index(src);
        r.entity = read_ref(src);
        if (dim >= 1) r.u = src.real();
        if (dim == 2) r.v = src.real();
        if (dim >= 1) r.dist = src.real();
      }
      break;
    }
    default: return false;
  }
  return true;
}

template <class Source>
void read_sol_keyword(Source& src, SolData& s) {
  const auto n = src.count(0, 0);
  const int ntypes = src.small_int();
  if (ntypes < 1 || ntypes > 64) src.fail(fmt::format("invalid number of solution fields {}", ntypes));
  s.types.clear();
  for (int k = 0; k < ntypes; ++k) {
    const int t = src.small_int();
    if (t < 1 || t > 4)
      src.fail(fmt::format("unknown solution type {} (expected 1 scalar, 2 vector, 3 symmetric matrix, 4 matrix)", t));
    s.types.push_back(static_cast<SolType>(t));
  }
  s.count = src.check_fits(n, s.stride());
  s.values.resize(s.count * std::size_t(s.stride()));
  for (auto& x : s.values) x = src.real();
}

[[noreturn]] void fail_index(const std::string& file, int code, const Locations& where, std::size_t entry,
                             std::uint32_t index, std::size_t bound, std::string_view what) {
  throw IoError(fmt::format("{}: keyword {} ({}), entry {}: {} index {} out of range 1..{}", file, keyword_name(code),
                            where.at(code), entry + 1, what, std::uint64_t(index) + 1, bound));
}

void check_indices(const MeshData& m, const std::string& file, const Locations& where) {
  const std::size_t nv = m.vertices.size();
  auto check = [&](int code, const auto& list) {
    for (std::size_t i = 0; i < list.size(); ++i) {
      if constexpr (std::is_integral_v<std::decay_t<decltype(list[i])>>) {
        if (list[i] >= nv) fail_index(file, code, where, i, list[i], nv, "vertex");
      } else {
        for (auto v : list[i])
          if (v >= nv) fail_index(file, code, where, i, v, nv, "vertex");
      }
    }
  };
  check(kEdges, m.edges);
  check(kTriangles, m.triangles);
  check(kTetrahedra, m.tets);
  check(kCorners, m.corners);
  check(kRequiredVertices, m.required_vertices);
  for (int dim = 0; dim < 3; ++dim) {
    const auto& list = m.on_geometry[static_cast<std::size_t>(dim)];
    for (std::size_t i = 0; i < list.size(); ++i)
      if (list[i].vertex >= nv)
        fail_index(file, kVerticesOnGeometricVertices + dim, where, i, list[i].vertex, nv, "vertex");
  }
  for (std::size_t i = 0; i < m.ridges.size(); ++i)
    if (m.ridges[i] >= m.edges.size()) fail_index(file, kRidges, where, i, m.ridges[i], m.edges.size(), "edge");
  for (std::size_t i = 0; i < m.required_edges.size(); ++i)
    if (m.required_edges[i] >= m.edges.size())
      fail_index(file, kRequiredEdges, where, i, m.required_edges[i], m.edges.size(), "edge");
  for (std::size_t i = 0; i < m.required_triangles.size(); ++i)
    if (m.required_triangles[i] >= m.triangles.size())
      fail_index(file, kRequiredTriangles, where, i, m.required_triangles[i], m.triangles.size(), "triangle");
}

void check_dimension(std::int64_t dim, const std::string& file) {
  if (dim != 3)
    throw IoError(fmt::format("{}: unsupported dimension {} (Metrica adapts 3D tetrahedral meshes)", file, dim));
}

// Walks the keywords of a binary file, calling visit(code) positioned at
// each keyword's content; returns the version.
template <class Visit>
int walk_binary(ByteReader& in, const std::string& file, Visit&& visit) {
  if (in.size() < 8) in.fail("file too short for a libMeshb binary header");
  const auto magic = in.raw<std::int32_t>();
  if (magic == kMagicSwapped)
    in.set_swap(true);
  else if (magic != kMagic)
    in.fail_at(fmt::format("bad magic number {} (not a libMeshb binary file)", magic), 0);
  const int version = in.raw<std::int32_t>();
  if (version < 1 || version > 4) in.fail_at(fmt::format("unsupported libMeshb version {}", version), 4);
  const Widths w(version);
  bool dimension_seen = false;
  while (true) {
    in.set_context("");
    // libMeshb always ends a binary file with End: without it the file was
    // cut at a keyword boundary.
    if (in.at_end()) in.fail("file is truncated: no End keyword");
    const std::size_t start = in.pos();
    const int code = in.raw<std::int32_t>();
    const auto name = keyword_name(code);
    in.set_context(name.empty() ? std::string_view("(unknown)") : name);
    const std::int64_t next = in.integer(w.offset);
    if (code == kEnd) break;
    if (next != 0 && (next <= std::int64_t(start) || std::uint64_t(next) > in.size()))
      in.fail_at(fmt::format("next-keyword offset {} lies outside the file (size {}): the file is truncated or corrupt",
                             next, in.size()),
                 start);
    if (code == kDimension) {
      check_dimension(in.raw<std::int32_t>(), file);
      dimension_seen = true;
    } else if (!name.empty()) {
      // A parsed keyword must end where the next one starts: a count that
      // disagrees with the data, or an offset that skips a keyword, is an
      // error, not a guess.
      if (visit(code, BinarySource{in, w}) && next != 0 && in.pos() != std::size_t(next))
        in.fail_at(fmt::format("the keyword's data ends at byte {} but the next keyword is at {}: its count "
                               "disagrees with the data, or the offset skips data",
                               in.pos(), next),
                   start);
    }
    if (next == 0) in.fail("file is truncated: no End keyword");
    in.seek(static_cast<std::size_t>(next));
  }
  if (!dimension_seen) throw IoError(fmt::format("{}: no Dimension keyword", file));
  return version;
}

template <class Visit>
int walk_text(TextReader& in, const std::string& file, Visit&& visit) {
  int version = 0;
  bool dimension_seen = false;
  while (true) {
    in.set_context("");
    const auto tok = in.token();
    // Some writers leave End out of ASCII files (the UGAWG .sol files):
    // a warning, not an error.
    if (tok.empty()) {
      log_missing_end(file);
      break;
    }
    const int code = keyword_code(tok);
    if (code == kEnd) break;
    in.set_context(tok);
    if (code == kVersion) {
      const auto v = in.integer("the version");
      if (v < 1 || v > 4) in.fail(fmt::format("unsupported libMeshb version {}", v));
      version = static_cast<int>(v);
    } else if (code == kDimension) {
      check_dimension(in.integer("the dimension"), file);
      dimension_seen = true;
    } else if (code != 0) {
      visit(code, TextSource{in, version == 0 ? 2 : version});
    } else {
      // An unknown keyword: skip its content up to the next keyword name.
      if (!std::isalpha(static_cast<unsigned char>(tok[0])))
        in.fail(fmt::format("expected a keyword, found '{}'", tok));
      while (true) {
        const auto next = in.peek();
        if (next.empty() || (std::isalpha(static_cast<unsigned char>(next[0])) && next != "nan" && next != "inf"))
          break;
        in.token();
      }
    }
  }
  if (!dimension_seen) throw IoError(fmt::format("{}: no Dimension keyword", file));
  return version == 0 ? 2 : version;
}

}  // namespace

std::string read_file_bytes(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw IoError(
        fmt::format("{}: {}", path, S_ISDIR(st.st_mode) ? "is a folder, not a file" : "is not a regular file"));
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError(fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
  std::string bytes;
  f.seekg(0, std::ios::end);
  const auto size = f.tellg();
  if (size < 0) throw IoError(fmt::format("{}: cannot read (not a regular file?)", path));
  bytes.resize(static_cast<std::size_t>(size));
  f.seekg(0);
  f.read(bytes.data(), size);
  if (!f) throw IoError(fmt::format("{}: read error", path));
  return bytes;
}

MeshData parse_mesh(std::string_view bytes, Encoding encoding, const std::string& name) {
  MeshData m;
  Locations where;
  auto visit = [&](int code, auto src) { return read_mesh_keyword(src, code, m, where); };
  if (encoding == Encoding::binary) {
    ByteReader in(bytes, name);
    m.version = walk_binary(in, name, visit);
  } else {
    TextReader in(bytes, name);
    m.version = walk_text(in, name, visit);
  }
  if (m.vertices.empty()) throw IoError(fmt::format("{}: no Vertices keyword", name));
  check_indices(m, name, where);
  return m;
}

SolData parse_sol(std::string_view bytes, Encoding encoding, const std::string& name) {
  SolData s;
  bool found = false;
  auto visit = [&](int code, auto src) {
    if (code != kSolAtVertices) return false;
    read_sol_keyword(src, s);
    found = true;
    return true;
  };
  if (encoding == Encoding::binary) {
    ByteReader in(bytes, name);
    s.version = walk_binary(in, name, visit);
  } else {
    TextReader in(bytes, name);
    s.version = walk_text(in, name, visit);
  }
  if (!found) throw IoError(fmt::format("{}: no SolAtVertices keyword", name));
  return s;
}

namespace {
bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

Encoding encoding_of(const std::string& path, std::string_view ascii_ext, std::string_view binary_ext) {
  if (is_standard_output(path)) return Encoding::ascii;
  if (ends_with(path, binary_ext)) return Encoding::binary;
  if (ends_with(path, ascii_ext)) return Encoding::ascii;
  throw IoError(fmt::format("{}: unknown extension (expected {} or {})", path, ascii_ext, binary_ext));
}

MeshData read_meshb(const std::string& path) {
  const auto enc = encoding_of(path, ".mesh", ".meshb");
  return parse_mesh(read_file_bytes(path), enc, path);
}

SolData read_sol(const std::string& path) {
  const auto enc = encoding_of(path, ".sol", ".solb");
  return parse_sol(read_file_bytes(path), enc, path);
}

}  // namespace metrica::io
