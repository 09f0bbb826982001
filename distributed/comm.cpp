#include <metrica/distributed/comm.hpp>

#include <fmt/core.h>

#include <cstdio>
#include <limits>

namespace metrica::distributed {

Comm::Comm(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

// MPI_Alltoallw over a record datatype: each rank's block, sent and
// received, is one record run at its absolute address (MPI_BOTTOM), so no
// side is packed into a buffer of its own and no byte displacement has to
// fit an int; only a run's record count does.
void Comm::exchange_records(std::size_t bytes, const std::vector<const void*>& send_at,
                            const std::vector<std::int64_t>& send, const std::vector<void*>& recv_at,
                            const std::vector<std::int64_t>& recv) const {
  // Agreed before the collective, so that no rank waits in it alone.
  int too_many = 0;
  for (int r = 0; r < size_; ++r)
    too_many |= send[r] > std::numeric_limits<int>::max() || recv[r] > std::numeric_limits<int>::max();
  int any = 0;
  MPI_Allreduce(&too_many, &any, 1, MPI_INT, MPI_MAX, comm_);
  if (any)
    throw InputError(fmt::format("distributed: more than {} records of {} bytes between two ranks (MPI's int counts)",
                                 std::numeric_limits<int>::max(), bytes));
  MPI_Datatype record;
  MPI_Type_contiguous(int(bytes), MPI_BYTE, &record);
  MPI_Type_commit(&record);
  std::vector<MPI_Datatype> made;
  // One record run at `at` as a datatype placed from MPI_BOTTOM.
  const auto run = [&](const void* at, std::int64_t records, int& count, MPI_Datatype& type) {
    type = record, count = 0;
    if (records == 0) return;
    MPI_Aint address;
    MPI_Get_address(at, &address);
    const int length = int(records);
    MPI_Type_create_hindexed(1, &length, &address, record, &type);
    MPI_Type_commit(&type);
    made.push_back(type);
    count = 1;
  };
  std::vector<int> send_count(size_), recv_count(size_), displacement(size_, 0);
  std::vector<MPI_Datatype> send_type(size_), recv_type(size_);
  for (int r = 0; r < size_; ++r) {
    run(send_at[r], send[r], send_count[r], send_type[r]);
    run(recv_at[r], recv[r], recv_count[r], recv_type[r]);
  }
  MPI_Alltoallw(MPI_BOTTOM, send_count.data(), displacement.data(), send_type.data(), MPI_BOTTOM, recv_count.data(),
                displacement.data(), recv_type.data(), comm_);
  for (MPI_Datatype& t : made) MPI_Type_free(&t);
  MPI_Type_free(&record);
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
std::vector<std::int64_t> Comm::io_parts(const std::vector<std::size_t>& slice_bytes) const {
  std::vector<std::int64_t> parts(std::size_t(max(std::int64_t(slice_bytes.size()))), 0);
  for (std::size_t i = 0; i < slice_bytes.size(); ++i)
    parts[i] = std::int64_t((slice_bytes[i] + kIoPart - 1) / kIoPart);
  MPI_Allreduce(MPI_IN_PLACE, parts.data(), int(parts.size()), MPI_INT64_T, MPI_MAX, comm_);
  return parts;
}
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
