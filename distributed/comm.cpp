#include <metrica/distributed/comm.hpp>

#include <fmt/core.h>

#include <cstdio>

namespace metrica::distributed {

Comm::Comm(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

// Point-to-point messages for the non-empty parts only, in pieces below
// 2^31 bytes (MPI's counts are int): a part's neighbours are few, so most
// pairs exchange nothing.
void Comm::exchange_raw(const std::vector<const char*>& parts, const std::vector<std::int64_t>& send_bytes,
                        const std::vector<std::int64_t>& recv_bytes, char* in) const {
  constexpr std::int64_t kPiece = std::int64_t{1} << 30;
  std::vector<MPI_Request> requests;
  std::int64_t at = 0;
  for (int r = 0; r < size_; ++r) {
    for (std::int64_t off = 0; off < recv_bytes[r]; off += kPiece) {
      requests.emplace_back();
      MPI_Irecv(in + at + off, int(std::min(kPiece, recv_bytes[r] - off)), MPI_BYTE, r, 7, comm_, &requests.back());
    }
    at += recv_bytes[r];
  }
  for (int r = 0; r < size_; ++r)
    for (std::int64_t off = 0; off < send_bytes[r]; off += kPiece) {
      requests.emplace_back();
      MPI_Isend(parts[r] + off, int(std::min(kPiece, send_bytes[r] - off)), MPI_BYTE, r, 7, comm_, &requests.back());
    }
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

namespace {
template <class T>
T all_reduce(T v, MPI_Datatype type, MPI_Op op, MPI_Comm comm) {
  T s{};
  MPI_Allreduce(&v, &s, 1, type, op, comm);
  return s;
}
}  // namespace

std::int64_t Comm::sum(std::int64_t v) const { return all_reduce(v, MPI_INT64_T, MPI_SUM, comm_); }
double Comm::sum(double v) const { return all_reduce(v, MPI_DOUBLE, MPI_SUM, comm_); }
std::int64_t Comm::max(std::int64_t v) const { return all_reduce(v, MPI_INT64_T, MPI_MAX, comm_); }
double Comm::min(double v) const { return all_reduce(v, MPI_DOUBLE, MPI_MIN, comm_); }
double Comm::max(double v) const { return all_reduce(v, MPI_DOUBLE, MPI_MAX, comm_); }
std::int64_t Comm::exclusive_scan(std::int64_t v) const {
  std::int64_t s = 0;
  MPI_Exscan(&v, &s, 1, MPI_INT64_T, MPI_SUM, comm_);
  return rank_ == 0 ? 0 : s;
}

void Comm::step(const std::function<void()>& body) const {
  int failed = 0;
  try {
    body();
  } catch (const ReportedFailure&) {
    failed = 1;
  } catch (const std::exception& e) {
    failed = 1;
    fmt::print(stderr, "error: rank {} of {}: {}\n", rank_, size_, e.what());
    std::fflush(stderr);
  }
  int any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, comm_);
  if (any) throw ReportedFailure{};
}

}  // namespace metrica::distributed
