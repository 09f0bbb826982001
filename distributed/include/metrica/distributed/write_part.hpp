// Writing a distributed mesh into one .meshb or .mesh (and its metric as
// one .solb or .sol, its tets and triangles as one .vtu): vertices numbered
// globally (a vertex held by several parts is written by the lowest rank
// holding it), each rank's rows placed at offsets from exclusive scans,
// written with MPI-IO into temporary files that rank 0 renames together
// once every rank has written its share of each. No rank gathers the mesh.
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/part.hpp>
#include <metrica/geometry/cad_model.hpp>

#include <functional>
#include <string>
#include <vector>

namespace metrica::distributed {

struct WrittenCounts {
  std::int64_t vertices = 0, triangles = 0, tets = 0;
  int version = 2;
};

// The file's numbering of the part's vertices: each is written by the
// lowest rank holding it; `number` is 1-based, `first` the count written
// by the ranks before this one. Collective.
struct VertexNumbering {
  std::vector<int> owner;            // per local vertex: the rank that writes it
  std::vector<std::int64_t> number;  // per local vertex: its number in the file
  std::int64_t owned = 0, first = 0, total = 0;
};
VertexNumbering number_vertices(const Comm& comm, const Part& part);

// An output written by every rank: a temporary beside `path` until
// StagedOutputs::commit renames it (with the run's other outputs);
// removed when not committed.
struct StagedFile {
  std::string temporary, path;
};
class SharedFile {
 public:
  SharedFile(const Comm& comm, const std::string& path);  // collective; IoError on every rank if not created
  ~SharedFile();
  SharedFile(const SharedFile&) = delete;
  SharedFile& operator=(const SharedFile&) = delete;
  MPI_File file() const { return file_; }
  StagedFile close();  // collective

 private:
  const Comm& comm_;
  MPI_File file_{};
  StagedFile staged_;
  bool open_ = false, closed_ = false;
};
// A run's outputs as one transaction (io::OutputSet's rule for files all
// ranks write): commit() has rank 0 rename every staged file onto its
// target (collective: an error fails every rank); what is not renamed,
// after an error or without a commit, is removed.
class StagedOutputs {
 public:
  explicit StagedOutputs(const Comm& comm) : comm_(comm) {}
  ~StagedOutputs();
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;
  void add(StagedFile file) { files_.push_back(std::move(file)); }
  void commit();

 private:
  const Comm& comm_;
  std::vector<StagedFile> files_;
  std::size_t renamed_ = 0;
};

// The mesh as one .meshb. `version` 0 chooses: 2, or 3 past 2 GB, or 4
// past 2^31 - 1 rows. With a model, the vertices' CAD association too
// (VerticesOnGeometric*, as the single process writes them).
StagedFile write_part(const Comm& comm, const Part& part, const VertexNumbering& numbering, const std::string& path,
                      int version, const CadModel* model, WrittenCounts* counts);

// The same as one ASCII .mesh (the single process's text; `version` 0
// writes 2): each rank formats its rows of each keyword and writes them
// after those of the ranks before it (an exclusive scan of their byte
// counts), rank 0 the keyword lines between them. A rank holds the text
// of one keyword of its part at a time.
StagedFile write_part_text(const Comm& comm, const Part& part, const VertexNumbering& numbering,
                           const std::string& path, int version, const CadModel* model, WrittenCounts* counts);

// The mesh for ParaView as one .vtu (the single process's arrays: points,
// tets then surface triangles, their ids as the cell field "ref"), its
// data appended raw after the XML so that each rank's rows go at offsets
// from scans.
StagedFile write_part_vtu(const Comm& comm, const Part& part, const VertexNumbering& numbering,
                          const std::string& path);

// The metric at the output's vertices as one .solb (SolAtVertices, one
// symmetric tensor per vertex, in write_part's order): metric_of(v) for
// the local vertices this rank writes. `version` as the mesh's (2 to 4).
StagedFile write_part_metric(const Comm& comm, const VertexNumbering& numbering,
                             const std::function<Sym6(std::size_t)>& metric_of, const std::string& path, int version);
// The same as one ASCII .sol.
StagedFile write_part_metric_text(const Comm& comm, const VertexNumbering& numbering,
                                  const std::function<Sym6(std::size_t)>& metric_of, const std::string& path,
                                  int version);

}  // namespace metrica::distributed
