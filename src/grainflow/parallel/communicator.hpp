// The ranks of an MPI run, and the few collective operations grainflow needs, behind one small
// class: without MPI (a build without it, or a process not started by mpirun) it is one rank and
// every operation is the identity, so the engines and drivers carry no #ifdefs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace grainflow::parallel {

class Communicator {
 public:
  // The world of this process: MPI_COMM_WORLD once start() ran under mpirun, else one rank.
  static Communicator& world();
  // Initialises MPI when the process was started by mpirun (or another launcher that sets the
  // usual environment); a plain run never touches MPI. Finalised at exit.
  static void start(int& argc, char**& argv);

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  bool any(bool local) const;  // logical OR over the ranks
  double max(double local) const;
  long long sum(long long local) const;
  double sum(double local) const;
  void sum_in_place(double* values, std::size_t count) const;  // element by element, on every rank
  // Each rank sends outgoing[r] to rank r; returns what each rank sent to this one.
  std::vector<std::vector<std::uint8_t>> exchange(const std::vector<std::vector<std::uint8_t>>& outgoing) const;
  // The same with only `partners` (symmetric: each partner names this rank too): point-to-point
  // messages, so that the cost stays with the neighbours as the rank count grows. outgoing has one
  // buffer per rank (only the partners' are sent); so has the result (only the partners' filled).
  // With `expected` (bytes from each rank, known to both sides) the sizes are not sent first: one
  // round of messages instead of two (the ghosts' refresh every step).
  std::vector<std::vector<std::uint8_t>> exchange_with(const std::vector<int>& partners,
                                                       const std::vector<std::vector<std::uint8_t>>& outgoing,
                                                       const std::vector<std::size_t>* expected = nullptr) const;
  // Rank 0 receives every rank's bytes in rank order; the others receive nothing.
  std::vector<std::vector<std::uint8_t>> gather(const std::vector<std::uint8_t>& mine) const;
  // Stops every rank (a failure on one rank that the others cannot see).
  [[noreturn]] void abort(int status) const;

 private:
  static constexpr int kSizeTag = 71, kDataTag = 72;  // exchange_with's two messages per partner
  static constexpr int kGatherTag = 73;
  int rank_ = 0, size_ = 1;
};

// Whether this build has MPI (`mpirun -np N grainflow ...` runs N ranks).
bool mpi_built();

}  // namespace grainflow::parallel
