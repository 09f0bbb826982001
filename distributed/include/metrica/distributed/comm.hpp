// The few message patterns the distributed executor needs, over one MPI
// communicator: an all-to-all of typed records (sizes first, then data),
// sums, an exclusive scan, and the agreement on failure that keeps an
// error on one rank from leaving the others waiting in a receive.
#pragma once

#include <metrica/error.hpp>

#include <cstdint>
#include <exception>
#include <functional>
#include <mpi.h>
#include <string>
#include <type_traits>
#include <vector>

namespace metrica::distributed {

// A rank's failure, already reported on that rank's stderr: the command
// exits 1 without printing it again.
using ReportedFailure = AlreadyReported;

class Comm {
 public:
  explicit Comm(MPI_Comm comm = MPI_COMM_WORLD);

  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm get() const { return comm_; }

  // Sends out[r] to rank r, for every r; returns what each rank sent here,
  // in rank order (from[r] is the count that came from rank r when given).
  template <class T>
  std::vector<T> exchange(const std::vector<std::vector<T>>& out, std::vector<std::int64_t>* from = nullptr) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::int64_t> send_bytes(size_), recv_bytes(size_);
    for (int r = 0; r < size_; ++r) send_bytes[r] = std::int64_t(out[r].size() * sizeof(T));
    MPI_Alltoall(send_bytes.data(), 1, MPI_INT64_T, recv_bytes.data(), 1, MPI_INT64_T, comm_);
    std::vector<T> in;
    std::int64_t total = 0;
    for (auto b : recv_bytes) total += b;
    in.resize(std::size_t(total) / sizeof(T));
    exchange_bytes(out, send_bytes, recv_bytes, reinterpret_cast<char*>(in.data()));
    if (from) {
      from->resize(size_);
      for (int r = 0; r < size_; ++r) (*from)[r] = recv_bytes[r] / std::int64_t(sizeof(T));
    }
    return in;
  }

  std::int64_t sum(std::int64_t v) const;
  double sum(double v) const;
  std::int64_t max(std::int64_t v) const;
  double min(double v) const;
  double max(double v) const;
  // The sum of v over the ranks below this one (0 on rank 0).
  std::int64_t exclusive_scan(std::int64_t v) const;
  void barrier() const { MPI_Barrier(comm_); }

  // Runs step on every rank, then agrees: when it threw on any rank, that
  // rank prints its message to stderr ("rank r: ...") and every rank
  // throws (ReportedFailure, which the command turns into exit 1), so no
  // rank goes on to a message another will never send.
  void step(const std::function<void()>& body) const;

 private:
  template <class T>
  void exchange_bytes(const std::vector<std::vector<T>>& out, const std::vector<std::int64_t>& send_bytes,
                      const std::vector<std::int64_t>& recv_bytes, char* in) const {
    std::vector<const char*> parts(size_);
    for (int r = 0; r < size_; ++r) parts[r] = reinterpret_cast<const char*>(out[r].data());
    exchange_raw(parts, send_bytes, recv_bytes, in);
  }
  void exchange_raw(const std::vector<const char*>& parts, const std::vector<std::int64_t>& send_bytes,
                    const std::vector<std::int64_t>& recv_bytes, char* in) const;

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
};

}  // namespace metrica::distributed
