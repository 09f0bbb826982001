#include <metrica/error.hpp>
#include <metrica/io/byte_reader.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/msh.hpp>
#include <metrica/log.hpp>

#include <fmt/format.h>

#include <charconv>
#include <cstring>
#include <map>
#include <unordered_map>

namespace metrica::io {
namespace {

// Nodes per element type in gmsh's numbering (0: a type this reader does
// not know, which a binary 2.2 file cannot be read past).
int nodes_of_type(int type) {
  static constexpr int kNodes[] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                                   8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
  return type >= 0 && type < static_cast<int>(std::size(kNodes)) ? kNodes[type] : 0;
}

const char* type_name(int type) {
  switch (type) {
    case 3:
    case 10:
    case 16: return "quadrangles";
    case 5:
    case 12:
    case 17: return "hexahedra";
    case 6:
    case 13:
    case 18: return "prisms";
    case 7:
    case 14:
    case 19: return "pyramids";
    default: return "elements of other types";
  }
}

// What an element becomes: its corner nodes come first in gmsh's order.
enum class Kind { tet, triangle, line, point, dropped };
Kind kind_of(int type) {
  switch (type) {
    case 4:
    case 11:
    case 29:
    case 30:
    case 31: return Kind::tet;
    case 2:
    case 9:
    case 20:
    case 21:
    case 22:
    case 23:
    case 24:
    case 25: return Kind::triangle;
    case 1:
    case 8:
    case 26:
    case 27:
    case 28: return Kind::line;
    case 15: return Kind::point;
    default: return Kind::dropped;
  }
}

// A cursor over the file: section lines in ASCII, the data in ASCII tokens
// or binary values (data-size bytes for size_t, the file's byte order).
class Cursor {
 public:
  Cursor(std::string_view bytes, const std::string& name) : s_(bytes), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const {
    if (section_.empty()) throw IoError(fmt::format("{}: {}", name_, what));
    throw IoError(fmt::format("{}: {} (section ${}, at byte offset {})", name_, what, section_, pos_));
  }
  void set_section(std::string_view s) { section_ = s; }
  void set_binary(bool binary, bool swap, int size_width) {
    binary_ = binary;
    swap_ = swap;
    size_width_ = size_width;
  }
  bool binary() const { return binary_; }

  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool at_end() {
    skip_space();
    return pos_ >= s_.size();
  }
  // The rest of the current line (without its end), the cursor after it.
  std::string_view line() {
    const std::size_t end = s_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? s_.size() : end;
    std::string_view l = s_.substr(pos_, stop - pos_);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    pos_ = end == std::string_view::npos ? s_.size() : end + 1;
    return l;
  }
  // The next non-blank line.
  std::string_view next_line() {
    skip_space();
    if (pos_ >= s_.size()) fail("unexpected end of file");
    return line();
  }
  std::string_view token() {
    skip_space();
    const std::size_t start = pos_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    if (start == pos_) fail("unexpected end of file");
    return s_.substr(start, pos_ - start);
  }
  template <class T>
  T parse(std::string_view what) {
    const std::string_view tok = token();
    T value{};
    const char* first = tok.data();
    if constexpr (std::is_floating_point_v<T>)
      if (*first == '+') ++first;
    const auto [end, ec] = std::from_chars(first, tok.data() + tok.size(), value);
    if (ec != std::errc() || end != tok.data() + tok.size())
      fail(fmt::format("expected {} for {}, found '{}'", std::is_floating_point_v<T> ? "a number" : "an integer", what,
                       tok));
    return value;
  }
  template <class T>
  T raw() {
    if (s_.size() - pos_ < sizeof(T)) fail("the file is truncated");
    T value;
    std::memcpy(&value, s_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return swap_ ? byteswap(value) : value;
  }

  // Values of the data, ASCII or binary.
  std::int64_t integer(std::string_view what) { return binary_ ? raw<std::int32_t>() : parse<std::int64_t>(what); }
  std::uint64_t size(std::string_view what) {
    if (!binary_) return parse<std::uint64_t>(what);
    return size_width_ == 4 ? raw<std::uint32_t>() : raw<std::uint64_t>();
  }
  double real(std::string_view what) { return binary_ ? raw<double>() : parse<double>(what); }

  // Past `$End<section>` (whatever data is left before it).
  void end_section(std::string_view section) {
    const std::string marker = fmt::format("$End{}", section);
    const std::size_t at = s_.find(marker, pos_);
    if (at == std::string_view::npos) fail(fmt::format("no {}", marker));
    pos_ = at;
    line();
  }
  // A count read from the file must fit in what is left of it.
  void check_count(std::uint64_t n, std::size_t bytes_each, std::string_view what) const {
    if (n > (s_.size() - pos_) / std::max<std::size_t>(bytes_each, 1))
      fail(fmt::format("{} {} cannot fit in the rest of the file", n, what));
  }

 private:
  std::string_view s_;
  const std::string& name_;
  std::size_t pos_ = 0;
  std::string section_;
  bool binary_ = false, swap_ = false;
  int size_width_ = 8;
};

// Node tags to indices into MeshData::vertices.
class NodeIndex {
 public:
  void reserve(std::uint64_t count, std::uint64_t max_tag) {
    dense_ = max_tag <= 8 * count + 1024;
    if (dense_) by_tag_.assign(max_tag + 1, kNoId);
  }
  void add(std::uint64_t tag, VertexId index, Cursor& in) {
    if (dense_ && tag >= by_tag_.size()) in.fail(fmt::format("node tag {} is beyond the largest tag announced", tag));
    const bool fresh = dense_ ? by_tag_[tag] == kNoId : sparse_.emplace(tag, index).second;
    if (!fresh) in.fail(fmt::format("node tag {} appears twice", tag));
    if (dense_) by_tag_[tag] = index;
  }
  VertexId at(std::uint64_t tag, Cursor& in) const {
    VertexId v = kNoId;
    if (dense_) {
      if (tag < by_tag_.size()) v = by_tag_[tag];
    } else if (auto it = sparse_.find(tag); it != sparse_.end()) {
      v = it->second;
    }
    if (v == kNoId) in.fail(fmt::format("an element refers to node {}, which $Nodes does not list", tag));
    return v;
  }

 private:
  bool dense_ = true;
  std::vector<VertexId> by_tag_;
  std::unordered_map<std::uint64_t, VertexId> sparse_;
};

struct Reading {
  MeshData m;
  NodeIndex nodes;
  bool nodes_seen = false;
  // Version 4.1: the physical tags of each (dim, entity tag).
  std::map<std::pair<int, int>, std::vector<int>> physical;
  std::map<int, std::size_t> dropped;  // by element type
  // Tets in a physical volume and not: a region each, or none at all.
  std::size_t tets_in_physical = 0, tets_outside_physical = 0;
  // One element: `nodes` tags, in the file's order; `in_group`: its ref is
  // a physical group's (else its entity's).
  void add_element(int type, int ref, bool in_group, const std::vector<std::uint64_t>& tags, Cursor& in) {
    const Kind kind = kind_of(type);
    switch (kind) {
      case Kind::tet:
        m.tets.push_back({nodes.at(tags[0], in), nodes.at(tags[1], in), nodes.at(tags[2], in), nodes.at(tags[3], in)});
        m.tet_refs.push_back(ref);
        ++(in_group ? tets_in_physical : tets_outside_physical);
        break;
      case Kind::triangle:
        m.triangles.push_back({nodes.at(tags[0], in), nodes.at(tags[1], in), nodes.at(tags[2], in)});
        m.triangle_refs.push_back(ref);
        break;
      case Kind::line:
        m.edges.push_back({nodes.at(tags[0], in), nodes.at(tags[1], in)});
        m.edge_refs.push_back(ref);
        break;
      case Kind::point: m.corners.push_back(nodes.at(tags[0], in)); break;
      case Kind::dropped: ++dropped[type]; break;
    }
  }
  int entity_ref(int dim, int tag) const {
    const auto it = physical.find({dim, tag});
    return it == physical.end() || it->second.empty() ? tag : it->second.front();
  }
  bool has_physical(int dim, int tag) const {
    const auto it = physical.find({dim, tag});
    return it != physical.end() && !it->second.empty();
  }
};

void read_entities(Cursor& in, Reading& r) {
  std::uint64_t counts[4];
  for (auto& c : counts) c = in.size("the number of entities");
  for (int dim = 0; dim < 4; ++dim) {
    in.check_count(counts[dim], in.binary() ? 4 : 2, "entities");
    for (std::uint64_t i = 0; i < counts[dim]; ++i) {
      const int tag = static_cast<int>(in.integer("an entity tag"));
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) in.real("an entity's bounding box");
      const std::uint64_t nphys = in.size("the number of physical tags");
      in.check_count(nphys, 4, "physical tags");
      auto& tags = r.physical[{dim, tag}];
      for (std::uint64_t k = 0; k < nphys; ++k) tags.push_back(static_cast<int>(in.integer("a physical tag")));
      if (dim == 0) continue;
      const std::uint64_t nbound = in.size("the number of bounding entities");
      in.check_count(nbound, 4, "bounding entities");
      for (std::uint64_t k = 0; k < nbound; ++k) in.integer("a bounding entity");
    }
  }
}

void read_nodes_41(Cursor& in, Reading& r) {
  const std::uint64_t blocks = in.size("the number of node blocks");
  const std::uint64_t count = in.size("the number of nodes");
  in.size("the smallest node tag");
  const std::uint64_t max_tag = in.size("the largest node tag");
  in.check_count(count, in.binary() ? 24 : 6, "nodes");
  r.nodes.reserve(count, max_tag);
  r.m.vertices.reserve(count);
  std::vector<std::uint64_t> tags;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const int dim = static_cast<int>(in.integer("a block's entity dimension"));
    in.integer("a block's entity tag");
    const bool parametric = in.integer("whether the block is parametric") != 0;
    const std::uint64_t n = in.size("the number of nodes of a block");
    in.check_count(n, in.binary() ? 8 : 2, "nodes");
    tags.resize(n);
    for (auto& t : tags) t = in.size("a node tag");
    for (std::uint64_t k = 0; k < n; ++k) {
      const double x = in.real("a coordinate"), y = in.real("a coordinate"), z = in.real("a coordinate");
      if (parametric)
        for (int p = 0; p < dim; ++p) in.real("a parametric coordinate");
      r.nodes.add(tags[k], static_cast<VertexId>(r.m.vertices.size()), in);
      r.m.vertices.emplace_back(x, y, z);
    }
  }
}

void read_elements_41(Cursor& in, Reading& r) {
  const std::uint64_t blocks = in.size("the number of element blocks");
  in.size("the number of elements");
  in.size("the smallest element tag");
  in.size("the largest element tag");
  std::vector<std::uint64_t> tags;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const int dim = static_cast<int>(in.integer("a block's entity dimension"));
    const int entity = static_cast<int>(in.integer("a block's entity tag"));
    const int type = static_cast<int>(in.integer("a block's element type"));
    const std::uint64_t n = in.size("the number of elements of a block");
    const int per = nodes_of_type(type);
    if (per == 0) in.fail(fmt::format("element type {} is not a type of gmsh's this reader knows", type));
    in.check_count(n, in.binary() ? 8 * (1 + static_cast<std::size_t>(per)) : 2, "elements");
    const int ref = r.entity_ref(dim, entity);
    const bool in_group = r.has_physical(dim, entity);
    tags.resize(static_cast<std::size_t>(per));
    for (std::uint64_t k = 0; k < n; ++k) {
      in.size("an element tag");
      for (auto& t : tags) t = in.size("a node tag");
      r.add_element(type, ref, in_group, tags, in);
    }
  }
}

void read_nodes_22(Cursor& in, Reading& r) {
  const auto count = in.parse<std::uint64_t>("the number of nodes");
  in.line();  // the count's line: a binary file's data starts after it
  in.check_count(count, in.binary() ? 28 : 8, "nodes");
  r.m.vertices.reserve(count);
  // Tags are not announced: read them first, then index.
  std::vector<std::uint64_t> tags(count);
  std::uint64_t max_tag = 0;
  for (std::uint64_t k = 0; k < count; ++k) {
    tags[k] = in.binary() ? static_cast<std::uint64_t>(in.raw<std::int32_t>()) : in.parse<std::uint64_t>("a node tag");
    const double x = in.real("a coordinate"), y = in.real("a coordinate"), z = in.real("a coordinate");
    r.m.vertices.emplace_back(x, y, z);
    max_tag = std::max(max_tag, tags[k]);
  }
  r.nodes.reserve(count, max_tag);
  for (std::uint64_t k = 0; k < count; ++k) r.nodes.add(tags[k], static_cast<VertexId>(k), in);
}

void read_elements_22(Cursor& in, Reading& r) {
  const auto count = in.parse<std::uint64_t>("the number of elements");
  in.line();
  in.check_count(count, in.binary() ? 16 : 8, "elements");
  std::vector<std::uint64_t> nodes;
  std::vector<int> tags;
  auto one = [&](int type, int ntags) {
    const int per = nodes_of_type(type);
    if (per == 0) in.fail(fmt::format("element type {} is not a type of gmsh's this reader knows", type));
    tags.resize(static_cast<std::size_t>(std::max(ntags, 0)));
    for (auto& t : tags) t = static_cast<int>(in.integer("an element tag"));
    nodes.resize(static_cast<std::size_t>(per));
    for (auto& n : nodes) n = static_cast<std::uint64_t>(in.integer("a node tag"));
    const int ref = tags.empty() ? 0 : tags[0] != 0 ? tags[0] : tags.size() > 1 ? tags[1] : 0;
    r.add_element(type, ref, !tags.empty() && tags[0] != 0, nodes, in);
  };
  if (!in.binary()) {
    for (std::uint64_t k = 0; k < count; ++k) {
      in.integer("an element number");
      const int type = static_cast<int>(in.integer("an element type"));
      const int ntags = static_cast<int>(in.integer("the number of tags"));
      if (ntags < 0 || ntags > 64) in.fail(fmt::format("an element with {} tags", ntags));
      one(type, ntags);
    }
    return;
  }
  // Binary: blocks of one type, each a header (type, count, tags) and
  // its elements (number, tags, nodes).
  for (std::uint64_t done = 0; done < count;) {
    const int type = in.raw<std::int32_t>();
    const std::int32_t n = in.raw<std::int32_t>();
    const int ntags = in.raw<std::int32_t>();
    if (n <= 0 || static_cast<std::uint64_t>(n) > count - done || ntags < 0 || ntags > 64)
      in.fail(fmt::format("a block of {} elements with {} tags", n, ntags));
    for (std::int32_t k = 0; k < n; ++k) {
      in.raw<std::int32_t>();
      one(type, ntags);
    }
    done += static_cast<std::uint64_t>(n);
  }
}

}  // namespace

MeshData parse_msh(std::string_view bytes, const std::string& name) {
  Cursor in(bytes, name);
  Reading r;
  int major = 0;
  bool elements_seen = false;
  while (!in.at_end()) {
    const std::string_view head = in.next_line();
    if (head.empty() || head[0] != '$')
      in.fail(fmt::format("expected a section ($Name), found '{}'", head.substr(0, 40)));
    const std::string section(head.substr(1));
    in.set_section(section);
    if (section == "MeshFormat") {
      const std::string_view version = in.token();
      const auto file_type = in.parse<int>("the file type");
      const auto data_size = in.parse<int>("the data size");
      if (version == "2.2" || version == "2.1" || version == "2")
        major = 2;
      else if (version == "4.1")
        major = 4;
      else
        in.fail(fmt::format("version {} is not read (save the mesh as version 4.1 or 2.2)", version));
      if (data_size != 8 && data_size != 4) in.fail(fmt::format("data size {} (8 or 4 expected)", data_size));
      in.line();
      if (file_type == 1) {
        const auto one = in.raw<std::int32_t>();
        if (one != 1 && byteswap(one) != 1) in.fail("the binary file's byte-order mark is not 1");
        in.set_binary(true, one != 1, data_size);
      }
      in.end_section(section);
    } else if (major == 0) {
      in.fail("the file does not start with $MeshFormat");
    } else if (section == "Entities" && major == 4) {
      read_entities(in, r);
      in.end_section(section);
    } else if (section == "Nodes") {
      if (r.nodes_seen) in.fail("a second $Nodes section (partitioned files are not read)");
      major == 4 ? read_nodes_41(in, r) : read_nodes_22(in, r);
      r.nodes_seen = true;
      in.end_section(section);
    } else if (section == "Elements") {
      if (!r.nodes_seen) in.fail("$Elements before $Nodes");
      major == 4 ? read_elements_41(in, r) : read_elements_22(in, r);
      elements_seen = true;
      in.end_section(section);
    } else {
      in.end_section(section);  // $PhysicalNames, $NodeData, ...: not needed
    }
    in.set_section({});
  }
  if (!r.nodes_seen) throw IoError(fmt::format("{}: no $Nodes section", name));
  if (!elements_seen) throw IoError(fmt::format("{}: no $Elements section", name));
  if (!r.dropped.empty()) {
    std::map<std::string, std::size_t> by_name;
    for (const auto& [type, n] : r.dropped) by_name[type_name(type)] += n;
    std::string list;
    for (const auto& [what, n] : by_name) list += fmt::format("{}{} {}", list.empty() ? "" : ", ", n, what);
    log::warn("{}: dropped {} (Metrica keeps tetrahedra, triangles, lines and points)", name, list);
  }
  if (r.tets_in_physical > 0 && r.tets_outside_physical > 0)
    throw IoError(
        fmt::format("{}: {} tetrahedra belong to no physical volume while {} do: a tet without a region "
                    "beside regions (give every volume a physical group, or none)",
                    name, r.tets_outside_physical, r.tets_in_physical));
  r.m.vertex_refs.assign(r.m.vertices.size(), 0);
  return std::move(r.m);
}

MeshData read_msh(const std::string& path) { return parse_msh(read_file_bytes(path), path); }

}  // namespace metrica::io
