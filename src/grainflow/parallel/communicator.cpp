#include "grainflow/parallel/communicator.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#ifdef GRAINFLOW_HAVE_MPI
#include <mpi.h>
#endif

namespace grainflow::parallel {
namespace {

Communicator& the_world() {
  static Communicator world;
  return world;
}

#ifdef GRAINFLOW_HAVE_MPI
bool launched_by_mpirun() {
  if (std::getenv("GRAINFLOW_SERIAL") != nullptr) return false;  // a sweep's child: one rank of its own
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

void finalize() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

bool active() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  return initialized != 0;
}
#endif

}  // namespace

bool mpi_built() {
#ifdef GRAINFLOW_HAVE_MPI
  return true;
#else
  return false;
#endif
}

Communicator& Communicator::world() { return the_world(); }

void Communicator::start([[maybe_unused]] int& argc, [[maybe_unused]] char**& argv) {
#ifdef GRAINFLOW_HAVE_MPI
  if (!launched_by_mpirun() || active()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);  // OpenMP threads stay inside a rank
  std::atexit(finalize);
  Communicator& w = the_world();
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size_);
#endif
}

#ifdef GRAINFLOW_HAVE_MPI
namespace {
// One value combined over all ranks (itself on one rank).
template <class T>
T all_reduce(int ranks, T local, MPI_Datatype type, MPI_Op op) {
  if (ranks == 1) return local;
  T out{};
  MPI_Allreduce(&local, &out, 1, type, op, MPI_COMM_WORLD);
  return out;
}
}  // namespace

bool Communicator::any(bool local) const { return all_reduce(size_, local ? 1 : 0, MPI_INT, MPI_LOR) != 0; }
double Communicator::max(double local) const { return all_reduce(size_, local, MPI_DOUBLE, MPI_MAX); }
long long Communicator::sum(long long local) const { return all_reduce(size_, local, MPI_LONG_LONG, MPI_SUM); }
double Communicator::sum(double local) const { return all_reduce(size_, local, MPI_DOUBLE, MPI_SUM); }
void Communicator::sum_in_place(double* values, std::size_t count) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}
#else
bool Communicator::any(bool local) const { return local; }
double Communicator::max(double local) const { return local; }
long long Communicator::sum(long long local) const { return local; }
double Communicator::sum(double local) const { return local; }
void Communicator::sum_in_place(double*, std::size_t) const {}
#endif

std::vector<std::vector<std::uint8_t>> Communicator::exchange(
    const std::vector<std::vector<std::uint8_t>>& outgoing) const {
  if (static_cast<int>(outgoing.size()) != size_) throw std::logic_error("Communicator::exchange: one buffer per rank");
  std::vector<std::vector<std::uint8_t>> incoming(size_);
#ifdef GRAINFLOW_HAVE_MPI
  if (size_ > 1) {
    std::vector<int> send_counts(size_), receive_counts(size_), send_offsets(size_), receive_offsets(size_);
    std::vector<std::uint8_t> send;
    for (int r = 0; r < size_; ++r) {
      send_counts[r] = static_cast<int>(outgoing[r].size());
      send_offsets[r] = static_cast<int>(send.size());
      send.insert(send.end(), outgoing[r].begin(), outgoing[r].end());
    }
    MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    int total = 0;
    for (int r = 0; r < size_; ++r) receive_offsets[r] = total, total += receive_counts[r];
    std::vector<std::uint8_t> receive(static_cast<std::size_t>(total));
    MPI_Alltoallv(send.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, receive.data(), receive_counts.data(),
                  receive_offsets.data(), MPI_BYTE, MPI_COMM_WORLD);
    for (int r = 0; r < size_; ++r)
      incoming[r].assign(receive.begin() + receive_offsets[r],
                         receive.begin() + receive_offsets[r] + receive_counts[r]);
    return incoming;
  }
#endif
  incoming[0] = outgoing[0];
  return incoming;
}

std::vector<std::vector<std::uint8_t>> Communicator::exchange_with(
    const std::vector<int>& partners, const std::vector<std::vector<std::uint8_t>>& outgoing,
    const std::vector<std::size_t>* expected) const {
  if (static_cast<int>(outgoing.size()) != size_)
    throw std::logic_error("Communicator::exchange_with: one buffer per rank");
  std::vector<std::vector<std::uint8_t>> incoming(size_);
#ifdef GRAINFLOW_HAVE_MPI
  if (size_ > 1) {
    const std::size_t n = partners.size();
    std::vector<unsigned long long> send_sizes(n), receive_sizes(n);
    std::vector<MPI_Request> requests(2 * n);
    for (std::size_t k = 0; k < n; ++k) send_sizes[k] = outgoing[partners[k]].size();
    if (expected != nullptr) {
      for (std::size_t k = 0; k < n; ++k) receive_sizes[k] = (*expected)[partners[k]];
    } else {
      // Sizes first, then the bytes; both sides post their receives before their sends.
      for (std::size_t k = 0; k < n; ++k)
        MPI_Irecv(&receive_sizes[k], 1, MPI_UNSIGNED_LONG_LONG, partners[k], kSizeTag, MPI_COMM_WORLD, &requests[k]);
      for (std::size_t k = 0; k < n; ++k)
        MPI_Isend(&send_sizes[k], 1, MPI_UNSIGNED_LONG_LONG, partners[k], kSizeTag, MPI_COMM_WORLD, &requests[n + k]);
      MPI_Waitall(static_cast<int>(2 * n), requests.data(), MPI_STATUSES_IGNORE);
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (receive_sizes[k] > static_cast<unsigned long long>(std::numeric_limits<int>::max()) ||
          send_sizes[k] > static_cast<unsigned long long>(std::numeric_limits<int>::max()))
        throw std::runtime_error("Communicator::exchange_with: a message above 2 GB (use more ranks)");
      incoming[partners[k]].resize(receive_sizes[k]);
      MPI_Irecv(incoming[partners[k]].data(), static_cast<int>(receive_sizes[k]), MPI_BYTE, partners[k], kDataTag,
                MPI_COMM_WORLD, &requests[k]);
    }
    for (std::size_t k = 0; k < n; ++k)
      MPI_Isend(outgoing[partners[k]].data(), static_cast<int>(send_sizes[k]), MPI_BYTE, partners[k], kDataTag,
                MPI_COMM_WORLD, &requests[n + k]);
    MPI_Waitall(static_cast<int>(2 * n), requests.data(), MPI_STATUSES_IGNORE);
    return incoming;
  }
#else
  (void)partners;
  (void)expected;
#endif
  incoming[0] = outgoing[0];
  return incoming;
}

std::vector<std::vector<std::uint8_t>> Communicator::gather(const std::vector<std::uint8_t>& mine) const {
#ifdef GRAINFLOW_HAVE_MPI
  if (size_ > 1) {
    // Rank by rank, in pieces of at most 1 GiB: a checkpoint of 10^7 particles gathers more than
    // MPI's int counts can name in one message.
    constexpr unsigned long long kPiece = 1ULL << 30;
    unsigned long long count = mine.size();
    std::vector<unsigned long long> counts(root() ? size_ : 0);
    MPI_Gather(&count, 1, MPI_UNSIGNED_LONG_LONG, counts.data(), 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    std::vector<std::vector<std::uint8_t>> out;
    if (root()) {
      out.resize(size_);
      out[0] = mine;
      for (int r = 1; r < size_; ++r) {
        out[r].resize(counts[r]);
        for (unsigned long long at = 0; at < counts[r]; at += kPiece)
          MPI_Recv(out[r].data() + at, static_cast<int>(std::min(kPiece, counts[r] - at)), MPI_BYTE, r, kGatherTag,
                   MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
    } else {
      for (unsigned long long at = 0; at < count; at += kPiece)
        MPI_Send(mine.data() + at, static_cast<int>(std::min(kPiece, count - at)), MPI_BYTE, 0, kGatherTag,
                 MPI_COMM_WORLD);
    }
    return out;
  }
#endif
  return {mine};
}

void Communicator::abort(int status) const {
#ifdef GRAINFLOW_HAVE_MPI
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, status);
#endif
  std::exit(status);
}

}  // namespace grainflow::parallel
