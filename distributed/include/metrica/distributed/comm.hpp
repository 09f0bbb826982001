// The few message patterns the distributed executor needs, over one MPI
// communicator: an all-to-all of typed records (sizes first, then data),
// sums, an exclusive scan, and the agreement on failure that keeps an
// error on one rank from leaving the others waiting in a receive.
#pragma once

#include <metrica/error.hpp>

#include <cstddef>
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
    std::vector<std::int64_t> send(size_), recv(size_);
    for (int r = 0; r < size_; ++r) send[r] = std::int64_t(out[r].size());
    MPI_Alltoall(send.data(), 1, MPI_INT64_T, recv.data(), 1, MPI_INT64_T, comm_);
    std::int64_t total = 0;
    for (auto n : recv) total += n;
    std::vector<T> in(static_cast<std::size_t>(total));
    std::vector<const void*> send_at(size_);
    std::vector<void*> recv_at(size_);
    std::int64_t at = 0;
    for (int r = 0; r < size_; ++r) {
      send_at[r] = out[r].data();
      recv_at[r] = in.data() + at;
      at += recv[r];
    }
    exchange_records(sizeof(T), send_at, send, recv_at, recv);
    if (from) *from = recv;
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

  // The ranks' file I/O in collective calls (MPI_File_*_at_all): for each
  // index any rank has a slice at, how many calls of at most kIoPart bytes
  // (an int of bytes) the largest slice there takes; every rank makes
  // that many calls for the index, with no bytes past its own slice.
  static constexpr std::size_t kIoPart = std::size_t{1} << 30;
  std::vector<std::int64_t> io_parts(const std::vector<std::size_t>& slice_bytes) const;

  // Runs step on every rank, then agrees: when it threw on any rank, that
  // rank prints its message to stderr ("rank r: ...") and every rank
  // throws (ReportedFailure, which the command turns into exit 1), so no
  // rank goes on to a message another will never send.
  void step(const std::function<void()>& body) const;

 private:
  // One all-to-all of records of `bytes` bytes: send[r] records at
  // send_at[r] to rank r, recv[r] from rank r into recv_at[r].
  void exchange_records(std::size_t bytes, const std::vector<const void*>& send_at,
                        const std::vector<std::int64_t>& send, const std::vector<void*>& recv_at,
                        const std::vector<std::int64_t>& recv) const;

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
};

}  // namespace metrica::distributed
